#include "sim/ode_geometry.h"

#include <cstdarg>
#include <cstdio>
#include <utility>

#include "collision/tolerances.h"

namespace polysim::sim {

OdeGeom OdeGeom::box(const Eigen::Vector3d& size, dSpaceID space) {
  ensureOdeInitialised();
  OdeGeom g;
  g.geom_ = dCreateBox(space, size.x(), size.y(), size.z());
  return g;
}

OdeGeom OdeGeom::triMesh(const collision::MeshData& mesh, dSpaceID space) {
  ensureOdeInitialised();
  OdeGeom g;
  for (const Eigen::Vector3d& v : mesh.vertices) g.vertices_.insert(g.vertices_.end(), {v.x(), v.y(), v.z()});
  for (const auto& face : mesh.faces)
    for (size_t k = 1; k + 1 < face.size(); ++k) {
      const Eigen::Vector3d& p = mesh.vertices[face[0]];
      const double area = 0.5 * (mesh.vertices[face[k]] - p).cross(mesh.vertices[face[k + 1]] - p).norm();
      if (area < collision::kMinFaceArea) continue;  // a collinear vertex on a polygon's edge
      g.indices_.insert(g.indices_.end(), {static_cast<dTriIndex>(face[0]), static_cast<dTriIndex>(face[k]),
                                           static_cast<dTriIndex>(face[k + 1])});
    }
  g.data_ = dGeomTriMeshDataCreate();
  dGeomTriMeshDataBuildDouble(g.data_, g.vertices_.data(), 3 * sizeof(double), static_cast<int>(mesh.vertices.size()),
                              g.indices_.data(), static_cast<int>(g.indices_.size()), 3 * sizeof(dTriIndex));
  g.geom_ = dCreateTriMesh(space, g.data_, nullptr, nullptr, nullptr);
  return g;
}

// The vectors' heap buffers move with them, so ODE's pointers into them stay valid.
OdeGeom::OdeGeom(OdeGeom&& other) noexcept
    : vertices_(std::move(other.vertices_)),
      indices_(std::move(other.indices_)),
      data_(std::exchange(other.data_, nullptr)),
      geom_(std::exchange(other.geom_, nullptr)) {}

OdeGeom& OdeGeom::operator=(OdeGeom&& other) noexcept {
  std::swap(vertices_, other.vertices_);
  std::swap(indices_, other.indices_);
  std::swap(data_, other.data_);
  std::swap(geom_, other.geom_);
  return *this;
}

OdeGeom::~OdeGeom() {
  if (geom_) dGeomDestroy(geom_);
  if (data_) dGeomTriMeshDataDestroy(data_);
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

namespace {

OdeMessageLog messageLog;

void countMessage(int errnum, const char* format, va_list arguments) {
  char text[256];
  std::vsnprintf(text, sizeof text, format, arguments);
  ++messageLog.count;
  messageLog.last = "ODE message " + std::to_string(errnum) + ": " + text;
}

}  // namespace

void ensureOdeInitialised() {
  struct OdeLibrary {
    OdeLibrary() {
      dInitODE2(0);
      dSetMessageHandler(&countMessage);
    }
    ~OdeLibrary() { dCloseODE(); }
  };
  static const OdeLibrary library;
}

const OdeMessageLog& odeMessages() { return messageLog; }

}  // namespace polysim::sim
