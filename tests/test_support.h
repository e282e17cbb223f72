#pragma once
// Helpers shared by the tests: Eigen comparisons that print both values, the world
// frames every geometric case is re-run under, and small meshes built by hand.

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>
#include <random>
#include <string>
#include <vector>

#include "collision/polygon_mesh.h"
#include "tests/poses.h"

namespace polysim::test {

/// A path in the test temp folder of its own for the running test: ctest runs tests in
/// parallel processes, and two tests writing one file read each other's halves.
inline std::string tempPath(const std::string& file) {
  const ::testing::TestInfo* info = ::testing::UnitTest::GetInstance()->current_test_info();
  std::string test = info ? std::string(info->test_suite_name()) + "." + info->name() : "no_test";
  for (char& c : test)
    if (c == '/') c = '_';
  return ::testing::TempDir() + test + "_" + file;
}

/// `draw()` (any callable returning a double) three times, as x, y, z in that order: for
/// tests that draw from their own generator and distribution. V3(d(rng), d(rng), d(rng))
/// takes its draws in the order the compiler evaluates a call's arguments (SeededDraws,
/// below); this takes them left to right, clang's order, so the scenes the clang pass
/// always checked are the ones both passes check.
template <class Draw>
Eigen::Vector3d drawnVector(Draw&& draw) {
  Eigen::Vector3d v;
  for (int k = 0; k < 3; ++k) v[k] = draw();
  return v;
}
/// The same for a quaternion's w, x, y, z (not normalized).
template <class Draw>
Eigen::Quaterniond drawnQuaternion(Draw&& draw) {
  const double w = draw();
  const Eigen::Vector3d xyz = drawnVector(draw);
  return Eigen::Quaterniond(w, xyz.x(), xyz.y(), xyz.z());
}

/// Seeded uniform draws for random scenes, each vector's components drawn x, y, z in turn.
/// Draws written as the arguments of one call, V3(draw(), draw(), draw()), are taken in
/// the order the compiler evaluates arguments, which g++ and clang do not share: one seed
/// then gives each compiler scenes of its own (a toss that struck a wall under g++ fell
/// short of it under clang). Take each draw in its own statement, or through vector().
class SeededDraws {
 public:
  explicit SeededDraws(unsigned long long seed) : random_(seed) {}
  double between(double lo, double hi) { return lo + (hi - lo) * unit_(random_); }
  /// Each component between lo's and hi's.
  Eigen::Vector3d vector(const Eigen::Vector3d& lo, const Eigen::Vector3d& hi) {
    Eigen::Vector3d v;
    for (int k = 0; k < 3; ++k) v[k] = between(lo[k], hi[k]);
    return v;
  }
  Eigen::Vector3d vector(double lo, double hi) { return vector(Eigen::Vector3d::Constant(lo), Eigen::Vector3d::Constant(hi)); }
  /// A unit vector (not uniform over the sphere: enough for an axis).
  Eigen::Vector3d direction() { return vector(-1.0, 1.0).normalized(); }

 private:
  std::mt19937_64 random_;
  std::uniform_real_distribution<double> unit_{0.0, 1.0};
};

/// |a - b| <= tol, printing both vectors on failure (FCL's eigen_matrix_compare habit).
inline ::testing::AssertionResult near(const Eigen::Vector3d& a, const Eigen::Vector3d& b, double tol) {
  if ((a - b).norm() <= tol) return ::testing::AssertionSuccess();
  return ::testing::AssertionFailure() << "[" << a.transpose() << "] vs [" << b.transpose() << "], distance "
                                       << (a - b).norm() << " > " << tol;
}

struct NamedFrame {
  std::string name;
  Eigen::Isometry3d X;
};

/// Identity, translated, rotated and near-identity world frames.
inline std::vector<NamedFrame> worldFrames() {
  Eigen::Isometry3d translated = Eigen::Isometry3d::Identity();
  translated.translation() << 3.5, -2.25, 7.0;
  Eigen::Isometry3d rotated = Eigen::Isometry3d::Identity();
  rotated.linear() = Eigen::AngleAxisd(0.9, Eigen::Vector3d(1, 2, 3).normalized()).toRotationMatrix();
  rotated.translation() << -1.0, 0.5, 2.0;
  Eigen::Isometry3d near = Eigen::Isometry3d::Identity();
  near.linear() = Eigen::AngleAxisd(1e-7, Eigen::Vector3d(0, 1, 1).normalized()).toRotationMatrix();
  near.translation() << 1e-7, 0, -1e-7;
  return {{"identity", Eigen::Isometry3d::Identity()}, {"translated", translated}, {"rotated", rotated}, {"near_identity", near}};
}

/// A prism made by extruding a profile in the (x, z) plane along y from 0 to `depth`.
/// `parts` are convex pieces of the profile, counter-clockwise, sharing vertices exactly
/// (no T-junctions); `outline` is the profile's boundary, counter-clockwise.
inline collision::MeshData extrudeProfile(const std::vector<std::vector<Eigen::Vector2d>>& parts,
                                          const std::vector<Eigen::Vector2d>& outline, double depth) {
  collision::MeshData m;
  auto id = [&](const Eigen::Vector2d& p, double y) {
    const Eigen::Vector3d v(p.x(), y, p.y());
    for (size_t i = 0; i < m.vertices.size(); ++i)
      if ((m.vertices[i] - v).norm() < 1e-12) return static_cast<int>(i);
    m.vertices.push_back(v);
    return static_cast<int>(m.vertices.size()) - 1;
  };
  for (const auto& part : parts) {
    std::vector<int> front, back;
    for (const auto& p : part) front.push_back(id(p, 0.0));
    for (auto it = part.rbegin(); it != part.rend(); ++it) back.push_back(id(*it, depth));
    m.faces.push_back(front);
    m.faces.push_back(back);
  }
  for (size_t i = 0; i < outline.size(); ++i) {
    const auto& p = outline[i];
    const auto& q = outline[(i + 1) % outline.size()];
    m.faces.push_back({id(p, 0.0), id(p, depth), id(q, depth), id(q, 0.0)});
  }
  return m;
}

/// A U (a staple) 3 wide, 2 high, 1 deep: legs x in [0,1] and [2,3] from z = 0 to 2,
/// joined by a bridge over z in [1, 2]. Non-convex, made of convex faces.
inline collision::MeshData makeStaple() {
  using V = Eigen::Vector2d;
  return extrudeProfile({{V(0, 0), V(1, 0), V(1, 1), V(1, 2), V(0, 2)},
                         {V(1, 1), V(2, 1), V(2, 2), V(1, 2)},
                         {V(2, 0), V(3, 0), V(3, 2), V(2, 2), V(2, 1)}},
                        {V(0, 0), V(1, 0), V(1, 1), V(2, 1), V(2, 0), V(3, 0), V(3, 2), V(2, 2), V(1, 2), V(0, 2)}, 1.0);
}

/// An L: a 2 x 1 foot (x in [0,2], z in [0,1]) with a 1 x 1 upright on its left
/// (x in [0,1], z in [1,2]); 1 deep. Volume 3, non-convex.
inline collision::MeshData makeL() {
  using V = Eigen::Vector2d;
  return extrudeProfile({{V(0, 0), V(1, 0), V(1, 1), V(1, 2), V(0, 2)}, {V(1, 0), V(2, 0), V(2, 1), V(1, 1)}},
                        {V(0, 0), V(1, 0), V(2, 0), V(2, 1), V(1, 1), V(1, 2), V(0, 2)}, 1.0);
}

/// A regular hexagonal prism of circumradius r and height h, centred on the origin,
/// axis along z: two six-vertex faces.
inline collision::MeshData makeHexPrism(double r, double h) {
  collision::MeshData m;
  for (int k = 0; k < 6; ++k) m.vertices.emplace_back(r * std::cos(k * M_PI / 3), r * std::sin(k * M_PI / 3), -h / 2);
  for (int k = 0; k < 6; ++k) m.vertices.emplace_back(r * std::cos(k * M_PI / 3), r * std::sin(k * M_PI / 3), h / 2);
  m.faces.push_back({5, 4, 3, 2, 1, 0});
  m.faces.push_back({6, 7, 8, 9, 10, 11});
  for (int k = 0; k < 6; ++k) m.faces.push_back({k, (k + 1) % 6, 6 + (k + 1) % 6, 6 + k});
  return m;
}

/// A square cup: outer side 2*outer, height `height`, walls `wall` thick, a floor
/// `floor` thick; the origin at the centre of its bottom face. Non-convex, 14 convex faces.
inline collision::MeshData makeCup(double outer, double height, double wall, double floor) {
  collision::MeshData m;
  const double w = outer - wall;
  auto square = [&](double h, double z) {
    const int first = static_cast<int>(m.vertices.size());
    m.vertices.emplace_back(-h, -h, z);
    m.vertices.emplace_back(h, -h, z);
    m.vertices.emplace_back(h, h, z);
    m.vertices.emplace_back(-h, h, z);
    return first;
  };
  const int ob = square(outer, 0), ot = square(outer, height), it = square(w, height), ib = square(w, floor);
  // Each face listed counter-clockwise seen from outside the solid.
  m.faces.push_back({ob + 0, ob + 3, ob + 2, ob + 1});  // bottom, facing -z
  m.faces.push_back({ib + 0, ib + 1, ib + 2, ib + 3});  // cavity floor, facing +z
  for (int k = 0; k < 4; ++k) {
    const int k1 = (k + 1) % 4;
    m.faces.push_back({ob + k, ob + k1, ot + k1, ot + k});  // outer wall
    m.faces.push_back({ot + k, ot + k1, it + k1, it + k});  // rim
    m.faces.push_back({it + k, it + k1, ib + k1, ib + k});  // inner wall, facing the cavity
  }
  return m;
}

}  // namespace polysim::test
