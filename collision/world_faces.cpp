#include "collision/world_faces.h"

namespace polysim::collision {

void WorldFaces::reset(const ObjNode& object) {
  const int faces = object.mesh->faceCount();
  const bool sameMesh = mesh_ == object.mesh.get() && static_cast<int>(stamp_.size()) == faces;
  // An object that has not moved (a floor, a wall) keeps the faces already placed.
  if (sameMesh && pose_.matrix() == object.X_WO.matrix()) {
    object_ = &object;
    return;
  }
  if (!sameMesh) {
    stamp_.assign(faces, 0);
    entries_.resize(faces);
    query_ = 0;
  }
  object_ = &object;
  mesh_ = object.mesh.get();
  pose_ = object.X_WO;
  ++query_;
  vertices_.clear();
  outward_.clear();
  sideNormals_.clear();
  flat_.clear();
  vertexIds_.clear();
  edgeIds_.clear();
}

const WorldFaces::Entry& WorldFaces::entry(int f) {
  Entry& e = entries_[f];
  if (stamp_[f] == query_) return e;
  stamp_[f] = query_;
  const PolygonMesh& mesh = *object_->mesh;
  const Eigen::Isometry3d& X = object_->X_WO;
  e.first = static_cast<int>(vertices_.size());
  e.box.setEmpty();
  const int* ids = mesh.faceVertices(f);
  for (int i = 0; i < mesh.faceSize(f); ++i) {
    vertices_.push_back(X * mesh.vertices()[ids[i]]);
    e.box.extend(vertices_.back());
    const int edge = mesh.faceEdge(f, i);
    outward_.push_back(X.linear() * mesh.edgeOutward(edge));
    flat_.push_back(mesh.edgeIsFlat(edge));
    vertexIds_.push_back(ids[i]);
    edgeIds_.push_back(edge);
  }
  const Plane& local = mesh.facePlane(f);
  e.plane.normal = X.linear() * local.normal;
  e.plane.offset = local.offset + e.plane.normal.dot(X.translation());
  const int n = mesh.faceSize(f);
  for (int i = 0; i < n; ++i) {
    const Eigen::Vector3d side = vertices_[e.first + (i + 1) % n] - vertices_[e.first + i];
    sideNormals_.push_back(side.cross(e.plane.normal).normalized());
  }
  return e;
}

PolygonView WorldFaces::view(int f) {
  const Entry& e = entry(f);
  PolygonView v;
  v.vertices = vertices_.data() + e.first;
  v.edgeOutward = outward_.data() + e.first;
  v.sideNormal = sideNormals_.data() + e.first;
  v.vertexIds = vertexIds_.data() + e.first;
  v.edgeIds = edgeIds_.data() + e.first;
  v.edgeFlat = flat_.data() + e.first;
  v.convexSide = object_->mesh->convexCreaseSides(f);  // the same in any pose
  v.anyConvexSide = object_->mesh->hasConvexCrease(f);
  v.size = object_->mesh->faceSize(f);
  v.plane = e.plane;
  v.faceId = f;
  return v;
}

}  // namespace polysim::collision
