#pragma once
// A polygonal object's shape: vertices in the object's own frame and planar convex
// faces of any vertex count. The object need not be convex, nor closed.

#include <Eigen/Geometry>
#include <string>
#include <vector>

namespace polysim::collision {

/// The plane {x : normal . x = offset}; normal is unit length and points out of the
/// object. signedDistance is positive outside, in metres.
struct Plane {
  Eigen::Vector3d normal = Eigen::Vector3d::UnitZ();
  double offset = 0.0;
  double signedDistance(const Eigen::Vector3d& p) const { return normal.dot(p) - offset; }
};

/// An undirected edge between two vertices and the (one or two) faces that share it.
/// face1 is -1 on the boundary of an open mesh.
struct MeshEdge {
  int v0 = 0, v1 = 0;
  int face0 = -1, face1 = -1;
};

/// The raw description of a mesh as a scene gives it: vertex positions (m, object frame)
/// and faces as counter-clockwise vertex index lists seen from outside.
struct MeshData {
  std::vector<Eigen::Vector3d> vertices;
  std::vector<std::vector<int>> faces;
};

/// Every problem with `data` as a polygon mesh, one readable sentence each ("face 3 is
/// not planar (vertex 7 is 0.02 off its plane)"); empty when the mesh is valid. With
/// `mustBeClosed`, a mesh whose edges are not each shared by exactly two faces with
/// opposite directions is rejected too (a dynamic body needs a closed surface). A closed
/// surface wound clockwise seen from outside (inside-out) is rejected either way.
std::vector<std::string> validateMesh(const MeshData& data, bool mustBeClosed);

/// An immutable, validated polygon mesh with its derived data: face planes, unique
/// edges, each face's edges, and the bounding box of its vertices (object frame).
class PolygonMesh {
 public:
  /// Builds from data that validateMesh accepted; throws std::invalid_argument otherwise.
  explicit PolygonMesh(MeshData data);

  const std::vector<Eigen::Vector3d>& vertices() const { return vertices_; }
  int faceCount() const { return static_cast<int>(faceStart_.size()) - 1; }
  /// The vertex indices of face f, counter-clockwise seen from outside.
  const int* faceVertices(int f) const { return faceIndices_.data() + faceStart_[f]; }
  int faceSize(int f) const { return faceStart_[f + 1] - faceStart_[f]; }
  /// The mesh edge running from vertex i to vertex i+1 of face f.
  int faceEdge(int f, int i) const { return faceEdges_[faceStart_[f] + i]; }
  const Plane& facePlane(int f) const { return planes_[f]; }
  const Eigen::AlignedBox3d& faceBounds(int f) const { return faceBounds_[f]; }
  const std::vector<MeshEdge>& edges() const { return edges_; }
  /// The edges at vertex v, as a range of edge indices.
  const int* vertexEdgesBegin(int v) const { return vertexEdges_.data() + vertexEdgeStart_[v]; }
  const int* vertexEdgesEnd(int v) const { return vertexEdges_.data() + vertexEdgeStart_[v + 1]; }
  /// Unit direction pointing out of the object at edge e: the normalized sum of the
  /// normals of its faces (the face normal for a boundary edge).
  const Eigen::Vector3d& edgeOutward(int e) const { return edgeOutward_[e]; }
  /// True when edge e joins two faces in the same plane (within kFlatEdgeAngle): an
  /// internal edge of a flat patch, not a crease or boundary of the surface.
  bool edgeIsFlat(int e) const { return edgeFlat_[e] != 0; }
  /// True when side i of face f (vertex i to i+1) is a convex crease: the face across it
  /// turns away from f's side by more than kFlatEdgeAngle (a box's edges, a cup's rim).
  /// Reflex creases, flat edges and open boundaries are not. A rigid motion keeps it.
  bool sideIsConvexCrease(int f, int i) const { return sideConvex_[faceStart_[f] + i] != 0; }
  /// The same for every side of face f, one flag per side; and whether any is set.
  const char* convexCreaseSides(int f) const { return sideConvex_.data() + faceStart_[f]; }
  bool hasConvexCrease(int f) const { return faceConvex_[f] != 0; }
  const Eigen::AlignedBox3d& bounds() const { return bounds_; }
  bool closed() const { return closed_; }
  /// True when the mesh bounds a convex solid: closed, connected, and every pair of
  /// faces meeting at an edge folds outward (each face's vertices lie behind the other's
  /// plane, within kPlanarityTolerance). Then a vertex with no neighbour farther along a
  /// direction is the farthest of all (see extremeVertex).
  bool convex() const { return convex_; }
  /// The vertex farthest along d (object frame, any length). Exact for a convex mesh, by
  /// climbing from neighbour to neighbour (O(sqrt(vertices)) steps on a sphere); on a
  /// non-convex mesh only a local maximum.
  int extremeVertex(const Eigen::Vector3d& d) const;
  /// Meshes with at most this many vertices are scanned rather than climbed: quicker.
  static constexpr size_t kScanUpTo = 32;
  /// The least and greatest d . x over the vertices: exact for a convex mesh (and for
  /// any mesh of at most kScanUpTo vertices, which are scanned).
  std::pair<double, double> extentAlong(const Eigen::Vector3d& d) const;
  /// A convex mesh's face normals and edge directions (unit, object frame), each listed
  /// once up to sign: the candidate axes of the separating axis test (a box has three of
  /// each). Both empty when the mesh is not convex or has more than
  /// kMaxSeparatingDirections of either.
  const std::vector<Eigen::Vector3d>& faceDirections() const { return faceDirections_; }
  const std::vector<Eigen::Vector3d>& edgeDirections() const { return edgeDirections_; }
  /// For a convex mesh with separating directions whose vertices pair up mirrored
  /// through their centroid (a box, an even prism): one vertex of each pair. The extent
  /// along any direction follows from these and centre() alone, at half the scan.
  /// Empty otherwise.
  const std::vector<Eigen::Vector3d>& mirroredHalf() const { return mirroredHalf_; }
  /// The centroid of the vertices, when mirroredHalf() is not empty.
  const Eigen::Vector3d& centre() const { return centre_; }
  /// The faces as index lists (for mass properties and output).
  std::vector<std::vector<int>> faceLists() const;

 private:
  bool connected() const;     // every face's vertex reachable from the first along edges
  bool foldsOutward() const;  // closed mesh: no edge folds inward
  void findSeparatingDirections();
  void findMirroredHalf();
  void classifySides();       // fills sideConvex_ and faceConvex_ from the planes and edges

  std::vector<Eigen::Vector3d> vertices_;
  std::vector<int> faceStart_;    // CSR offsets into faceIndices_, size faceCount()+1
  std::vector<int> faceIndices_;
  std::vector<int> faceEdges_;    // parallel to faceIndices_
  std::vector<Plane> planes_;
  std::vector<Eigen::AlignedBox3d> faceBounds_;
  std::vector<MeshEdge> edges_;
  std::vector<int> vertexEdgeStart_;  // CSR offsets into vertexEdges_, size vertex count + 1
  std::vector<int> vertexEdges_;
  std::vector<Eigen::Vector3d> edgeOutward_;
  std::vector<char> edgeFlat_;
  std::vector<char> sideConvex_;  // parallel to faceIndices_
  std::vector<char> faceConvex_;  // per face: some side is a convex crease
  Eigen::AlignedBox3d bounds_;
  bool closed_ = false;
  bool convex_ = false;
  std::vector<int> climbStarts_;  // the farthest vertices along the 26 directions of a cube
  std::vector<Eigen::Vector3d> faceDirections_, edgeDirections_;
  std::vector<Eigen::Vector3d> mirroredHalf_;
  Eigen::Vector3d centre_ = Eigen::Vector3d::Zero();
};

}  // namespace polysim::collision
