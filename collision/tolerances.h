#pragma once
// Every tolerance of the collision module, in one place. Each value has its unit and
// the reason it has the size it has. Scene-level settings (the contact tolerance a scene
// chooses) live in ContactSettings; these are the fixed numerical guards.

namespace polysim::collision {

/// Contact distance band epsilon (m) when a scene gives none (SPEC.md default). Two
/// features closer than this are in contact; a feature more than this inside the other
/// object interpenetrates.
inline constexpr double kDefaultContactTolerance = 1e-4;

/// How far (m) a face's vertex may lie off the face's best-fit plane before the mesh is
/// rejected as non-planar. Two orders below the default contact tolerance, so that a
/// face accepted as planar is flat at the resolution contacts are judged at.
inline constexpr double kPlanarityTolerance = 1e-6;

/// Smallest face area (m^2) accepted in a mesh: a face smaller than this has no
/// reliable normal (its cross products are round-off).
inline constexpr double kMinFaceArea = 1e-12;

/// How far (m) a face's vertex may lie on the wrong side of the line through its
/// neighbours before the face counts as non-convex; the same scale as planarity.
inline constexpr double kConvexityTolerance = 1e-9;

/// How far (rad) the exterior angles of a face may sum away from one full turn before
/// the face counts as self-overlapping; far above the round-off of a few atan2 calls.
inline constexpr double kWindingTolerance = 1e-6;

/// Relative guard for divisions by a squared length or a determinant: below this
/// fraction of the product of the squared lengths, two directions are treated as
/// parallel. sqrt of double epsilon: the angle (rad) resolvable from a cross product.
inline constexpr double kParallelSine = 1.5e-8;

/// Largest angle (rad) between the normals of two faces sharing an edge for the edge to
/// count as flat (an internal edge of a triangulated plane, not a boundary of the
/// surface). Flat edges are no boundary when judging how deep a cut lies inside a face.
/// A planar patch within kPlanarityTolerance over 0.01 m faces bends by about 1e-4.
inline constexpr double kFlatEdgeAngle = 1e-4;

/// Bounds on the number of times the voxel grid halves an object's container (M).
/// Garcia-Alonso et al. found 8 or 9 best for their meshes; polysim picks M so that
/// voxels are about as long as the object's faces (VoxelGrid::chooseHalvings): a box
/// needs none, a 20480-triangle sphere about 16. The benchmark in tests/bench sweeps M.
/// The upper bound caps the grid's memory (2^(M+1) cells of 48 bytes: 6 MB at 16).
inline constexpr int kMinVoxelHalvings = 0;
inline constexpr int kMaxVoxelHalvings = 16;

}  // namespace polysim::collision
