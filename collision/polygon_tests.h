#pragma once
// The polygon-level test of the intersection module: one convex polygon of object A
// against one of object B, both in the world frame, judged with the contact tolerance.

#include <vector>

#include "collision/clip.h"
#include "collision/contact.h"
#include "collision/polygon_mesh.h"

namespace polysim::collision {

/// One face of an object placed in the world frame, with the ids of its features.
struct PolygonView {
  const Eigen::Vector3d* vertices = nullptr;     // world, counter-clockwise about plane.normal
  const Eigen::Vector3d* edgeOutward = nullptr;  // world; edge i runs from vertex i to i+1
  const Eigen::Vector3d* sideNormal = nullptr;   // world, unit, in the plane, out of the polygon across side i
  const int* vertexIds = nullptr;                // mesh vertex of each corner
  const int* edgeIds = nullptr;                  // mesh edge of each side
  const char* edgeFlat = nullptr;                // side i is a flat internal edge (no boundary)
  const char* convexSide = nullptr;              // side i is a convex crease (PolygonMesh::convexCreaseSides)
  bool anyConvexSide = false;                    // some side is (a floor's triangle has none)
  int size = 0;
  Plane plane;                                   // world, normal out of the object
  int faceId = -1;
};

/// Scratch buffers reused between calls, so that the hot loop does not allocate.
struct PolygonScratch {
  std::vector<double> dP, dQ;
  std::vector<Eigen::Vector3d> clipA, clipB;
  std::vector<std::pair<Eigen::Vector3d, double>> wedge;       // planes bounding an object near a face
  Polygon2 p2, q2, overlap, clipWork;
  std::vector<std::pair<double, double>> lines;  // depth along a cut, per sharp edge
  std::vector<Contact> discard;                  // contacts found when none are wanted
  std::vector<char> onLine;                      // per vertex of a polygon: ends a line contact
  // Emptied contacts whose point buffers the next contacts reuse: a pile's detection
  // builds millions of contacts of a few points, each two allocations when new.
  std::vector<Contact> spare;
};

/// Most emptied contacts PolygonScratch::spare keeps. Every contact recycled into it
/// should have been built from it (makeContact); one that was not (AreaOnPatch::finish
/// built its own, once) makes the pool grow for good: a refilled pile's resident memory
/// rose by 1.8 MB every 1000 steps (polysim_soak, 8000 steps: 11 to 25 MB). The bound
/// keeps any such imbalance finite; one pair's test builds far fewer.
inline constexpr size_t kMaxSpareContacts = 256;

/// A contact without points yet (Contact::addPoint adds them with their gaps), built in a
/// spare one's buffers when there is one (recycleContacts).
Contact makeContact(PolygonScratch& s, ContactType type, const Eigen::Vector3d& normal, Feature a, Feature b);

/// Empties `contacts`, keeping the buffers of up to kMaxSpareContacts of them in `s` for
/// the contacts testPolygonPair builds next.
void recycleContacts(std::vector<Contact>& contacts, PolygonScratch& s);

/// The verdict for one polygon pair.
struct PolygonPairOutcome {
  Status status = Status::Separate;
  /// For Interpenetrating, how far (m) one polygon goes inside the other's object.
  double depth = 0.0;
  /// For Contact, the pair is face on face (its contact is an area).
  bool area = false;
};

class AreaCover;
class AreaOnPatch;

/// Whether testPolygonPair judges interpenetration itself, or the caller already has
/// (convex objects, by their penetration depth; see testObjectPair) and wants contacts only.
enum class DepthVerdict { Judged, DecidedByCaller };

/// Tests polygon p (of object A) against q (of object B) with contact tolerance eps (m).
///
/// Interpenetrating: p reaches more than eps behind q, measured as the smaller of (1) how
/// far p goes behind q's plane inside q's prism, within the wedge of q's convex creases
/// (crease_depth.h), and (2) how far p's cut through q's plane lies inside q, from q's
/// boundary edges that are not flat (and the same for q into p); or a convex crease of p
/// crosses one of q more than eps deep along their common normal.
/// Contact: not interpenetrating, and some feature pair is within eps. Touching counts
/// as contact. When `contacts` is non-null and the pair is in contact, its contacts
/// (area, lines, points; normal from B towards A) are appended, possibly with
/// duplicates that the caller merges (see contact_reduction.h). When `cover` says an
/// area contact already found holds whatever the pair would add, nothing is appended
/// and the pair counts as in contact. When `patch` is given (begun on p, and `contacts`
/// non-null), a facing pair that is not interpenetrating goes to the patch instead: its
/// area joins the patch's pieces, or it is left unsettled (area_on_patch.h) and counts
/// as separate until the caller settles it. With DepthVerdict::DecidedByCaller the pair
/// is never Interpenetrating: the features within eps are its contacts however deep the
/// polygons' own measure finds them.
PolygonPairOutcome testPolygonPair(const PolygonView& p, const PolygonView& q, double eps,
                                   std::vector<Contact>* contacts, PolygonScratch& scratch,
                                   const AreaCover* cover = nullptr, AreaOnPatch* patch = nullptr,
                                   DepthVerdict verdict = DepthVerdict::Judged);

/// How far (m) p goes inside q's object or q inside p's, measured as in testPolygonPair
/// (0 when neither goes behind the other); not compared with any tolerance.
double penetrationDepth(const PolygonView& p, const PolygonView& q, double eps, PolygonScratch& scratch);

}  // namespace polysim::collision
