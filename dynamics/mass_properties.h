#pragma once
// Mass properties of a closed polygon mesh, exact for polyhedra, convex or not.

#include <Eigen/Dense>
#include <vector>

namespace polysim::dynamics {

/// Volume, centre of mass and inertia of a solid of uniform density.
struct MassProperties {
  double mass = 0.0;                                          // kg
  double volume = 0.0;                                        // m^3; negative for an inside-out mesh
  Eigen::Vector3d centerOfMass = Eigen::Vector3d::Zero();     // m, mesh frame
  Eigen::Matrix3d inertia = Eigen::Matrix3d::Zero();          // kg m^2, about the centre of mass, mesh axes
};

/// The properties of the solid bounded by a closed, outward-oriented polygon mesh
/// (vertices in m, faces counter-clockwise seen from outside) with the given density
/// (kg/m^3). Each face is fanned into triangles, and each triangle with the origin
/// spans a signed tetrahedron whose volume, first and second moments are summed
/// (the divergence theorem; Tonon 2004's closed forms for a tetrahedron).
MassProperties computeMassProperties(const std::vector<Eigen::Vector3d>& vertices,
                                     const std::vector<std::vector<int>>& faces, double density);

/// The same solid scaled to the given total mass (kg).
MassProperties withMass(MassProperties props, double mass);

}  // namespace polysim::dynamics
