#include "dynamics/mass_properties.h"

namespace polysim::dynamics {

MassProperties computeMassProperties(const std::vector<Eigen::Vector3d>& vertices,
                                     const std::vector<std::vector<int>>& faces, double density) {
  // Second moments about the origin, C = integral of x x^T dV. For the tetrahedron
  // (0, a, b, c) with A = [a b c], C = det(A)/120 * A S A^T, S = ones + identity.
  const Eigen::Matrix3d S = Eigen::Matrix3d::Ones() + Eigen::Matrix3d::Identity();
  // Shift to a point inside the mesh's span first: the sums then cancel less (Box2D's
  // local-origin habit).
  Eigen::Vector3d origin = Eigen::Vector3d::Zero();
  for (const Eigen::Vector3d& v : vertices) origin += v;
  origin /= static_cast<double>(vertices.size());

  double volume = 0.0;
  Eigen::Vector3d firstMoment = Eigen::Vector3d::Zero();
  Eigen::Matrix3d C = Eigen::Matrix3d::Zero();
  for (const std::vector<int>& face : faces)
    for (size_t k = 1; k + 1 < face.size(); ++k) {
      Eigen::Matrix3d A;
      A << vertices[face[0]] - origin, vertices[face[k]] - origin, vertices[face[k + 1]] - origin;
      const double det = A.determinant();
      volume += det / 6.0;
      firstMoment += det / 24.0 * (A.col(0) + A.col(1) + A.col(2));
      C += det / 120.0 * (A * S * A.transpose());
    }

  MassProperties p;
  p.volume = volume;
  p.mass = density * volume;
  const Eigen::Vector3d c = firstMoment / volume;  // relative to `origin`
  p.centerOfMass = origin + c;
  const Eigen::Matrix3d Ccom = density * (C - volume * c * c.transpose());  // about the centre of mass
  p.inertia = Ccom.trace() * Eigen::Matrix3d::Identity() - Ccom;
  return p;
}

MassProperties withMass(MassProperties props, double mass) {
  const double scale = mass / props.mass;
  props.mass = mass;
  props.inertia *= scale;
  return props;
}

}  // namespace polysim::dynamics
