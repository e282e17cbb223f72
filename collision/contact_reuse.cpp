#include "collision/contact_reuse.h"

#include <algorithm>
#include <functional>
#include <limits>

#include "collision/tolerances.h"

namespace polysim::collision {
namespace {

// b's frame relative to the world and a's pose in b's frame.
Eigen::Isometry3d relativePose(const ObjNode& A, const ObjNode& B) { return B.X_WO.inverse() * A.X_WO; }

// A bound on how far any point of a (within `reach` of its origin) moved relative to b
// between two relative poses: |t - t0| + |(R - R0) p| <= |t - t0| + ||R - R0||_F |p|.
// The Frobenius norm, not an angle: acos near 1 loses half the digits.
double displacementBound(const Eigen::Isometry3d& now, const Eigen::Isometry3d& then, double reach) {
  return (now.translation() - then.translation()).norm() + (now.linear() - then.linear()).norm() * reach;
}

// `out` becomes contact c carried by the rigid motion X (out's buffers reused).
void carry(const Contact& c, const Eigen::Isometry3d& X, Contact& out) {
  out = c;
  out.normal = X.linear() * c.normal;
  for (Eigen::Vector3d& p : out.points) p = X * p;
}

}  // namespace

size_t ContactReuse::KeyHash::operator()(const Key& k) const {
  const size_t h = std::hash<long long>()((static_cast<long long>(k.a) << 32) ^ static_cast<unsigned>(k.b));
  return h ^ (std::hash<double>()(k.tolerance) * 31);
}

std::optional<PairResult> ContactReuse::find(const ObjectDatabase& db, int a, int b) {
  const ObjNode& A = db.objects[a];
  const ObjNode& B = db.objects[b];
  if (!enabled_ || A.id < 0 || B.id < 0) return std::nullopt;
  const auto found = results_.find({A.id, B.id, db.tolerance});
  if (found == results_.end()) return std::nullopt;
  Kept& k = found->second;
  if (k.meshA != A.mesh.get() || k.meshB != B.mesh.get()) return std::nullopt;
  const double drift = displacementBound(relativePose(A, B), k.X_BA, k.reachA);
  const double eps = db.tolerance;
  if (!(drift <= kContactReuseFraction * eps)) return std::nullopt;
  // The separation and every gap moved by at most `drift`: the pair stays short of
  // interpenetrating and some feature stays inside the band, so it is still in contact.
  double deepest = std::numeric_limits<double>::infinity();
  for (const Contact& c : k.contacts) deepest = std::min(deepest, c.separation);
  if (!(k.separation - drift > -eps && deepest + drift <= eps)) return std::nullopt;
  k.usedAt = query_;
  ++reused_;
  PairResult pair;
  pair.a = a;
  pair.b = b;
  pair.status = Status::Contact;
  pair.contacts.resize(k.contacts.size());
  for (size_t i = 0; i < k.contacts.size(); ++i) carry(k.contacts[i], B.X_WO, pair.contacts[i]);
  return pair;
}

void ContactReuse::keep(const ObjectDatabase& db, const PairResult& pair, const std::optional<double>& separation) {
  const ObjNode& A = db.objects[pair.a];
  const ObjNode& B = db.objects[pair.b];
  if (!enabled_ || A.id < 0 || B.id < 0 || pair.status != Status::Contact || pair.contacts.empty() || !separation) return;
  // A pair kept before is overwritten in place: its contacts' buffers serve again, where
  // a fresh entry allocated every point list of a settling pile's pairs at every test.
  Kept& k = results_[Key{A.id, B.id, db.tolerance}];
  k.separation = *separation;
  k.meshA = A.mesh.get();
  k.meshB = B.mesh.get();
  k.X_BA = relativePose(A, B);
  k.reachA = 0.0;
  for (const Eigen::Vector3d& v : A.mesh->vertices()) k.reachA = std::max(k.reachA, v.norm());
  const Eigen::Isometry3d X_BW = B.X_WO.inverse();
  k.contacts.resize(pair.contacts.size());
  for (size_t i = 0; i < pair.contacts.size(); ++i) carry(pair.contacts[i], X_BW, k.contacts[i]);
  k.usedAt = query_;
}

void ContactReuse::endQuery() {
  if (!enabled_) return;
  ++query_;
  if (query_ % kStaleQueries != 0) return;
  for (auto it = results_.begin(); it != results_.end();)
    it = query_ - it->second.usedAt > kStaleQueries ? results_.erase(it) : std::next(it);
}

}  // namespace polysim::collision
