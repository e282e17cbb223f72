#include "dynamics/shock_propagation.h"

#include <algorithm>
#include <utility>

#include "dynamics/buckets.h"
#include "dynamics/contact_sweeps.h"
#include "dynamics/settings.h"
#include "dynamics/solve_bodies.h"

namespace polysim::dynamics::solver {
namespace {

constexpr int kUnranked = -1;

// Each body's level, by its number in `bodies`: 0 for a static body in the rows, 1 + the
// lowest level among the bodies it rests on for a moving one (breadth first), kUnranked
// if it rests on nothing that reaches a static body. A row links the body below to the
// one above when its normal (from b towards a) leans up or down by kSupportCosine;
// without gravity (`up` zero) every row links both ways. Rows with restitution do not
// link.
std::vector<int> levelsOf(const std::vector<Row>& rows, const SolveBodies& bodies, const Eigen::Vector3d& up) {
  const size_t count = static_cast<size_t>(bodies.count());
  std::vector<int> below, above;  // each link's body below and body above it
  std::vector<int> level(count, kUnranked), queue;  // queue: breadth first, taken from `next`
  const bool anyWay = up.isZero(0.0);
  const auto link = [&](int from, int to) { below.push_back(from), above.push_back(to); };
  for (size_t k = 0; k < rows.size(); ++k) {
    const Row& r = rows[k];
    if (r.restitution > 0) continue;
    const int a = bodies.a(k), b = bodies.b(k);
    const double rise = r.normal.dot(up);  // > 0: a rests on b
    if (anyWay || rise >= kSupportCosine) link(b, a);
    if (anyWay || rise <= -kSupportCosine) link(a, b);
    for (const auto& [i, body] : {std::pair{a, r.a}, std::pair{b, r.b}})
      if (body->isStatic && level[i] == kUnranked) level[i] = 0, queue.push_back(i);
  }
  const Buckets linksFrom(static_cast<int>(count), below);  // each body's links up, in the rows' order
  for (size_t next = 0; next < queue.size(); ++next) {
    const int i = queue[next];
    for (const int* l = linksFrom.begin(i); l != linksFrom.end(i); ++l)
      if (const int j = above[static_cast<size_t>(*l)]; level[j] == kUnranked) level[j] = level[i] + 1, queue.push_back(j);
  }
  return level;
}

}  // namespace

void forEachLevel(const std::vector<Row>& rows, const SolveBodies& bodies, const Eigen::Vector3d& up,
                  const std::function<void(std::vector<Row>& sub, const std::vector<int>& picked)>& solveLevel) {
  const std::vector<int> level = levelsOf(rows, bodies, up);
  std::vector<int> levelOfRow(rows.size(), kUnranked);  // a row's level: its upper body's
  int levelCount = 0;
  for (size_t k = 0; k < rows.size(); ++k) {
    const int la = level[bodies.a(k)], lb = level[bodies.b(k)];
    if (rows[k].restitution > 0 || la == kUnranked || lb == kUnranked) continue;
    levelOfRow[k] = std::max(la, lb);
    levelCount = std::max(levelCount, levelOfRow[k] + 1);
  }
  const Buckets rowsOfLevel(levelCount, levelOfRow);
  for (int L = 1; L < levelCount; ++L) {
    if (rowsOfLevel.empty(L)) continue;
    const std::vector<int> picked(rowsOfLevel.begin(L), rowsOfLevel.end(L));
    // Each lower body a row of the level touches, copied once and marked static; the
    // rows point at the copies once all are made (the vector may move them till then).
    std::vector<RigidBody> fixed;
    std::vector<int> fixedOf(static_cast<size_t>(bodies.count()), -1);  // by body number: its copy in `fixed`
    std::vector<std::pair<int, int>> heldEnds;  // each row's a and b: its copy in `fixed`, or -1
    heldEnds.reserve(picked.size());
    auto heldFixed = [&](int number, const RigidBody* body) {
      if (body->isStatic || level[number] >= L) return -1;
      int& held = fixedOf[static_cast<size_t>(number)];
      if (held < 0) {
        held = static_cast<int>(fixed.size());
        RigidBody& copy = fixed.emplace_back(*body);
        copy.isStatic = true;
        copy.inverseMass = 0.0;
      }
      return held;
    };
    for (int k : picked) heldEnds.emplace_back(heldFixed(bodies.a(k), rows[k].a), heldFixed(bodies.b(k), rows[k].b));
    std::vector<Row> sub;
    sub.reserve(picked.size());
    for (size_t i = 0; i < picked.size(); ++i) {
      Row r = rows[picked[i]];
      if (heldEnds[i].first >= 0) r.a = &fixed[heldEnds[i].first];
      if (heldEnds[i].second >= 0) r.b = &fixed[heldEnds[i].second];
      prepareAxes(r);
      sub.push_back(r);
    }
    solveLevel(sub, picked);
  }
}

SolveStats propagateShock(std::vector<Row>& rows, const SolveBodies& bodies, int maxSweeps, const Eigen::Vector3d& up) {
  SolveStats stats;
  forEachLevel(rows, bodies, up, [&](std::vector<Row>& sub, const std::vector<int>& picked) {
    const SolveStats swept = ContactSweeps(sub).run(sub, maxSweeps);
    stats.iterations += swept.iterations;
    stats.rowSolves += swept.rowSolves;
    for (size_t i = 0; i < picked.size(); ++i) {
      rows[picked[i]].normalImpulse = sub[i].normalImpulse;
      rows[picked[i]].frictionImpulse = sub[i].frictionImpulse;
    }
  });
  return stats;
}

}  // namespace polysim::dynamics::solver
