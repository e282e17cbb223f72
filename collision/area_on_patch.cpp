#include "collision/area_on_patch.h"

#include <cmath>

#include "collision/tolerances.h"

namespace polysim::collision {

void AreaOnPatch::begin(const PolygonView& p) {
  p_ = p;
  started_ = false;
  corners_.clear();
  pieceEnd_.clear();
  pieceArea_.clear();
  unsettled_.clear();
  firstFace_ = -1;
}

Eigen::Vector3d AreaOnPatch::contactCorner(const Eigen::Vector2d& x, double& gap) const {
  const Eigen::Vector3d onPatch = frame_.to3d(x);
  gap = p_.plane.signedDistance(onPatch) / along_;
  return onPatch + (0.5 * gap) * frame_.normal;
}

AreaOnPatch::Outcome AreaOnPatch::add(const PolygonView& q, double eps) {
  if (!started_) {
    frame_ = PlaneFrame(q.vertices[0], q.plane.normal);
    along_ = -p_.plane.normal.dot(q.plane.normal);
    p2_.resize(p_.size);
    for (int k = 0; k < p_.size; ++k) p2_[p_.size - 1 - k] = frame_.to2d(p_.vertices[k]);  // reversed: CCW about the patch normal
    perimeterP_ = perimeter(p2_);
    started_ = true;
  } else if (q.plane.normal.dot(frame_.normal) < std::cos(kFlatEdgeAngle)) {
    return Outcome::OffPatch;
  }
  q2_.resize(q.size);
  for (int k = 0; k < q.size; ++k) {
    if (std::abs(frame_.normal.dot(q.vertices[k] - frame_.origin)) > kPlanarityTolerance) return Outcome::OffPatch;
    q2_[k] = frame_.to2d(q.vertices[k]);
  }
  double area = 0.0;
  if (!isArea(eps, area)) {
    unsettled_.push_back(q.faceId);
    return Outcome::Unsettled;
  }
  if (firstFace_ < 0) firstFace_ = q.faceId;
  corners_.insert(corners_.end(), piece_.begin(), piece_.end());
  pieceEnd_.push_back(static_cast<int>(corners_.size()));
  pieceArea_.push_back(area);
  return Outcome::Area;
}

bool AreaOnPatch::isArea(double eps, double& area) {
  clipConvex(q2_, p2_, piece_, work_);
  if (piece_.size() < 3) return false;
  // A piece is a convex part of p, so its perimeter is at most p's: most pieces are
  // judged without measuring their own.
  area = signedArea(piece_);
  if (area <= 0.5 * eps * perimeterP_ && area <= 0.5 * eps * perimeter(piece_)) return false;
  for (const Eigen::Vector2d& x : piece_) {
    double gap = 0.0;
    contactCorner(x, gap);
    if (std::abs(gap) > eps) return false;
  }
  return true;
}

bool AreaOnPatch::finish(std::vector<Contact>& out, PolygonScratch& scratch) const {
  if (pieceEnd_.empty()) return false;
  double areaSum = 0.0;
  for (double a : pieceArea_) areaSum += a;
  auto emit = [&](const Eigen::Vector2d* first, const Eigen::Vector2d* last) {
    Contact c = makeContact(scratch, ContactType::Area, frame_.normal, {Feature::Kind::Face, p_.faceId},
                            {Feature::Kind::Face, firstFace_});
    c.points.reserve(static_cast<size_t>(last - first));
    for (const Eigen::Vector2d* x = first; x != last; ++x) {
      double gap = 0.0;
      const Eigen::Vector3d corner = contactCorner(*x, gap);
      c.addPoint(corner, gap);
    }
    out.push_back(std::move(c));
  };
  // The pieces are disjoint parts of p (faces of one mesh do not overlap), so they cover
  // p exactly when their areas add up to p's; each corner of p is then a corner of some
  // piece, already checked to lie within the band.
  if (areaSum >= (1.0 - kCoverRoundOff) * signedArea(p2_)) {
    emit(p2_.data(), p2_.data() + p2_.size());
    return true;
  }
  int begin = 0;
  for (size_t i = 0; i < pieceEnd_.size(); ++i) {
    emit(corners_.data() + begin, corners_.data() + pieceEnd_[i]);
    begin = pieceEnd_[i];
  }
  return false;
}

}  // namespace polysim::collision
