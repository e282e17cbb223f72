#pragma once
// ODE geoms built from polysim meshes, so that both engines are asked about the same
// geometry in the benchmarks. ODE is only ever the reference.

#include <ode/ode.h>

#include <Eigen/Geometry>
#include <vector>

#include "collision/polygon_mesh.h"

namespace polysim::bench {

/// An ODE triangle mesh of a polysim mesh (polygons fanned into triangles). Owns the
/// arrays ODE points into; keep it alive as long as the geom.
class OdeTriMesh {
 public:
  explicit OdeTriMesh(const collision::MeshData& mesh);
  ~OdeTriMesh();
  OdeTriMesh(const OdeTriMesh&) = delete;
  OdeTriMesh& operator=(const OdeTriMesh&) = delete;
  dGeomID geom() const { return geom_; }

 private:
  std::vector<double> vertices_;
  std::vector<dTriIndex> indices_;
  dTriMeshDataID data_ = nullptr;
  dGeomID geom_ = nullptr;
};

/// Sets an ODE geom's pose from an isometry.
void setPose(dGeomID geom, const Eigen::Isometry3d& X_WO);

}  // namespace polysim::bench
