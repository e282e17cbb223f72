#include "sim/scene_generators.h"

#include <cmath>
#include <random>
#include <stdexcept>

#include "collision/tolerances.h"

namespace polysim::sim {
namespace {

using nlohmann::ordered_json;

// Uniform numbers from the raw 64-bit output of a seeded Mersenne twister: the same on
// every standard library (std::uniform_real_distribution is not).
class Random {
 public:
  explicit Random(unsigned long long seed) : engine_(seed) {}
  double uniform(double lo, double hi) { return lo + (hi - lo) * static_cast<double>(engine_() >> 11) * 0x1.0p-53; }
  // A unit quaternion [w, x, y, z]: a turn by an angle up to `largest` about a random axis.
  ordered_json tilt(double largest) {
    if (largest <= 0.0) return {1.0, 0.0, 0.0, 0.0};
    double x, y, z, n;
    do {
      x = uniform(-1, 1), y = uniform(-1, 1), z = uniform(-1, 1);
      n = std::sqrt(x * x + y * y + z * z);
    } while (n < 0.1 || n > 1.0);  // uniform directions: inside the unit ball, not near its centre
    const double half = 0.5 * uniform(0.0, largest), s = std::sin(half) / n;
    return {std::cos(half), x * s, y * s, z * s};
  }

 private:
  std::mt19937_64 engine_;
};

ordered_json box(const std::string& name, double sx, double sy, double sz, double x, double y, double z) {
  return {{"name", name}, {"shape", {{"type", "box"}, {"size", {sx, sy, sz}}}}, {"position", {x, y, z}}};
}

ordered_json staticBox(const std::string& name, double sx, double sy, double sz, double x, double y, double z) {
  ordered_json b = box(name, sx, sy, sz, x, y, z);
  b["static"] = true;
  return b;
}

ordered_json dynamicBox(const std::string& name, double sx, double sy, double sz, double x, double y, double z) {
  ordered_json b = box(name, sx, sy, sz, x, y, z);
  b["mass"] = 1.0;
  return b;
}

// A square ground slab `side` m wide whose top face is z = 0.
ordered_json ground(double side) { return staticBox("ground", side, side, 1.0, 0.0, 0.0, -0.5); }

// An open square cup: outer half-width `outer`, walls `wall` thick, a floor `floor`
// thick, `height` high, the origin at the centre of its bottom face; 16 vertices and 14
// convex faces, counter-clockwise seen from outside.
ordered_json cupShape(double outer, double height, double wall, double floor) {
  const double inner = outer - wall;
  ordered_json vertices = ordered_json::array();
  for (const auto& [h, z] : {std::pair{outer, 0.0}, std::pair{outer, height}, std::pair{inner, height}, std::pair{inner, floor}})
    for (const auto& [sx, sy] : {std::pair{-1, -1}, std::pair{1, -1}, std::pair{1, 1}, std::pair{-1, 1}})
      vertices.push_back({sx * h, sy * h, z});
  const int ob = 0, ot = 4, it = 8, ib = 12;  // first vertex of each square
  ordered_json faces = ordered_json::array();
  faces.push_back({ob + 0, ob + 3, ob + 2, ob + 1});  // bottom, facing -z
  faces.push_back({ib + 0, ib + 1, ib + 2, ib + 3});  // cavity floor, facing +z
  for (int k = 0; k < 4; ++k) {
    const int k1 = (k + 1) % 4;
    faces.push_back({ob + k, ob + k1, ot + k1, ot + k});  // outer wall
    faces.push_back({ot + k, ot + k1, it + k1, it + k});  // rim
    faces.push_back({it + k, it + k1, ib + k1, ib + k});  // inner wall, facing the cavity
  }
  return {{"type", "mesh"}, {"vertices", vertices}, {"faces", faces}};
}

void stack(int count, ordered_json& bodies) {
  bodies.push_back(ground(20.0));
  for (int k = 0; k < count; ++k) bodies.push_back(dynamicBox("box" + std::to_string(k), 1, 1, 1, 0, 0, 0.5 + k));
}

void pyramid(int base, ordered_json& bodies) {
  constexpr double kPitch = 1.05;  // m between neighbouring centres of a row
  bodies.push_back(ground(base * kPitch + 10.0));
  for (int row = 0; row < base; ++row) {
    const int n = base - row;
    for (int i = 0; i < n; ++i)
      bodies.push_back(dynamicBox("r" + std::to_string(row) + "b" + std::to_string(i), 1, 1, 1,
                                  (i - 0.5 * (n - 1)) * kPitch, 0, 0.5 + row));
  }
}

void pile(int count, double tilt, Random& random, ordered_json& bodies) {
  constexpr double kSpacing = 1.5, kPen = 16.0, kWall = 10.0;
  // A unit box turned by up to 0.3 rad reaches at most 0.69 m from its centre along an
  // axis, so boxes 1.5 m apart cannot touch; the grid is at most 10 wide to fit the pen.
  int side = 1;  // the smallest cube holding `count`, at most 10 wide
  while (side < 10 && side * side * side < count) ++side;
  bodies.push_back(ground(kPen + 4.0));
  const double h = 0.5 * kPen + 0.5;  // wall centres, 1 m thick walls just outside the pen
  bodies.push_back(staticBox("wall_x_neg", 1, kPen + 2, kWall, -h, 0, 0.5 * kWall));
  bodies.push_back(staticBox("wall_x_pos", 1, kPen + 2, kWall, h, 0, 0.5 * kWall));
  bodies.push_back(staticBox("wall_y_neg", kPen, 1, kWall, 0, -h, 0.5 * kWall));
  bodies.push_back(staticBox("wall_y_pos", kPen, 1, kWall, 0, h, 0.5 * kWall));
  for (int k = 0; k < count; ++k) {
    const int i = k % side, j = (k / side) % side, layer = k / (side * side);
    ordered_json b = dynamicBox("box" + std::to_string(k), 1, 1, 1, (i - 0.5 * (side - 1)) * kSpacing,
                                (j - 0.5 * (side - 1)) * kSpacing, 1.5 + layer * kSpacing);
    b["orientation"] = random.tilt(tilt);
    bodies.push_back(b);
  }
}

void dominoes(int count, Random& random, ordered_json& bodies) {
  // 2 m tall slabs about 1 m apart (0.9 to 1.1 m at random): each falling one reaches
  // the next, and none can touch another standing.
  bodies.push_back(ground(count * 1.1 + 10.0));
  double x = -0.5 * (count - 1);
  for (int k = 0; k < count; ++k, x += random.uniform(0.9, 1.1)) {
    ordered_json b = dynamicBox("domino" + std::to_string(k), 0.2, 1, 2, x, 0, 1.0);
    if (k == 0) b["angular_velocity"] = {0.0, 1.5, 0.0};  // tips over towards +x
    bodies.push_back(b);
  }
}

void cups(int count, double tilt, Random& random, ordered_json& bodies) {
  constexpr double kHeight = 0.6, kHalfWidth = 0.5;
  // 0.2 m between neighbours, plus room for both to be tilted: a turn about the bottom
  // centre by `tilt` moves a vertex up or down by at most its distance from there times
  // sin(tilt).
  const double reach = std::sqrt(2 * kHalfWidth * kHalfWidth + kHeight * kHeight);
  const double drop = 0.2 + 2 * reach * std::sin(tilt);
  bodies.push_back(ground(20.0));
  for (int k = 0; k < count; ++k) {
    ordered_json b = {{"name", "cup" + std::to_string(k)},
                      {"shape", cupShape(kHalfWidth, kHeight, 0.05, 0.05)},
                      {"position", {random.uniform(-0.05, 0.05), random.uniform(-0.05, 0.05), drop + k * (kHeight + drop)}},
                      {"mass", 1.0}};
    if (tilt > 0) b["orientation"] = random.tilt(tilt);
    bodies.push_back(b);
  }
}

struct Defaults {
  int count;
  double tilt, duration;
};

Defaults defaultsFor(const std::string& kind) {
  if (kind == "stack") return {10, 0.0, 60.0};
  if (kind == "pyramid") return {10, 0.0, 10.0};
  if (kind == "pile") return {125, 0.3, 20.0};
  if (kind == "dominoes") return {10, 0.0, 10.0};
  return {20, 0.0, 10.0};  // cups
}

}  // namespace

const std::vector<std::string>& sceneKinds() {
  static const std::vector<std::string> kinds = {"stack", "pyramid", "pile", "dominoes", "cups"};
  return kinds;
}

ordered_json makeScene(const MakeOptions& o) {
  bool known = false;
  for (const std::string& k : sceneKinds()) known = known || k == o.kind;
  if (!known) throw std::invalid_argument("make: unknown kind \"" + o.kind + "\" (stack, pyramid, pile, dominoes or cups)");
  const Defaults d = defaultsFor(o.kind);
  const int count = o.count.value_or(d.count);
  const double tilt = o.tilt.value_or(d.tilt);
  if (count < 1 || count > 10000) throw std::invalid_argument("make: --count must be from 1 to 10000");
  if (!(tilt >= 0.0 && tilt <= 0.3)) throw std::invalid_argument("make: --tilt must be from 0 to 0.3 rad");
  if (tilt > 0 && o.kind != "pile" && o.kind != "cups")
    throw std::invalid_argument("make: --tilt applies to pile and cups only (a tilted " + o.kind + " would start interpenetrating)");
  if (o.dt && !(*o.dt > 0.0 && std::isfinite(*o.dt))) throw std::invalid_argument("make: --dt must be positive");
  if (o.duration && !(*o.duration > 0.0 && std::isfinite(*o.duration)))
    throw std::invalid_argument("make: --duration must be positive");

  Random random(o.seed);
  ordered_json bodies = ordered_json::array();
  if (o.kind == "stack") stack(count, bodies);
  if (o.kind == "pyramid") pyramid(count, bodies);
  if (o.kind == "pile") pile(count, tilt, random, bodies);
  if (o.kind == "dominoes") dominoes(count, random, bodies);
  if (o.kind == "cups") cups(count, tilt, random, bodies);

  ordered_json scene;
  scene["name"] = o.kind + "_" + std::to_string(count) + (tilt > 0 ? "_seed" + std::to_string(o.seed) : "");
  scene["gravity"] = {0.0, 0.0, -9.81};
  scene["dt"] = o.dt.value_or(1.0 / 60.0);
  scene["duration"] = o.duration.value_or(d.duration);
  scene["contact"] = {{"tolerance", collision::kDefaultContactTolerance}, {"restitution", 0.0}, {"friction", 0.5}};
  scene["bodies"] = bodies;
  return scene;
}

}  // namespace polysim::sim
