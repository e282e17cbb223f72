#include "collision/normal_cone.h"

#include "collision/tolerances.h"

namespace polysim::collision {
namespace {

// Whether every vertex of face f stays within the allowance below the plane through
// `origin` square to `outward`.
bool faceStaysBelow(const PolygonMesh& mesh, int f, const Eigen::Vector3d& origin, const Eigen::Vector3d& outward,
                    double eps) {
  for (int k = 0; k < mesh.faceSize(f); ++k) {
    const Eigen::Vector3d d = mesh.vertices()[mesh.faceVertices(f)[k]] - origin;
    if (d.dot(outward) > eps + kNormalConeSlack * d.norm()) return false;
  }
  return true;
}

// An edge is reflex when its second face rises above the first one's plane. None of a
// convex mesh's is: convex() checked each face against the other's plane, by this test.
bool isReflex(const PolygonMesh& mesh, const MeshEdge& edge) {
  if (mesh.convex() || edge.face0 < 0 || edge.face1 < 0) return false;
  const Plane& plane = mesh.facePlane(edge.face0);
  for (int k = 0; k < mesh.faceSize(edge.face1); ++k)
    if (plane.signedDistance(mesh.vertices()[mesh.faceVertices(edge.face1)[k]]) > kPlanarityTolerance) return true;
  return false;
}

bool edgeAdmits(const PolygonMesh& mesh, const MeshEdge& edge, const Eigen::Vector3d& outward, double eps) {
  if (isReflex(mesh, edge)) return true;
  const Eigen::Vector3d& origin = mesh.vertices()[edge.v0];
  for (int f : {edge.face0, edge.face1})
    if (f >= 0 && !faceStaysBelow(mesh, f, origin, outward, eps)) return false;
  // The edge itself must lie in the plane too, both ways.
  const Eigen::Vector3d d = mesh.vertices()[edge.v1] - origin;
  return std::abs(d.dot(outward)) <= eps + kNormalConeSlack * d.norm();
}

bool vertexAdmits(const PolygonMesh& mesh, int v, const Eigen::Vector3d& outward, double eps) {
  const Eigen::Vector3d& origin = mesh.vertices()[v];
  bool admits = true;
  for (const int* e = mesh.vertexEdgesBegin(v); e != mesh.vertexEdgesEnd(v); ++e) {
    const MeshEdge& edge = mesh.edges()[*e];
    if (isReflex(mesh, edge)) return true;
    const Eigen::Vector3d d = mesh.vertices()[edge.v0 == v ? edge.v1 : edge.v0] - origin;
    admits = admits && d.dot(outward) <= eps + kNormalConeSlack * d.norm();
  }
  return admits;
}

}  // namespace

bool inNormalCone(const PolygonMesh& mesh, const Feature& feature, const Eigen::Vector3d& outward, double eps) {
  if (feature.id < 0) return true;  // unknown feature: no evidence against
  switch (feature.kind) {
    case Feature::Kind::Face: {
      const int f = feature.id;
      return mesh.facePlane(f).normal.dot(outward) > 0 &&
             faceStaysBelow(mesh, f, mesh.vertices()[mesh.faceVertices(f)[0]], outward, eps) &&
             faceStaysBelow(mesh, f, mesh.vertices()[mesh.faceVertices(f)[0]], -outward, eps);
    }
    case Feature::Kind::Edge: return edgeAdmits(mesh, mesh.edges()[feature.id], outward, eps);
    case Feature::Kind::Vertex: return vertexAdmits(mesh, feature.id, outward, eps);
  }
  return true;
}

}  // namespace polysim::collision
