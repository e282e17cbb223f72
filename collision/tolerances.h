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

/// Largest angle (rad) between two faces' opposed normals for them to be tried as
/// face-on-face; whether they are is then decided where they overlap (every corner of
/// the overlap within the contact tolerance of both planes). 0.01 rad lets a 1 cm face
/// tilt by the whole default tolerance.
inline constexpr double kFaceContactAngle = 1e-2;

/// Fraction of a face's area by which the area pieces found under it (one per face of a
/// flat patch, area_on_patch.h) may fall short of it and still cover it: round-off of
/// clipping the face into pieces, far below a missing strip of any width that matters.
/// A real shortfall (the face overhangs the patch) leaves the pieces to be merged exactly.
inline constexpr double kCoverRoundOff = 1e-9;

/// How far (rad) a contact normal may lie outside a feature's normal cone (the face's
/// normal; the wedge between an edge's faces; the cone among a vertex's faces) and still
/// count as a way to touch that feature. Covers round-off and the tilts the contact band
/// allows (a 1 m face tilted by a 1e-4 m tolerance is 1e-4 rad), with margin.
inline constexpr double kNormalConeSlack = 1e-3;

/// Contact reuse (contact_reuse.h): a pair keeps its last full test's contacts while no
/// point of one object has moved relative to the other by more than this fraction of the
/// contact tolerance (0.1 um at the default). A reused gap is then within that distance
/// of a fresh test's, a thousandth of the band: far below what the solver's allowed
/// overlap (a quarter of the band) or any reported figure resolves. Bodies at rest move
/// far less (a resting pyramid of 210 boxes: 5e-12 m in half a second); settling ones
/// far more (millimetres a step), so the exact size hardly changes what is reused.
inline constexpr double kContactReuseFraction = 1e-3;

/// Bounds on the number of times the voxel grid halves an object's container (M).
/// Garcia-Alonso et al. found 8 or 9 best for their meshes; polysim picks M so that the
/// surface crosses each leaf voxel with about kFacesPerVoxel faces
/// (VoxelGrid::chooseHalvings): a box needs none, a 20480-triangle sphere 10, a 10 m
/// floor of 20000 triangles 8. The benchmark in tests/bench sweeps M.
/// The upper bound caps the grid's memory (2^(M+1) cells of 48 bytes: 6 MB at 16).
inline constexpr int kMinVoxelHalvings = 0;
inline constexpr int kMaxVoxelHalvings = 16;

/// Faces a leaf voxel should hold. Measured on the issue-2 benchmarks: a box on a
/// triangulated floor wants coarse voxels (many faces each: the contact patch covers
/// hundreds of faces and fine voxels list each face several times), the tip of one
/// sphere in another wants finer ones. 32 gives the best M measured for both the
/// 20480-triangle sphere (M 10: 6.5 us where 16 faces, M 12, took 14.6 us) and the
/// 20000-triangle floor (M 8); 64 was 50% slower on the floors (see the note of issue 2
/// and tests/bench/intersection_bench.cpp).
inline constexpr double kFacesPerVoxel = 32.0;

/// Most distinct face normals (and, separately, edge directions) a convex mesh may have
/// for the separating axis test to measure its separation (convex_separation.h): the
/// test tries every face normal and every cross product of two edge directions, so two
/// meshes at the limit cost 2 * 16 + 16 * 16 axes. A box has 3 and 3, a hexagonal prism 4
/// and 4; curved shapes go over and are measured polygon by polygon instead.
inline constexpr int kMaxSeparatingDirections = 16;

/// How deep (in contact tolerances) two crossing creases of objects that are not convex
/// are measured (crease_depth.cpp): a crossing beyond eps is interpenetration, and one
/// this deep is always seen as such. Far deeper, the closest points of two creases may
/// lie on parts of the objects far apart (a cup's rim edge and the bottom edge of the cup
/// under it), whose "crossing" says nothing; a real overlap that deep is seen by the
/// polygons' own measure.
inline constexpr double kCrossingReach = 16.0;

/// collisionDetect() stops refining the time of contact when the bracket is narrower
/// than this fraction of the interval: far below any physical time scale of a step,
/// well above the round-off of t in [0, 1].
inline constexpr double kTimeTolerance = 1e-9;

/// The regula-falsi method stops once the signed separation is within this fraction of
/// the contact tolerance (and the state is not interpenetrating): close enough to the
/// exact touching time that the time error is this distance over the approach speed.
inline constexpr double kRootDistanceFraction = 1e-3;

/// How far (in contact tolerances) regula falsi measures separations; beyond it a
/// distance is only known to be large, and a bisection step is taken instead. Small, so
/// that measuring touches only the polygons near the contact.
inline constexpr double kSeparationReach = 64.0;

/// Most guesses (each a test or a separation measure) a root finder of collisionDetect()
/// may make while refining a bracket, a guard against non-convergence (bisection needs
/// log2(1/kTimeTolerance) = 30). The scan of the sub-intervals before it is not counted.
inline constexpr int kMaxTimeOfContactIterations = 100;

/// Between two tests, no point may move (relative to the other object) more than this
/// fraction of the thinner object's thickness, so that nothing passes through unseen.
inline constexpr double kTunnelingSafety = 0.5;

/// collisionDetect() leaves out of its verdict-only tests a convex pair whose separation
/// at the interval's start, less the motion both may make in it, stays above minus the
/// tolerance by at least this fraction of it (it cannot interpenetrate anywhere in the
/// interval: the separation moves by no more than the motion). Far above the round-off
/// of the separating axis test, far below the quarter band the solver lets pairs sink.
inline constexpr double kUnwatchedMarginFraction = 1e-3;

/// Most sub-intervals collisionDetect() splits an interval into against tunnelling;
/// beyond it the no-tunnelling guarantee is not kept (the result says so).
inline constexpr int kMaxSubintervals = 4096;

/// The inside test of containment (containment.h) casts a ray and counts the faces it
/// crosses; a crossing within this fraction of the face's size of the face's rim is
/// ambiguous (the ray may cross two faces at their shared edge, or graze a vertex), and
/// the ray is cast again in another direction. Far above round-off, far below any face.
inline constexpr double kGrazingFraction = 1e-9;

}  // namespace polysim::collision
