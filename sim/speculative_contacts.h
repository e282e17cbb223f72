#pragma once
// Speculative contacts (Catto, "Physics for game programmers: continuous collision",
// GDC 2013; Box2D v3 and Jolt use them): features that are apart but close enough to
// touch within the step go to the contact solver with their gap, and it lets each such
// point close by its gap and no more. A box rocking onto its next corner, a domino
// leaning onto its neighbour or a settling pile then reach their new contacts without a
// back-up each: collisionDetect() still backs up whatever interpenetrates anyway (an
// impact of a body flying free, a turn the straight-line view of the solver missed), so
// committed states keep the seed's guarantee; speculative contacts only make that rarer.

#include <functional>
#include <vector>

#include "collision/intersection.h"

namespace polysim::sim {

/// How far apart (m) two features may be and still be given to the solver as a
/// speculative contact. Box2D v3 uses 4 linear slops (2 cm). Wider, more rocking and
/// settling is caught (a box turning at 2 rad/s sweeps its corner 3 cm in a step of
/// 1/60 s); but a gap that wide may also be a feature the body would pass by (a ghost
/// contact, which stops it short), and the pyramids' boxes stand 5 cm apart. Measured on
/// the first 2 s of a tilted pile of 343 boxes, one build: 1,923 contact events at 2 cm,
/// 2,347 at 5 cm, 2,930 at 10 cm (6,278 without, in an earlier one).
inline constexpr double kSpeculativeReach = 0.02;

/// What an object of the database is to the speculative test.
enum class SpeculativeRole {
  Left,    // not tested at all
  Still,   // tested against moving objects only, as if static (a body at rest)
  Moving,  // tested against every object not left
};

/// The pairs of `db`'s objects found within `reach` (m) of each other at their current
/// poses, as `roleOf(object index)` says, with the contacts the test found in that band
/// (body indices, by `bodyOf`; empty: the same). `onlyOf`, when given (per body): only
/// the pairs with a body it marks are tested, each exactly as the whole test would.
std::vector<collision::PairResult> speculativePairs(const collision::ObjectDatabase& db,
                                                    collision::IntersectionWorkspace& workspace, double reach,
                                                    const std::vector<int>& bodyOf,
                                                    const std::function<SpeculativeRole(int)>& roleOf,
                                                    const std::vector<char>* onlyOf = nullptr);

/// The solver's contacts from `found` (speculativePairs(), body indices) and `touching`
/// (the pairs in contact within `tolerance` (m), body indices): every pair of `found` in
/// contact that `speculate` accepts gets the contacts found so (those within the
/// tolerance as before, plus the features that may touch within the step, each with its
/// own gap; a pair not in `touching` has none below `tolerance`, as the detector found it
/// apart). `touching` are all returned: with the widened contacts where found and
/// accepted (plus each of their own contacts whose normal no widened contact shares: the
/// detector's verdict is the one a step keeps), else as they are.
std::vector<collision::PairResult> mergeSpeculative(const std::vector<collision::PairResult>& found,
                                                    const std::vector<collision::PairResult>& touching, double tolerance,
                                                    const std::function<bool(const collision::PairResult&)>& speculate);

/// The solver's contacts for a step or for what remains of it after an event:
/// mergeSpeculative() of speculativePairs() (`reach`, `roleOf`) and `touching`, with the
/// database's tolerance.
std::vector<collision::PairResult> withSpeculativeContacts(
    const collision::ObjectDatabase& db, collision::IntersectionWorkspace& workspace, double reach,
    const std::vector<int>& bodyOf, const std::vector<collision::PairResult>& touching,
    const std::function<SpeculativeRole(int)>& roleOf, const std::function<bool(const collision::PairResult&)>& speculate);

}  // namespace polysim::sim
