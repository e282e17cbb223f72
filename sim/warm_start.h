#pragma once
// Warm starting a step's contact solve from the last step's: each new contact point
// starts from the force an old point of the same pair had at (nearly) the same place.

#include <vector>

#include "dynamics/contact_solver.h"

namespace polysim::sim {

/// A contact point is taken for last solve's point of the same pair when it lies within
/// this distance (m) of it; it then starts from that point's force (warm start). Resting
/// contacts reappear at the same place to round-off; 1 mm is far from both. At 1 cm, a
/// point sliding or swaying up to 60 cm/s keeps its force too, but the tilted piles of
/// 1000 rested worse (seeds 1 to 7 and 11, 20 s: 7,599 against 7,931 boxes at rest).
inline constexpr double kWarmStartRadius = 1e-3;

/// Sets each of `points`' impulses (N s over `horizon` s) from the force (N) of the first
/// point of `lastSolved` of the same pair of bodies within kWarmStartRadius whose normal
/// faces the same way; points with none keep theirs. A pair is the same whichever of its
/// bodies is `a`: the order a pair comes in may change between steps (a body still at
/// one step's start and moving at the next is tested the other way round), and with it
/// the normal's sign and the friction's (the impulse on `a`); the normal impulse is the
/// same.
void warmStartFromLastSolve(const std::vector<dynamics::ContactPoint>& lastSolved, std::vector<dynamics::ContactPoint>& points,
                            double horizon);

}  // namespace polysim::sim
