#pragma once
// ODE geoms built from polysim shapes, so that both engines are asked about the same
// geometry: the baseline run, the contact comparison and the benchmarks. ODE is only
// ever the reference.

#include <ode/ode.h>

#include <Eigen/Geometry>
#include <string>
#include <vector>

#include "collision/polygon_mesh.h"

namespace polysim::sim {

/// One ODE geom: a dBox (ODE's best path) or a dTriMesh of a polysim mesh (polygons fanned
/// into triangles; fan triangles with no area are left out, ODE cannot give them a
/// normal). Owns the arrays ODE points into, and destroys the geom with itself.
class OdeGeom {
 public:
  /// A box of the given full size (m), centred on its frame.
  static OdeGeom box(const Eigen::Vector3d& size, dSpaceID space = nullptr);
  static OdeGeom triMesh(const collision::MeshData& mesh, dSpaceID space = nullptr);

  OdeGeom(OdeGeom&& other) noexcept;
  OdeGeom& operator=(OdeGeom&& other) noexcept;
  OdeGeom(const OdeGeom&) = delete;
  OdeGeom& operator=(const OdeGeom&) = delete;
  ~OdeGeom();

  dGeomID geom() const { return geom_; }

 private:
  OdeGeom() = default;
  std::vector<double> vertices_;
  std::vector<dTriIndex> indices_;
  dTriMeshDataID data_ = nullptr;
  dGeomID geom_ = nullptr;
};

/// Sets an ODE geom's world pose from an isometry (for a geom attached to a body, this
/// moves the body).
void setPose(dGeomID geom, const Eigen::Isometry3d& X_WO);

/// ODE's global state, initialised once for the process on first use.
void ensureOdeInitialised();

/// ODE's warnings (dMessage, such as dWorldStep's "LCP internal error") are counted here
/// instead of printed, so that they are reported with the run they belong to instead of
/// flooding stderr. Process-wide: a run reads the count before and after.
struct OdeMessageLog {
  long count = 0;
  std::string last;  // the latest message's text
};
const OdeMessageLog& odeMessages();

}  // namespace polysim::sim
