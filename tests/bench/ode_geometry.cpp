#include "tests/bench/ode_geometry.h"

namespace polysim::bench {

OdeTriMesh::OdeTriMesh(const collision::MeshData& mesh) {
  for (const Eigen::Vector3d& v : mesh.vertices) vertices_.insert(vertices_.end(), {v.x(), v.y(), v.z()});
  for (const auto& face : mesh.faces)
    for (size_t k = 1; k + 1 < face.size(); ++k)
      indices_.insert(indices_.end(), {static_cast<dTriIndex>(face[0]), static_cast<dTriIndex>(face[k]),
                                       static_cast<dTriIndex>(face[k + 1])});
  data_ = dGeomTriMeshDataCreate();
  dGeomTriMeshDataBuildDouble(data_, vertices_.data(), 3 * sizeof(double), static_cast<int>(mesh.vertices.size()),
                              indices_.data(), static_cast<int>(indices_.size()), 3 * sizeof(dTriIndex));
  geom_ = dCreateTriMesh(nullptr, data_, nullptr, nullptr, nullptr);
}

OdeTriMesh::~OdeTriMesh() {
  dGeomDestroy(geom_);
  dGeomTriMeshDataDestroy(data_);
}

void setPose(dGeomID geom, const Eigen::Isometry3d& X) {
  dGeomSetPosition(geom, X.translation().x(), X.translation().y(), X.translation().z());
  dMatrix3 R;  // ODE: 3 rows of 4, row-major
  for (int r = 0; r < 3; ++r) {
    for (int c = 0; c < 3; ++c) R[4 * r + c] = X.linear()(r, c);
    R[4 * r + 3] = 0.0;
  }
  dGeomSetRotation(geom, R);
}

}  // namespace polysim::bench
