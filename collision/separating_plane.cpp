#include "collision/separating_plane.h"

#include <algorithm>
#include <array>
#include <limits>

#include "collision/broadphase.h"
#include "collision/tolerances.h"

namespace polysim::collision {
namespace {

// The largest d . x over a box: its centre's level plus its half extents projected on |d|.
double boxTop(const Eigen::AlignedBox3d& box, const Eigen::Vector3d& d) {
  return d.dot(box.center()) + 0.5 * d.cwiseAbs().dot(box.sizes());
}

constexpr double kInfinity = std::numeric_limits<double>::infinity();

// Calls visit(v) for each vertex of the faces listed in a leaf (a vertex may come twice).
template <class Visit>
void forEachLeafVertex(const ObjNode& object, const VoxelCell& leaf, Visit&& visit) {
  const PolygonMesh& mesh = *object.mesh;
  const VoxelGrid& grid = *object.grid;
  for (const int* f = grid.facesBegin(leaf); f != grid.facesEnd(leaf); ++f) {
    const int* ids = mesh.faceVertices(*f);
    for (int k = 0; k < mesh.faceSize(*f); ++k) visit(mesh.vertices()[ids[k]]);
  }
}

// A depth-first stack of cells: each pop pushes at most two children one level down, so
// it never holds more than one cell per level plus one.
class CellStack {
 public:
  CellStack() { push(VoxelCell{}); }
  bool empty() const { return size_ == 0; }
  void push(const VoxelCell& cell) { cells_[size_++] = cell; }
  VoxelCell pop() { return cells_[--size_]; }

 private:
  std::array<VoxelCell, VoxelGrid::kMostHalvings + 2> cells_;
  int size_ = 0;
};

}  // namespace

double topLevelAlong(const ObjNode& object, const Eigen::Vector3d& d, double slack, double known) {
  const VoxelGrid& grid = *object.grid;
  double best = known;  // may be -infinity
  CellStack stack;
  while (!stack.empty()) {
    const VoxelCell cell = stack.pop();
    const Eigen::AlignedBox3d& box = grid.contentBox(cell);
    if (box.isEmpty() || boxTop(box, d) <= best + slack) continue;
    if (grid.isLeaf(cell)) {
      forEachLeafVertex(object, cell, [&](const Eigen::Vector3d& v) { best = std::max(best, d.dot(v)); });
      continue;
    }
    VoxelCell first, second;
    grid.children(cell, first, second);
    // The more promising half goes on top, so that a good bound prunes the other early.
    const bool firstHigher = boxTop(grid.contentBox(first), d) >= boxTop(grid.contentBox(second), d);
    stack.push(firstHigher ? second : first);
    stack.push(firstHigher ? first : second);
  }
  return best;
}

namespace {

// How far an object reaches along a unit world direction d: a level some vertex reaches,
// and a level no vertex passes (the same for a convex mesh, whose extreme vertex is
// found exactly; `slack` above it otherwise).
struct Reach {
  double reached, limit;
};

Reach reachAlong(const ObjNode& object, const Eigen::Vector3d& d, double slack, double known) {
  const Eigen::Vector3d local = object.X_WO.linear().transpose() * d;
  const double shift = d.dot(object.X_WO.translation());
  if (object.mesh->convex()) {
    const double level = local.dot(object.mesh->vertices()[object.mesh->extremeVertex(local)]) + shift;
    return {level, level};
  }
  const double level = topLevelAlong(object, local, slack, known - shift) + shift;
  return {level, level + slack};
}

}  // namespace

bool separatedAlongCentreLine(const ObjNode& a, const ObjNode& b, double eps) {
  const Eigen::AlignedBox3d boxA = worldContainer(a), boxB = worldContainer(b);
  const Eigen::Vector3d line = boxB.center() - boxA.center();
  if (line.norm() == 0.0) return false;
  const Eigen::Vector3d d = line.normalized();
  // a's top along d and b's bottom (its top along -d). A non-convex object's is bounded
  // within a slack: start coarse (few cells), then tighten it to the gap the vertices
  // found leave, until the bounds settle the question either way.
  double slack = 0.125 * std::min(boxA.diagonal().norm(), boxB.diagonal().norm());
  Reach top{-kInfinity, -kInfinity}, bottom{-kInfinity, -kInfinity};  // bottom: along -d
  constexpr int kRounds = 4;
  for (int round = 0; round < kRounds; ++round) {
    top = reachAlong(a, d, slack, top.reached);
    bottom = reachAlong(b, -d, slack, bottom.reached);
    const double gap = -bottom.reached - top.reached;  // between real vertices: the true gap is no wider
    if (gap <= eps) return false;
    if (-bottom.limit - top.limit > eps) return true;
    slack = 0.25 * (gap - eps);
  }
  return false;
}

}  // namespace polysim::collision
