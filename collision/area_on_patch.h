#pragma once
// One face of object A resting on a flat patch of object B's faces: a box on a floor
// triangulated into thousands of triangles. Clipping the face against each triangle and
// handing every piece to the reduction (contact_reduction.h) costs a contact, a frame and
// a hull per triangle; this keeps the pieces in one frame of the patch's plane and, when
// they cover the whole face, reports the face itself as the one area contact.

#include <vector>

#include "collision/clip.h"
#include "collision/contact.h"
#include "collision/polygon_tests.h"

namespace polysim::collision {

class AreaOnPatch {
 public:
  /// Starts the patch under face p of A (world frame), forgetting the previous one.
  void begin(const PolygonView& p);

  enum class Outcome {
    Area,       // q's overlap with p is a real area within the band: kept as a piece
    Unsettled,  // no area of its own (too thin, or out of the band): see finish()
    OffPatch,   // q is not coplanar with the patch's first face: test it on its own
  };
  /// Adds face q of B, facing p. The patch's plane is the first added face's; q joins
  /// when its normal is within kFlatEdgeAngle of it and its vertices within
  /// kPlanarityTolerance (m) of it. Area follows areaContact's rule (polygon_tests.h):
  /// the overlap, seen along the patch's normal, is wider than eps/2 and has every
  /// corner within eps (m) of p's plane.
  Outcome add(const PolygonView& q, double eps);

  /// Appends the patch's area contacts (normal from B towards A) and returns whether the
  /// pieces cover p (up to kCoverRoundOff of its area). Covered, the contact is p itself
  /// seen on the patch, and whatever the Unsettled faces have within eps of p lies on it:
  /// they add nothing. Otherwise every piece is appended, for the reduction to merge,
  /// and the Unsettled faces must be tested on their own. Each corner has its own gap.
  /// The contacts are built in `scratch`'s spare buffers (makeContact).
  bool finish(std::vector<Contact>& out, PolygonScratch& scratch) const;
  /// The faces that add() found Unsettled, in the order added.
  const std::vector<int>& unsettled() const { return unsettled_; }

 private:
  // Where x (2D, patch frame) meets the plane of a face within kPlanarityTolerance of the
  // patch, moved halfway to p's plane: a corner of the contact polygon.
  Eigen::Vector3d contactCorner(const Eigen::Vector2d& x, double& gap) const;
  // Clips q2_ to p2_ into piece_; true when the piece is an area (add()'s rule), with its
  // area (m^2).
  bool isArea(double eps, double& area);

  PolygonView p_;
  PlaneFrame frame_{Eigen::Vector3d::Zero(), Eigen::Vector3d::UnitZ()};
  bool started_ = false;
  double along_ = 1.0;                   // -p.normal . patch normal: gap along the patch normal per unit distance along p's
  Polygon2 p2_;                          // p seen on the patch, counter-clockwise about the patch normal
  double perimeterP_ = 0.0;              // of p2_
  Polygon2 q2_, piece_, work_;           // scratch
  std::vector<Eigen::Vector2d> corners_;  // every piece's corners, piece after piece
  std::vector<int> pieceEnd_;             // one past each piece's last corner
  std::vector<double> pieceArea_;
  std::vector<int> unsettled_;
  int firstFace_ = -1;
};

}  // namespace polysim::collision
