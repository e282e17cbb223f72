#include "dynamics/shock_propagation.h"

#include <algorithm>
#include <deque>

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
  std::vector<std::vector<int>> above(static_cast<size_t>(bodies.count()));  // the bodies each one holds up
  std::vector<int> level(static_cast<size_t>(bodies.count()), kUnranked);
  std::deque<int> queue;
  const bool anyWay = up.isZero(0.0);
  for (size_t k = 0; k < rows.size(); ++k) {
    const Row& r = rows[k];
    if (r.restitution > 0) continue;
    const int a = bodies.a(k), b = bodies.b(k);
    const double rise = r.normal.dot(up);  // > 0: a rests on b
    if (anyWay || rise >= kSupportCosine) above[b].push_back(a);
    if (anyWay || rise <= -kSupportCosine) above[a].push_back(b);
    for (const auto& [i, body] : {std::pair{a, r.a}, std::pair{b, r.b}})
      if (body->isStatic && level[i] == kUnranked) level[i] = 0, queue.push_back(i);
  }
  while (!queue.empty()) {
    const int i = queue.front();
    queue.pop_front();
    for (int j : above[i])
      if (level[j] == kUnranked) level[j] = level[i] + 1, queue.push_back(j);
  }
  return level;
}

}  // namespace

void forEachLevel(const std::vector<Row>& rows, const SolveBodies& bodies, const Eigen::Vector3d& up,
                  const std::function<void(std::vector<Row>& sub, const std::vector<int>& picked)>& solveLevel) {
  const std::vector<int> level = levelsOf(rows, bodies, up);
  std::vector<std::vector<int>> rowsOfLevel;
  for (size_t k = 0; k < rows.size(); ++k) {
    const Row& r = rows[k];
    const int la = level[bodies.a(k)], lb = level[bodies.b(k)];
    if (r.restitution > 0 || la == kUnranked || lb == kUnranked) continue;
    const size_t top = static_cast<size_t>(std::max(la, lb));
    if (rowsOfLevel.size() <= top) rowsOfLevel.resize(top + 1);
    rowsOfLevel[top].push_back(static_cast<int>(k));
  }
  for (size_t L = 1; L < rowsOfLevel.size(); ++L) {
    const std::vector<int>& picked = rowsOfLevel[L];
    if (picked.empty()) continue;
    std::deque<RigidBody> fixed;  // stable addresses
    std::vector<RigidBody*> fixedOf(static_cast<size_t>(bodies.count()), nullptr);  // by body number
    auto heldFixed = [&](int number, RigidBody* body) {
      RigidBody*& held = fixedOf[static_cast<size_t>(number)];
      if (!held) {
        held = &fixed.emplace_back(*body);
        held->isStatic = true;
        held->inverseMass = 0.0;
      }
      return held;
    };
    std::vector<Row> sub;
    sub.reserve(picked.size());
    for (int k : picked) {
      Row r = rows[k];
      if (!r.a->isStatic && level[bodies.a(k)] < static_cast<int>(L)) r.a = heldFixed(bodies.a(k), r.a);
      if (!r.b->isStatic && level[bodies.b(k)] < static_cast<int>(L)) r.b = heldFixed(bodies.b(k), r.b);
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
