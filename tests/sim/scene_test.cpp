// Scene loading: every class of bad input SPEC.md lists is rejected with one message that
// names the file, the body and the field; good scenes load with SPEC.md's defaults.

#include "sim/scene.h"

#include <gtest/gtest.h>

#include <unistd.h>

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>

namespace polysim::sim {
namespace {

namespace fs = std::filesystem;

class SceneFiles : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() / ("polysim_scene_test_" + std::to_string(::getpid()));
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }

  std::string write(const std::string& name, const std::string& text) {
    const fs::path p = dir_ / name;
    std::ofstream(p) << text;
    return p.string();
  }
  // The error message for a scene, or "" if it loads.
  std::string errorFor(const std::string& text) {
    const std::string path = write("scene.json", text);
    try {
      checkInitialState(loadScene(path));
    } catch (const SceneError& e) {
      const std::string what = e.what();
      EXPECT_EQ(what.rfind(path + ": ", 0), 0u) << "message must start with the file: " << what;
      return what;
    }
    return "";
  }

 public:
  // A scene of a ground and one body whose fields are `body`.
  static std::string withBody(const std::string& body) {
    return R"({"bodies": [{"name": "ground", "static": true, "shape": {"type": "box", "size": [20, 20, 1]},
               "position": [0, 0, -0.5]}, {"name": "box", )" + body + "}]}";
  }

 protected:
  fs::path dir_;
};

const char* kBox = R"("shape": {"type": "box", "size": [1, 1, 1]}, "position": [0, 0, 2])";

TEST_F(SceneFiles, LoadsWithSpecDefaults) {
  const Scene s = loadScene(write("ok.json", withBody(kBox)));
  EXPECT_EQ(s.name, "ok");
  EXPECT_DOUBLE_EQ(s.dt, 1.0 / 240.0);
  EXPECT_DOUBLE_EQ(s.duration, 1.0);
  EXPECT_DOUBLE_EQ(s.gravity.z(), -9.81);
  EXPECT_DOUBLE_EQ(s.contact.tolerance, 1e-4);
  EXPECT_DOUBLE_EQ(s.contact.friction, 0.5);
  EXPECT_DOUBLE_EQ(s.contact.restitution, 0.0);
  EXPECT_DOUBLE_EQ(s.contact.speculativeReach, 0.02);
  EXPECT_TRUE(s.contact.reuseContacts);
  EXPECT_TRUE(s.sleep.enabled);
  EXPECT_DOUBLE_EQ(s.sleep.speed, 0.01);
  EXPECT_DOUBLE_EQ(s.sleep.time, 0.5);
  ASSERT_EQ(s.bodies.size(), 2u);
  EXPECT_TRUE(s.bodies[0].isStatic);
  EXPECT_FALSE(s.bodies[1].mass.has_value());
  EXPECT_EQ(s.bodies[1].mesh.faces.size(), 6u);
}

struct Rejection {
  std::string name, scene, expected;
};
// ctest names each case by this (otherwise, under clang, by the struct's bytes).
void PrintTo(const Rejection& r, std::ostream* os) { *os << r.name; }

class SceneRejection : public SceneFiles, public ::testing::WithParamInterface<Rejection> {};

TEST_P(SceneRejection, NamesFileBodyAndField) {
  const std::string message = errorFor(GetParam().scene);
  EXPECT_NE(message.find(GetParam().expected), std::string::npos) << "got: " << message;
}

const std::string kCube = R"("vertices": [[-1,-1,-1],[1,-1,-1],[-1,1,-1],[1,1,-1],[-1,-1,1],[1,-1,1],[-1,1,1],[1,1,1]])";
const std::string kCubeFaces = R"([[0,2,3,1],[4,5,7,6],[0,1,5,4],[2,6,7,3],[0,4,6,2],[1,3,7,5]])";
std::string cubeWith(const std::string& faces, const std::string& vertices = kCube) {
  return R"("shape": {"type": "mesh", )" + vertices + R"(, "faces": )" + faces + R"(}, "position": [0, 0, 3])";
}

INSTANTIATE_TEST_SUITE_P(
    EveryClass, SceneRejection,
    ::testing::Values(
        Rejection{"malformed_json", R"({"bodies": [)", "malformed JSON"},
        Rejection{"not_an_object", "[1, 2]", "must be a JSON object"},
        Rejection{"missing_bodies", R"({"name": "x"})", "missing field \"bodies\""},
        Rejection{"empty_bodies", R"({"bodies": []})", "bodies: must be a non-empty array"},
        Rejection{"missing_shape", SceneFiles::withBody(R"("position": [0, 0, 2])"), "body \"box\": missing field \"shape\""},
        Rejection{"missing_name", R"({"bodies": [{"shape": {"type": "box", "size": [1,1,1]}}]})", "body 0: missing field \"name\""},
        Rejection{"mistyped_position", SceneFiles::withBody(R"("shape": {"type": "box", "size": [1,1,1]}, "position": "up")"),
                  "body \"box\": position must be an array of 3 numbers (got a string)"},
        Rejection{"mistyped_static", SceneFiles::withBody(std::string(kBox) + R"(, "static": 1)"), "static must be true or false"},
        Rejection{"unknown_shape", SceneFiles::withBody(R"("shape": {"type": "cone"})"), "body \"box\": shape: unknown shape type \"cone\""},
        Rejection{"unknown_field", SceneFiles::withBody(std::string(kBox) + R"(, "positon": [0,0,1])"), "unknown field \"positon\""},
        Rejection{"infinite_number", SceneFiles::withBody(std::string(kBox) + R"(, "velocity": [0, 0, 1e999])"),
                  "malformed JSON: number overflow parsing '1e999'"},
        Rejection{"zero_size", SceneFiles::withBody(R"("shape": {"type": "box", "size": [1, 0, 1]})"), "shape: size must be positive"},
        Rejection{"negative_mass", SceneFiles::withBody(std::string(kBox) + R"(, "mass": -2)"), "body \"box\": mass must be positive (got -2)"},
        Rejection{"zero_density", SceneFiles::withBody(std::string(kBox) + R"(, "density": 0)"), "density must be positive"},
        Rejection{"mass_and_density", SceneFiles::withBody(std::string(kBox) + R"(, "mass": 1, "density": 5)"), "mass or density, not both"},
        Rejection{"non_unit_quaternion", SceneFiles::withBody(std::string(kBox) + R"(, "orientation": [1, 0, 0, 0.1])"),
                  "orientation must be a unit quaternion"},
        Rejection{"short_quaternion", SceneFiles::withBody(std::string(kBox) + R"(, "orientation": [0.9, 0, 0, 0])"),
                  "orientation must be a unit quaternion [w, x, y, z] (its length is 0.9)"},
        Rejection{"negative_radius", SceneFiles::withBody(R"("shape": {"type": "icosphere", "radius": -1})"), "radius must be positive"},
        Rejection{"duplicate_names", R"({"bodies": [{"name": "a", "shape": {"type": "box", "size": [1,1,1]}},
                   {"name": "a", "shape": {"type": "box", "size": [1,1,1]}, "position": [5,0,0]}]})", "body \"a\": duplicate name"},
        Rejection{"index_out_of_range", SceneFiles::withBody(cubeWith(R"([[0,2,3,1],[4,5,7,6],[0,1,5,4],[2,6,7,3],[0,4,6,2],[1,3,7,9]])")),
                  "body \"box\": shape: face 5 uses vertex 9, out of range 0..7"},
        Rejection{"index_beyond_int", SceneFiles::withBody(cubeWith(R"([[4294967297,2,3,1],[4,5,7,6]])")),
                  "body \"box\": shape: face 0 uses vertex 4294967297, out of range 0..7"},  // it wrapped to 1
        Rejection{"subdivisions_beyond_int", SceneFiles::withBody(R"("shape": {"type": "icosphere", "radius": 1, "subdivisions": 4294967297})"),
                  "shape: subdivisions 4294967297 is out of range"},
        Rejection{"empty_name", R"({"bodies": [{"name": "", "shape": {"type": "box", "size": [1,1,1]}}]})", "body 0: name must not be empty"},
        Rejection{"face_with_two_vertices", SceneFiles::withBody(cubeWith(R"([[0,2],[4,5,7,6]])")), "face 0 has 2 vertices"},
        Rejection{"non_planar_face", SceneFiles::withBody(cubeWith(kCubeFaces,
                  R"("vertices": [[-1,-1,-1],[1,-1,-1],[-1,1,-1],[1,1,-1],[-1,-1,1],[1,-1,1],[-1,1,1],[1,1,1.2]])")),
                  "body \"box\": shape: face 1 is not planar (vertex"},
        Rejection{"non_convex_face", R"({"bodies": [{"name": "ramp", "static": true, "shape": {"type": "mesh",
                   "vertices": [[0,0,0],[2,1,0],[0,2,0],[0.5,1,0]], "faces": [[0,1,2,3]]}}]})",
                  "body \"ramp\": shape: face 0 is not convex"},
        Rejection{"zero_area_face", R"({"bodies": [{"name": "sliver", "static": true, "shape": {"type": "mesh",
                   "vertices": [[0,0,0],[1,0,0],[2,0,0]], "faces": [[0,1,2]]}}]})", "face 0 has zero area"},
        Rejection{"open_mesh_on_dynamic_body", SceneFiles::withBody(cubeWith(R"([[0,2,3,1],[4,5,7,6],[0,1,5,4],[2,6,7,3],[0,4,6,2]])")),
                  "body \"box\": shape: is not closed"},
        Rejection{"inside_out_mesh", SceneFiles::withBody(cubeWith(R"([[1,3,2,0],[6,7,5,4],[4,5,1,0],[3,7,6,2],[2,6,4,0],[5,7,3,1]])")),
                  "body \"box\": shape: is inside-out"},
        Rejection{"inside_out_static_mesh",
                  SceneFiles::withBody(cubeWith(R"([[1,3,2,0],[6,7,5,4],[4,5,1,0],[3,7,6,2],[2,6,4,0],[5,7,3,1]])") +
                                       R"(, "static": true)"),
                  "body \"box\": shape: is inside-out"},
        Rejection{"sweeps_zero", R"({"contact": {"solver_sweeps": 0}, "bodies": [{"name": "a", "shape": {"type": "box", "size": [1,1,1]}}]})",
                  "contact: solver_sweeps must be at least 1 (got 0)"},
        Rejection{"sweeps_fraction", R"({"contact": {"solver_sweeps": 2.5}, "bodies": [{"name": "a", "shape": {"type": "box", "size": [1,1,1]}}]})",
                  "contact: solver_sweeps must be an integer"},
        Rejection{"reach_negative", R"({"contact": {"speculative_reach": -0.01}, "bodies": [{"name": "a", "shape": {"type": "box", "size": [1,1,1]}}]})",
                  "contact: speculative_reach must not be negative (0 turns speculative contacts off)"},
        Rejection{"reach_inside_band", R"({"contact": {"tolerance": 0.001, "speculative_reach": 0.0005}, "bodies": [{"name": "a", "shape": {"type": "box", "size": [1,1,1]}}]})",
                  "contact: speculative_reach must be 0 or at least the tolerance (0.001 m)"},
        Rejection{"reuse_mistyped", R"({"contact": {"reuse_contacts": 1}, "bodies": [{"name": "a", "shape": {"type": "box", "size": [1,1,1]}}]})",
                  "contact: reuse_contacts must be true or false (got a number)"},
        Rejection{"sleep_not_an_object", R"({"sleep": true, "bodies": [{"name": "a", "shape": {"type": "box", "size": [1,1,1]}}]})",
                  "sleep: must be an object"},
        Rejection{"sleep_negative_speed", R"({"sleep": {"speed": -1}, "bodies": [{"name": "a", "shape": {"type": "box", "size": [1,1,1]}}]})",
                  "sleep: speed must be positive (got -1)"},
        Rejection{"sleep_mistyped_enabled", R"({"sleep": {"enabled": "no"}, "bodies": [{"name": "a", "shape": {"type": "box", "size": [1,1,1]}}]})",
                  "sleep: enabled must be true or false (got a string)"},
        Rejection{"sleep_unknown_field", R"({"sleep": {"treshold": 1}, "bodies": [{"name": "a", "shape": {"type": "box", "size": [1,1,1]}}]})",
                  "sleep: unknown field \"treshold\""},
        Rejection{"empty_mesh", SceneFiles::withBody(R"("shape": {"type": "mesh", "vertices": [], "faces": []})"),
                  "body \"box\": shape: vertices is empty (a mesh needs at least 3)"},
        Rejection{"number_beyond_a_double",
                  R"({"bodies": [{"name": "a", "shape": {"type": "box", "size": [1,1,1]}, "velocity": [0, 1e999, 0]}]})",
                  "malformed JSON: number overflow parsing '1e999' at bodies[0].velocity[1]"},
        Rejection{"number_beyond_a_double_on_top", R"({"dt": -1e999, "bodies": []})",
                  "malformed JSON: number overflow parsing '-1e999' at dt"},
        Rejection{"syntax_error", "{\"bodies\": [{\"name\": \"a\",\n ,}]}", "malformed JSON: parse error at line 2, column 2"},
        Rejection{"missing_obj_file", SceneFiles::withBody(R"("shape": {"type": "obj", "file": "nowhere.obj"})"),
                  "body \"box\": shape: file \"nowhere.obj\": no such file"},
        Rejection{"inside_another_at_start", SceneFiles::withBody(R"("shape": {"type": "box", "size": [0.2, 0.2, 0.2]}, "position": [3, 2, -0.5])"),
                  "bodies \"box\" and \"ground\": interpenetrate at the start"},  // wholly inside: no polygons meet
        Rejection{"interpenetrating_at_start", SceneFiles::withBody(R"("shape": {"type": "box", "size": [1,1,1]}, "position": [0, 0, 0.3])"),
                  "bodies \"box\" and \"ground\": interpenetrate at the start"}),
    [](const ::testing::TestParamInfo<Rejection>& info) { return info.param.name; });

TEST_F(SceneFiles, CollectsEveryProblemIntoOneMessage) {
  const std::string message =
      errorFor(R"({"dt": -1, "bodies": [{"name": "a", "shape": {"type": "box", "size": [1,-1,1]}, "mass": 0}]})");
  EXPECT_NE(message.find("dt must be positive"), std::string::npos);
  EXPECT_NE(message.find("size must be positive"), std::string::npos);
  EXPECT_NE(message.find("mass must be positive"), std::string::npos);
}

TEST_F(SceneFiles, ReadsObjMeshesRelativeToTheScene) {
  write("tet.obj", "# a tetrahedron\nv 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nf 1 3 2\nf 1 2 4\nf 1 4 3\nf 2/1 3/2 4/3\n");
  const Scene s = loadScene(write("obj.json", withBody(R"("shape": {"type": "obj", "file": "tet.obj"}, "position": [0,0,2])")));
  EXPECT_EQ(s.bodies[1].mesh.vertices.size(), 4u);
  EXPECT_EQ(s.bodies[1].mesh.faces.size(), 4u);
}

TEST_F(SceneFiles, CommandFailsWithOneMessageAndNoOutput) {
  const std::string path = write("bad.json", withBody(R"("shape": {"type": "box", "size": [1, 0, 1]})"));
  const std::string out = (dir_ / "out.txt").string(), err = (dir_ / "err.txt").string();
  const int status = std::system((std::string(POLYSIM_BINARY) + " contacts " + path + " >" + out + " 2>" + err).c_str());
  EXPECT_NE(status, 0);
  EXPECT_EQ(fs::file_size(out), 0u);
  std::ifstream errText(err);
  std::string first;
  std::getline(errText, first);
  EXPECT_NE(first.find(path + ": body \"box\": shape: size must be positive"), std::string::npos) << first;
}

}  // namespace
}  // namespace polysim::sim
