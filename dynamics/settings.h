#pragma once
// The dynamics' numerical settings, in one place, each with its unit and reason.

namespace polysim::dynamics {

/// Most sweeps of the contact solver over its contacts in one solve, and of each level
/// of its shock propagation. Stacks converge slowest; with block solving a resting
/// 20-box stack takes 45 sweeps a step on average (a cold start takes all of them, the
/// warm-started steps after it few). What 100 sweeps leave, shock propagation settles
/// level by level (shock_propagation.h); at 600 without it a dropped column of 20 cups
/// swayed at 8 cm/s for good, and the tilted pile of 125 took 5.3 s of CPU for 20 s
/// (1.5 s now). At 50 the dominoes (one level: all on the floor) no longer come to rest.
inline constexpr int kMaxSolverIterations = 100;

/// The solver stops once no sweep changes any accumulated impulse by more than this
/// (N s per kg of the lighter body, i.e. m/s). A resting body keeps a residual speed
/// of this order, so it is set where 60 s of rest drift less than a micrometre.
inline constexpr double kSolverVelocityTolerance = 1e-12;

/// How deep (as a fraction of the contact tolerance) a contact may overlap before the
/// solver pushes it back. Deeper contacts are pushed back to this depth over the time to
/// the next detection by split impulses (rigid_body.h), which move poses without adding
/// momentum. Bisection backs up to a state nearly a whole tolerance deep (it brackets the
/// first interpenetrating time); left there, a resting contact sits on the band's edge and
/// the least rocking interpenetrates at once, stalling the step at its start.
inline constexpr double kAllowedOverlapFraction = 0.25;

/// The push solve stops once no sweep changes a push velocity by more than this (m/s).
/// Pushes correct positions at the scale of the tolerance (1e-4 m over a step of 1/60 s is
/// 6e-3 m/s); an error of 1e-9 m/s moves a body by 1e-11 m per step.
inline constexpr double kPushVelocityTolerance = 1e-9;

/// Relative round-off allowed in the small complementarity problems of block solving
/// (small_lcp.h): residuals are judged against this fraction of the problem's largest
/// coefficient. Far above double round-off, far below any physical impulse ratio.
inline constexpr double kLcpRoundOff = 1e-9;

/// Relative round-off allowed when the solver checks that a solve did not raise the
/// bodies' kinetic energy (contact_solver.cpp): far below any physical gain, far above
/// the round-off of summing a pile's energies.
inline constexpr double kEnergyRoundOff = 1e-9;

/// Approach speeds (m/s) below this do not bounce: restitution applies only above it, so
/// a resting body is not kicked by the speed gravity gives it in one step (g dt is
/// 0.04 m/s at 240 Hz and 0.16 m/s at 60 Hz).
inline constexpr double kBounceThreshold = 0.5;

/// A body moving slower than this (m/s, also for angular speed times its size) is
/// reported at rest.
inline constexpr double kRestSpeed = 1e-3;

/// Sleeping (sleep.h): a body is slow while it, and the farthest point of its spin, move
/// slower than kSleepSpeed (m/s); an island whose bodies have all been slow for
/// kTimeToSleep (s) falls asleep. Box2D and Jolt use 0.05 m/s and 0.5 s; polysim's
/// resting contacts settle to far below 1 mm/s, so a body still moving at 1 cm/s is
/// settling, not resting. The price of any speed rule: a body that starts from rest
/// accelerating at less than kSleepSpeed / kTimeToSleep (0.02 m/s^2) sleeps before it is
/// seen moving.
inline constexpr double kSleepSpeed = 1e-2;
inline constexpr double kTimeToSleep = 0.5;

}  // namespace polysim::dynamics
