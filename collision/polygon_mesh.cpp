#include "collision/polygon_mesh.h"

#include <algorithm>

#include <cmath>
#include <map>
#include <sstream>
#include <stdexcept>
#include <utility>

#include "collision/tolerances.h"

namespace polysim::collision {
namespace {

// Newell's method: the normal of a polygon from the sum of its edges' cross terms. Its
// length is twice the polygon's area, and it is robust for nearly collinear vertices.
Eigen::Vector3d newellNormal(const std::vector<Eigen::Vector3d>& v, const std::vector<int>& face) {
  Eigen::Vector3d n = Eigen::Vector3d::Zero();
  for (size_t i = 0; i < face.size(); ++i) {
    const Eigen::Vector3d& a = v[face[i]];
    const Eigen::Vector3d& b = v[face[(i + 1) % face.size()]];
    n += a.cross(b);
  }
  return n;
}

std::string faceProblem(int f, const std::vector<Eigen::Vector3d>& v, const std::vector<int>& face) {
  std::ostringstream out;
  const Eigen::Vector3d n2 = newellNormal(v, face);
  const double area = 0.5 * n2.norm();
  if (!(area > kMinFaceArea)) {
    out << "face " << f << " has zero area";
    return out.str();
  }
  const Eigen::Vector3d n = n2.normalized();
  double offset = 0.0;
  for (int i : face) offset += n.dot(v[i]);
  offset /= static_cast<double>(face.size());
  int worst = face[0];
  double worstDistance = 0.0;
  for (int i : face) {
    const double d = std::abs(n.dot(v[i]) - offset);
    if (d > worstDistance) worstDistance = d, worst = i;
  }
  if (worstDistance > kPlanarityTolerance) {
    out << "face " << f << " is not planar (vertex " << worst << " is " << worstDistance
        << " off its plane)";
    return out.str();
  }
  // Convex and counter-clockwise about n: every vertex on the left of the directed line
  // through its two predecessors, and the exterior angles summing to one full turn (a
  // star-shaped pentagon turns left everywhere but twice around).
  const size_t k = face.size();
  double turning = 0.0;
  for (size_t i = 0; i < k; ++i) {
    const Eigen::Vector3d& a = v[face[i]];
    const Eigen::Vector3d& b = v[face[(i + 1) % k]];
    const Eigen::Vector3d& c = v[face[(i + 2) % k]];
    const Eigen::Vector3d ab = b - a, bc = c - b;
    const Eigen::Vector3d inward = n.cross(ab).normalized();  // left of ab, in the plane
    if (ab.norm() > 0 && inward.dot(c - a) < -kConvexityTolerance) {
      out << "face " << f << " is not convex (vertex " << face[(i + 2) % k]
          << " turns the wrong way)";
      return out.str();
    }
    if (ab.norm() > 0 && bc.norm() > 0)
      turning += std::atan2(n.dot(ab.cross(bc)), ab.dot(bc));
  }
  if (std::abs(turning - 2 * M_PI) > kWindingTolerance) {
    out << "face " << f << " is not convex (its boundary winds " << turning / (2 * M_PI)
        << " times)";
    return out.str();
  }
  return {};
}

}  // namespace

std::vector<std::string> validateMesh(const MeshData& data, bool mustBeClosed) {
  std::vector<std::string> problems;
  const int nv = static_cast<int>(data.vertices.size());
  if (nv < 3) problems.push_back("has " + std::to_string(nv) + " vertices (at least 3 needed)");
  if (data.faces.empty()) problems.push_back("has no faces");
  for (int i = 0; i < nv; ++i)
    if (!data.vertices[i].allFinite())
      problems.push_back("vertex " + std::to_string(i) + " is not a finite number");
  if (!problems.empty()) return problems;

  bool indicesOk = true;
  for (size_t f = 0; f < data.faces.size(); ++f) {
    const auto& face = data.faces[f];
    const std::string name = "face " + std::to_string(f);
    if (face.size() < 3) {
      problems.push_back(name + " has " + std::to_string(face.size()) + " vertices (at least 3 needed)");
      indicesOk = false;
      continue;
    }
    for (size_t i = 0; i < face.size(); ++i) {
      if (face[i] < 0 || face[i] >= nv) {
        problems.push_back(name + " uses vertex " + std::to_string(face[i]) + ", out of range 0.." +
                           std::to_string(nv - 1));
        indicesOk = false;
      }
      for (size_t j = 0; j < i; ++j)
        if (face[j] == face[i]) {
          problems.push_back(name + " uses vertex " + std::to_string(face[i]) + " twice");
          indicesOk = false;
        }
    }
  }
  if (!indicesOk) return problems;

  for (size_t f = 0; f < data.faces.size(); ++f) {
    std::string p = faceProblem(static_cast<int>(f), data.vertices, data.faces[f]);
    if (!p.empty()) problems.push_back(std::move(p));
  }

  // Directed edge -> faces using it. A closed, consistently oriented surface uses every
  // directed edge exactly once and its reverse exactly once.
  std::map<std::pair<int, int>, std::vector<int>> directed;
  for (size_t f = 0; f < data.faces.size(); ++f) {
    const auto& face = data.faces[f];
    for (size_t i = 0; i < face.size(); ++i)
      directed[{face[i], face[(i + 1) % face.size()]}].push_back(static_cast<int>(f));
  }
  for (const auto& [edge, faces] : directed) {
    const std::string name = "edge " + std::to_string(edge.first) + "-" + std::to_string(edge.second);
    if (faces.size() > 1) {
      problems.push_back(name + " runs the same way in faces " + std::to_string(faces[0]) + " and " +
                         std::to_string(faces[1]) + " (inconsistent orientation or a non-manifold edge)");
    } else if (mustBeClosed && !directed.count({edge.second, edge.first})) {
      problems.push_back("is not closed: " + name + " of face " + std::to_string(faces[0]) +
                         " has no neighbouring face");
    }
    if (problems.size() > 20) {
      problems.push_back("(further problems not listed)");
      break;
    }
  }
  if (!problems.empty()) return problems;
  // A closed surface wound clockwise seen from outside is inside-out: its normals point
  // into the solid, and every contact with it would be judged from the wrong side. Its
  // signed volume (divergence theorem over the faces' fans) is then negative.
  const bool closed = std::all_of(directed.begin(), directed.end(),
                                  [&directed](const auto& e) { return directed.count({e.first.second, e.first.first}) > 0; });
  double sixVolume = 0.0;
  for (const auto& face : data.faces)
    for (size_t i = 1; i + 1 < face.size(); ++i)
      sixVolume += data.vertices[face[0]].dot(data.vertices[face[i]].cross(data.vertices[face[i + 1]]));
  if (closed && sixVolume < 0.0)
    problems.push_back("is inside-out: its faces are wound clockwise seen from outside (list each face's vertices "
                       "counter-clockwise seen from outside the solid)");
  return problems;
}

PolygonMesh::PolygonMesh(MeshData data) {
  const std::vector<std::string> problems = validateMesh(data, false);
  if (!problems.empty()) throw std::invalid_argument("invalid polygon mesh: " + problems.front());
  vertices_ = std::move(data.vertices);

  std::map<std::pair<int, int>, int> edgeIndex;  // undirected (min, max) -> edge
  faceStart_.push_back(0);
  for (size_t f = 0; f < data.faces.size(); ++f) {
    const auto& face = data.faces[f];
    Eigen::AlignedBox3d box;
    for (size_t i = 0; i < face.size(); ++i) {
      const int a = face[i], b = face[(i + 1) % face.size()];
      faceIndices_.push_back(a);
      box.extend(vertices_[a]);
      const auto key = std::minmax(a, b);
      auto [it, inserted] = edgeIndex.try_emplace({key.first, key.second}, static_cast<int>(edges_.size()));
      if (inserted) edges_.push_back({a, b, static_cast<int>(f), -1});
      else edges_[it->second].face1 = static_cast<int>(f);
      faceEdges_.push_back(it->second);
    }
    faceStart_.push_back(static_cast<int>(faceIndices_.size()));
    const Eigen::Vector3d n = newellNormal(vertices_, face).normalized();
    double offset = 0.0;
    for (int i : face) offset += n.dot(vertices_[i]);
    planes_.push_back({n, offset / static_cast<double>(face.size())});
    faceBounds_.push_back(box);
    bounds_.extend(box);
  }
  vertexEdgeStart_.assign(vertices_.size() + 1, 0);
  for (const MeshEdge& e : edges_) ++vertexEdgeStart_[e.v0 + 1], ++vertexEdgeStart_[e.v1 + 1];
  for (size_t v = 0; v < vertices_.size(); ++v) vertexEdgeStart_[v + 1] += vertexEdgeStart_[v];
  vertexEdges_.resize(2 * edges_.size());
  std::vector<int> next(vertexEdgeStart_.begin(), vertexEdgeStart_.end() - 1);
  for (size_t e = 0; e < edges_.size(); ++e)
    for (int v : {edges_[e].v0, edges_[e].v1}) vertexEdges_[next[v]++] = static_cast<int>(e);

  closed_ = true;
  edgeOutward_.reserve(edges_.size());
  for (const MeshEdge& e : edges_) {
    Eigen::Vector3d out = planes_[e.face0].normal;
    if (e.face1 >= 0) out += planes_[e.face1].normal;
    else closed_ = false;
    const bool flat = e.face1 >= 0 && planes_[e.face0].normal.dot(planes_[e.face1].normal) >= std::cos(kFlatEdgeAngle);
    edgeFlat_.push_back(flat);
    // Two faces folded flat onto each other have no outward direction; keep face0's.
    edgeOutward_.push_back(out.norm() > kParallelSine ? out.normalized() : planes_[e.face0].normal);
  }
  classifySides();
  convex_ = !edges_.empty() && closed_ && connected() && foldsOutward();
  for (int x = -1; x <= 1 && !vertices_.empty(); ++x)
    for (int y = -1; y <= 1; ++y)
      for (int z = -1; z <= 1; ++z) {
        if (x == 0 && y == 0 && z == 0) continue;
        const Eigen::Vector3d d(x, y, z);
        int best = 0;
        for (size_t v = 1; v < vertices_.size(); ++v)
          if (d.dot(vertices_[v]) > d.dot(vertices_[best])) best = static_cast<int>(v);
        climbStarts_.push_back(best);
      }
  if (convex_) findSeparatingDirections();
}

void PolygonMesh::findSeparatingDirections() {
  // Adds u unless it is parallel to one already listed; false once the list is full.
  auto addDistinct = [](std::vector<Eigen::Vector3d>& list, const Eigen::Vector3d& u) {
    for (const Eigen::Vector3d& w : list)
      if (u.cross(w).norm() <= kParallelSine) return true;
    if (list.size() == static_cast<size_t>(kMaxSeparatingDirections)) return false;
    list.push_back(u);
    return true;
  };
  bool few = true;
  for (int f = 0; f < faceCount() && few; ++f) few = addDistinct(faceDirections_, planes_[f].normal);
  for (size_t e = 0; e < edges_.size() && few; ++e)
    few = addDistinct(edgeDirections_, (vertices_[edges_[e].v1] - vertices_[edges_[e].v0]).normalized());
  if (!few) faceDirections_.clear(), edgeDirections_.clear();
  if (few && vertices_.size() <= kScanUpTo) findMirroredHalf();
}

void PolygonMesh::classifySides() {
  sideConvex_.assign(faceIndices_.size(), 0);
  faceConvex_.assign(faceCount(), 0);
  for (int f = 0; f < faceCount(); ++f) {
    const int* ids = faceVertices(f);
    const Eigen::Vector3d& n = planes_[f].normal;
    for (int i = 0, size = faceSize(f); i < size; ++i) {
      const MeshEdge& e = edges_[faceEdge(f, i)];
      if (e.face1 < 0 || edgeFlat_[faceEdge(f, i)]) continue;  // a boundary or a flat patch bounds nothing
      const Eigen::Vector3d side = (vertices_[ids[(i + 1) % size]] - vertices_[ids[i]]).cross(n).normalized();
      const Eigen::Vector3d& across = planes_[e.face0 == f ? e.face1 : e.face0].normal;
      sideConvex_[faceStart_[f] + i] = side.dot(across) > kFlatEdgeAngle;
      faceConvex_[f] = faceConvex_[f] || sideConvex_[faceStart_[f] + i];
    }
  }
}

void PolygonMesh::findMirroredHalf() {
  Eigen::Vector3d centre = Eigen::Vector3d::Zero();
  for (const Eigen::Vector3d& v : vertices_) centre += v;
  centre /= static_cast<double>(vertices_.size());
  std::vector<char> paired(vertices_.size(), 0);
  std::vector<Eigen::Vector3d> half;
  for (size_t i = 0; i < vertices_.size(); ++i) {
    if (paired[i]) continue;
    const Eigen::Vector3d mirror = 2.0 * centre - vertices_[i];
    size_t j = i + 1;
    while (j < vertices_.size() && (paired[j] || (vertices_[j] - mirror).norm() > kPlanarityTolerance)) ++j;
    if (j == vertices_.size()) return;  // not symmetric (a vertex at the centre has no pair either)
    paired[i] = paired[j] = 1;
    half.push_back(vertices_[i]);
  }
  centre_ = centre;
  mirroredHalf_ = std::move(half);
}

bool PolygonMesh::connected() const {
  std::vector<char> seen(vertices_.size(), 0);
  std::vector<int> todo{faceIndices_.front()};
  seen[todo.back()] = 1;
  while (!todo.empty()) {
    const int v = todo.back();
    todo.pop_back();
    for (const int* e = vertexEdgesBegin(v); e != vertexEdgesEnd(v); ++e) {
      const int w = edges_[*e].v0 == v ? edges_[*e].v1 : edges_[*e].v0;
      if (!seen[w]) seen[w] = 1, todo.push_back(w);
    }
  }
  for (int v : faceIndices_)
    if (!seen[v]) return false;
  return true;
}

bool PolygonMesh::foldsOutward() const {
  auto behind = [&](int face, int other) {
    for (int k = 0; k < faceSize(other); ++k)
      if (planes_[face].signedDistance(vertices_[faceVertices(other)[k]]) > kPlanarityTolerance) return false;
    return true;
  };
  for (const MeshEdge& e : edges_)
    if (!behind(e.face0, e.face1) || !behind(e.face1, e.face0)) return false;
  return true;
}

std::pair<double, double> PolygonMesh::extentAlong(const Eigen::Vector3d& d) const {
  if (vertices_.size() > kScanUpTo) return {d.dot(vertices_[extremeVertex(-d)]), d.dot(vertices_[extremeVertex(d)])};
  double lo = d.dot(vertices_.front()), hi = lo;
  for (const Eigen::Vector3d& v : vertices_) {
    const double level = d.dot(v);
    lo = std::min(lo, level);
    hi = std::max(hi, level);
  }
  return {lo, hi};
}

int PolygonMesh::extremeVertex(const Eigen::Vector3d& d) const {
  if (vertices_.size() <= kScanUpTo) {
    int best = 0;
    for (size_t v = 1; v < vertices_.size(); ++v)
      if (d.dot(vertices_[v]) > d.dot(vertices_[best])) best = static_cast<int>(v);
    return best;
  }
  int v = climbStarts_.front();
  for (int start : climbStarts_)
    if (d.dot(vertices_[start]) > d.dot(vertices_[v])) v = start;
  double level = d.dot(vertices_[v]);
  for (int at = -1; at != v;) {  // steepest ascent until no neighbour is farther
    at = v;
    for (const int* e = vertexEdgesBegin(at); e != vertexEdgesEnd(at); ++e) {
      const int w = edges_[*e].v0 == at ? edges_[*e].v1 : edges_[*e].v0;
      const double l = d.dot(vertices_[w]);
      if (l > level) level = l, v = w;
    }
  }
  return v;
}

std::vector<std::vector<int>> PolygonMesh::faceLists() const {
  std::vector<std::vector<int>> faces(faceCount());
  for (int f = 0; f < faceCount(); ++f) faces[f].assign(faceVertices(f), faceVertices(f) + faceSize(f));
  return faces;
}

}  // namespace polysim::collision
