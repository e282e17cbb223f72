#include "sim/scene.h"

#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>
#include <memory>
#include <nlohmann/json.hpp>
#include <set>

#include "collision/intersection.h"
#include "collision/shapes.h"
#include "dynamics/mass_properties.h"
#include "sim/json_text.h"
#include "sim/obj_reader.h"
#include "sim/scene_fields.h"

namespace polysim::sim {
namespace {

using nlohmann::json;

// Largest icosphere subdivision accepted: 20 * 4^7 = 327680 triangles.
constexpr int kMaxSubdivisions = 7;
// How far (SPEC.md) a given orientation may be from unit length.
constexpr double kUnitQuaternionTolerance = 1e-6;

using scene_fields::Fields;
using scene_fields::Problems;

collision::MeshData meshFromJson(Fields& shape) {
  collision::MeshData mesh;
  const json& vertices = shape.raw("vertices");
  const json& faces = shape.raw("faces");
  if (!vertices.is_array()) return shape.problem("vertices must be an array of [x, y, z]"), mesh;
  if (!faces.is_array()) return shape.problem("faces must be an array of vertex index lists"), mesh;
  if (vertices.empty()) return shape.problem("vertices is empty (a mesh needs at least 3)"), mesh;
  for (size_t i = 0; i < vertices.size(); ++i) {
    const json& v = vertices[i];
    if (!v.is_array() || v.size() != 3 || !v[0].is_number() || !v[1].is_number() || !v[2].is_number())
      return shape.problem("vertex " + std::to_string(i) + " must be [x, y, z]"), collision::MeshData{};
    mesh.vertices.emplace_back(v[0].get<double>(), v[1].get<double>(), v[2].get<double>());
  }
  for (size_t f = 0; f < faces.size(); ++f) {
    const json& face = faces[f];
    std::vector<int> ids;
    bool ok = face.is_array();
    for (size_t k = 0; ok && k < face.size(); ++k) {
      ok = face[k].is_number_integer();
      if (!ok) break;
      // Read wide, so that 2^32 + 1 cannot wrap to 1; validateMesh checks the range of the rest.
      const long long id = face[k].get<long long>();
      if (id < 0 || id > std::numeric_limits<int>::max())
        return shape.problem("face " + std::to_string(f) + " uses vertex " + std::to_string(id) + ", out of range 0.." +
                             std::to_string(static_cast<long long>(vertices.size()) - 1)),
               collision::MeshData{};
      ids.push_back(static_cast<int>(id));
    }
    if (!ok) return shape.problem("face " + std::to_string(f) + " must be a list of vertex indices"), collision::MeshData{};
    mesh.faces.push_back(std::move(ids));
  }
  return mesh;
}

// Reads body.shape into `body`; returns false when it could not be read at all.
bool readShape(const json& shapeJson, BodySpec& body, const std::filesystem::path& sceneDir, Problems& problems,
               const std::string& where) {
  if (!shapeJson.is_object()) return problems.add(where, "shape must be an object"), false;
  Fields shape(shapeJson, where + ": shape", problems);
  const std::optional<std::string> type = shape.string("type", true);
  if (!type) return false;
  body.shapeType = *type;
  if (*type == "box") {
    shape.allowOnly({"type", "size"});
    const auto size = shape.vector<3>("size", true);
    if (!size) return false;
    if ((size->array() <= 0).any()) return shape.problem("size must be positive in every axis"), false;
    body.boxSize = *size;
    body.mesh = collision::makeBox(*size);
  } else if (*type == "mesh") {
    shape.allowOnly({"type", "vertices", "faces"});
    if (!shape.has("vertices") || !shape.has("faces"))
      return shape.problem("missing field \"" + std::string(shape.has("vertices") ? "faces" : "vertices") + "\""), false;
    body.mesh = meshFromJson(shape);
    if (body.mesh.vertices.empty()) return false;
  } else if (*type == "obj") {
    shape.allowOnly({"type", "file"});
    const auto file = shape.string("file", true);
    if (!file) return false;
    try {
      body.mesh = readObjFile((sceneDir / *file).string());
    } catch (const std::exception& e) {
      return shape.problem("file \"" + *file + "\": " + e.what()), false;
    }
  } else if (*type == "icosphere") {
    shape.allowOnly({"type", "radius", "subdivisions"});
    const auto radius = shape.positive("radius", true);
    const auto n = shape.has("subdivisions") ? shape.integer("subdivisions") : std::optional<int>(0);
    if (n && (*n < 0 || *n > kMaxSubdivisions))
      return shape.problem("subdivisions must be 0.." + std::to_string(kMaxSubdivisions)), false;
    if (!radius || !n) return false;
    body.mesh = collision::makeIcosphere(*radius, *n);
  } else {
    return shape.problem("unknown shape type \"" + *type + "\" (box, mesh, obj or icosphere)"), false;
  }
  const std::vector<std::string> meshProblems = collision::validateMesh(body.mesh, !body.isStatic);
  for (const std::string& p : meshProblems) shape.problem(p);
  return meshProblems.empty();
}

BodySpec readBody(const json& bodyJson, size_t index, const std::filesystem::path& sceneDir,
                  Problems& problems) {
  BodySpec body;
  std::string where = "body " + std::to_string(index);
  if (!bodyJson.is_object()) return problems.add(where, "must be an object"), body;
  Fields f(bodyJson, where, problems);
  if (const auto name = f.string("name", true)) {
    body.name = *name;
    if (name->empty()) problems.add(where, "name must not be empty");
    else where = "body \"" + *name + "\"";
  }
  Fields fields(bodyJson, where, problems);
  fields.allowOnly({"name", "shape", "static", "position", "orientation", "velocity", "angular_velocity", "mass",
                    "density", "restitution", "friction"});
  body.isStatic = fields.boolean("static").value_or(false);
  if (auto p = fields.vector<3>("position")) body.position = *p;
  if (auto v = fields.vector<3>("velocity")) body.velocity = *v;
  if (auto w = fields.vector<3>("angular_velocity")) body.angularVelocity = *w;
  if (auto q = fields.vector<4>("orientation")) {
    if (std::abs(q->norm() - 1.0) > kUnitQuaternionTolerance)
      fields.problem("orientation must be a unit quaternion [w, x, y, z] (its length is " + Fields::num(q->norm()) + ")");
    body.orientation = Eigen::Quaterniond((*q)[0], (*q)[1], (*q)[2], (*q)[3]).normalized();
  }
  if (fields.has("mass") && fields.has("density")) fields.problem("give mass or density, not both");
  body.mass = fields.positive("mass");
  body.density = fields.positive("density");
  body.restitution = fields.number("restitution");
  body.friction = fields.number("friction");
  if (body.restitution && (*body.restitution < 0 || *body.restitution > 1)) fields.problem("restitution must be in [0, 1]");
  if (body.friction && *body.friction < 0) fields.problem("friction must not be negative");

  if (!fields.has("shape")) {
    fields.problem("missing field \"shape\"");
  } else if (readShape(bodyJson.at("shape"), body, sceneDir, problems, where) && !body.isStatic) {
    const auto props = dynamics::computeMassProperties(body.mesh.vertices, body.mesh.faces, 1.0);
    if (props.volume <= 0) fields.problem("shape: the mesh encloses no volume");  // inside-out ones are refused above
  }
  return body;
}

// The optional settings objects "contact" and "sleep".
void readSettings(const json& root, Scene& scene, Problems& problems) {
  auto object = [&](const char* key) -> std::optional<Fields> {
    if (!root.contains(key)) return std::nullopt;
    if (!root[key].is_object()) return problems.add(key, "must be an object"), std::nullopt;
    return Fields(root[key], key, problems);
  };
  if (std::optional<Fields> contact = object("contact")) {
    contact->allowOnly({"tolerance", "restitution", "friction", "solver_sweeps", "speculative_reach", "reuse_contacts"});
    if (auto t = contact->positive("tolerance")) scene.contact.tolerance = *t;
    if (auto e = contact->number("restitution")) {
      if (*e < 0 || *e > 1) contact->problem("restitution must be in [0, 1]");
      scene.contact.restitution = *e;
    }
    if (auto mu = contact->number("friction")) {
      if (*mu < 0) contact->problem("friction must not be negative");
      scene.contact.friction = *mu;
    }
    if (auto n = contact->integer("solver_sweeps")) {
      if (*n < 1) contact->problem("solver_sweeps must be at least 1 (got " + std::to_string(*n) + ")");
      else scene.contact.solverSweeps = *n;
    }
    if (auto reach = contact->number("speculative_reach")) {
      if (*reach < 0) contact->problem("speculative_reach must not be negative (0 turns speculative contacts off)");
      else if (*reach > 0 && *reach < scene.contact.tolerance)
        contact->problem("speculative_reach must be 0 or at least the tolerance (" + Fields::num(scene.contact.tolerance) + " m)");
      else scene.contact.speculativeReach = *reach;
    }
    if (auto reuse = contact->boolean("reuse_contacts")) scene.contact.reuseContacts = *reuse;
  }
  if (std::optional<Fields> sleep = object("sleep")) {
    sleep->allowOnly({"enabled", "speed", "time"});
    if (auto on = sleep->boolean("enabled")) scene.sleep.enabled = *on;
    if (auto v = sleep->positive("speed")) scene.sleep.speed = *v;
    if (auto t = sleep->positive("time")) scene.sleep.time = *t;
  }
}

}  // namespace

Eigen::Isometry3d BodySpec::pose() const {
  Eigen::Isometry3d X = Eigen::Isometry3d::Identity();
  X.linear() = orientation.toRotationMatrix();
  X.translation() = position;
  return X;
}

Eigen::Vector3d Scene::up() const {
  return gravity.isZero() ? Eigen::Vector3d::UnitZ() : Eigen::Vector3d(-gravity.normalized());
}

dynamics::MassProperties BodySpec::massProperties() const {
  const auto props = dynamics::computeMassProperties(mesh.vertices, mesh.faces, density.value_or(1000.0));
  return mass ? dynamics::withMass(props, *mass) : props;
}

double BodySpec::reachFrom(const Eigen::Vector3d& point) const {
  double reach = 0.0;
  for (const Eigen::Vector3d& v : mesh.vertices) reach = std::max(reach, (v - point).norm());
  return reach;
}

Scene loadScene(const std::string& path) {
  Problems problems(path);
  if (std::filesystem::exists(path) && !std::filesystem::is_regular_file(path)) {
    problems.add("", "not a file (a scene is a JSON file)");
    problems.raise();
  }
  std::ifstream in(path);
  if (!in) {
    problems.add("", "cannot read the file");
    problems.raise();
  }
  return readScene(in, path);
}

Scene readScene(std::istream& in, const std::string& path) {
  Problems problems(path);
  json root;
  try {
    root = parseJsonText(in);
  } catch (const std::runtime_error& e) {
    problems.add("", std::string("malformed JSON: ") + e.what());
    problems.raise();
  }
  if (!root.is_object()) {
    problems.add("", "the scene must be a JSON object");
    problems.raise();
  }

  Scene scene;
  scene.file = path;
  Fields top(root, "", problems);
  top.allowOnly({"name", "gravity", "dt", "duration", "contact", "sleep", "bodies"});
  scene.name = top.string("name").value_or(std::filesystem::path(path).stem().string());
  if (auto g = top.vector<3>("gravity")) scene.gravity = *g;
  if (auto dt = top.positive("dt")) scene.dt = *dt;
  if (auto d = top.positive("duration")) scene.duration = *d;
  readSettings(root, scene, problems);
  if (!top.has("bodies")) {
    problems.add("", "missing field \"bodies\"");
  } else if (!root["bodies"].is_array() || root["bodies"].empty()) {
    problems.add("bodies", "must be a non-empty array");
  } else {
    const std::filesystem::path dir = std::filesystem::path(path).parent_path();
    std::set<std::string> names;
    for (size_t i = 0; i < root["bodies"].size(); ++i) {
      BodySpec body = readBody(root["bodies"][i], i, dir, problems);
      if (!body.name.empty() && !names.insert(body.name).second)
        problems.add("body \"" + body.name + "\"", "duplicate name (body names must be unique)");
      scene.bodies.push_back(std::move(body));
    }
  }
  if (!problems.empty()) problems.raise();
  return scene;
}

collision::ObjectDatabase buildObjectDatabase(const Scene& scene) {
  collision::ObjectDatabase db;
  db.tolerance = scene.contact.tolerance;
  for (const BodySpec& b : scene.bodies)
    db.add(b.name, std::make_shared<collision::PolygonMesh>(b.mesh), b.pose(), b.isStatic);
  return db;
}

void checkInitialState(const Scene& scene) {
  const collision::ObjectDatabase db = buildObjectDatabase(scene);
  // A dynamic body no thicker than twice the band has no inside the band can tell from
  // its outside: resting on the ground it would be judged in contact from both faces.
  Problems thin(scene.file);
  for (size_t i = 0; i < scene.bodies.size(); ++i)
    if (!scene.bodies[i].isStatic && db.objects[i].thickness <= 2 * scene.contact.tolerance)
      thin.add("body \"" + scene.bodies[i].name + "\": shape",
               "is " + Fields::num(db.objects[i].thickness) + " m thick at its thinnest, not more than twice the "
               "contact tolerance (" + Fields::num(scene.contact.tolerance) + " m)");
  if (!thin.empty()) thin.raise();
  collision::IntersectionOptions options;
  options.contacts = false;
  const collision::IntersectionResult r = collision::test4Intersection(db, options);
  if (r.status != collision::Status::Interpenetrating) return;
  Problems problems(scene.file);
  for (const collision::PairResult& p : r.pairs)
    if (p.status == collision::Status::Interpenetrating)
      problems.add("bodies \"" + scene.bodies[p.a].name + "\" and \"" + scene.bodies[p.b].name + "\"",
                   "interpenetrate at the start (by at least " + Fields::num(p.depth) + " m)");
  problems.raise();
}

}  // namespace polysim::sim
