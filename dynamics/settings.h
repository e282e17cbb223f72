#pragma once
// The dynamics' numerical settings, in one place, each with its unit and reason.

namespace polysim::dynamics {

/// Most sweeps of the contact solver over a moving group of contacts in one solve (see
/// kSettlingSolverSweeps for one nearly at rest), and of each level of its shock
/// propagation. Stacks converge slowest; with block solving a resting
/// 20-box stack takes a few sweeps a step once warm-started. What the sweeps leave, shock
/// propagation settles level by level (shock_propagation.h), and its impulses warm-start
/// the next step; a resting pyramid's sweeps end at this limit every step, so sweeps
/// beyond it buy nothing that pass does not. Measured in one run each, 60 against 100:
/// the pyramid of 820 boxes 2.7 against 3.5 ms a step (every box within 1e-7 m of its
/// start in 10 s), the tilted pile of 125 0.54 against 0.79 ms, the 1000-box pile's first
/// 10 s 133 against 209 ms, and no energy gained by columns of 20 frictionless cups
/// (seeds 1 to 8, 8 s). At 40 a frictionless cup column broke the energy bound and the
/// resting 20-box stack needed shock propagation; at 30 the pyramid of 820 leaned 1.9 cm.
/// Stopping only moving groups sooner (some contact faster than kSettlingSpeed, not all
/// bodies rested; resting and settling groups as now) was measured and not kept: piles of
/// 1000, seeds 1 to 4, 10 s, side by side, 58.4 s of CPU at 60, 53.8 at 50, 49.2 at 40
/// (all at rest, no energy gained); but at 30 the wedged box (FailureModes) gained
/// 0.011 J and frictionless cup columns (seed 2) reached the event bound, and at 20 a
/// corner tower box never rested as well. A 16% saving 10 sweeps from a failure.
inline constexpr int kMaxSolverIterations = 60;

/// A solve's sweep limit unless the scene sets `solver_sweeps` (which bounds every solve).
/// Only a settling group uses more than kMaxSolverIterations of it: one still unconverged
/// there while no contact's bodies move apart faster than kSettlingSpeed (m/s, at the
/// point). Columns of ten boxes side by side, bridged by a top box, stopped at 60 sweeps a
/// step with boxes at 1 to 3 cm/s and never came to rest (pile of 1000, seed 2: 40 boxes
/// moving at 20 s); swept on, they rest within a second and sleep. A fast group (a landing
/// pile) stops at kMaxSolverIterations: its answer is overturned by the next impact
/// anyway, and its solves are most of the cost. Piles of 1000, seeds 1 to 12, 20 s, side
/// by side in one run: at 200 all 12,000 boxes at rest, the last pile by 9.1 s, 610 s of
/// CPU, 18 steps at the event bound; at 600 all by 11.0 s, 700 s, 17 (at 60: 11,937 at
/// rest). Piles of 343 (seeds 1 to 3, 12 s) cost 15.5 s at 200 against 24.8 s at 600.
/// A resting stack's solves need more now and then: warm-started, each stops after a
/// sweep or two while an error below the tolerance builds up, until one step it shows
/// and the whole column converges again (the 20-box stack, sleeping off: 93 sweeps once
/// in 240 steps at 200; at 250 one solve of 250 ended unconverged and went on to shock
/// propagation, which BusyScenes.RestingStackOf20TakesAFewSweepsAStep forbids).
/// A group whose bodies all ended their last solve at rest (kRestSpeed), all of its
/// contacts with friction, is not settling but resting, and stops at kMaxSolverIterations:
/// shock propagation holds it. A resting pyramid of 210 boxes paid 200 sweeps in each of its
/// 31 steps before it slept (0.83 s of CPU over 10 s; 0.54 with this rule, same session).
/// Raised from 200 to 1000 with event reach (sim/event_reach.h), which stopped giving an
/// unconverged group more sweeps at each event of its island: at 200, a column of the
/// tilted pile's middle towers (seed 2, sleeping off) propped on one corner ended in a
/// steady 7 mm/s creep, and seed 15 (before event reach too) at 3 mm/s; at 1000 both rest
/// by 6.7 s, and the wedged box (FailureModes) by 6 s. The pile of 1000 (seed 1, its first
/// 6 s) then costs 57.5 s of CPU against 78.1 s for 200 sweeps without event reach, side
/// by side, and rests by 4.0 s against 4.8 s.
inline constexpr int kSettlingSolverSweeps = 1000;
inline constexpr double kSettlingSpeed = 0.05;

/// A settling group's sweeps past kMaxSolverIterations also stop once they stall: when
/// the kSettlingStallWindow sweeps just made have not cut the smallest change a sweep
/// made so far (its largest impulse change, m/s) by kSettlingLeastGain of itself. What
/// is left goes to shock propagation, as at the limit. Traced on the tilted pile of 125
/// (seed 1), 513 of its 518 settling solves ran the whole 1000 sweeps unconverged, some
/// repeating one change to the last digit for 900 sweeps (a cycle, not a convergence);
/// in the first 3 s of the pile of 1000, settling sweeps were 65% of all sweeps and this
/// rule would stop two thirds of them. Side by side, one run each: the pile of 125 (20 s)
/// 1.97 against 2.41 s of CPU, at rest by 1.85 against 2.0 s; piles of 1000 (20 s, seeds
/// 1 to 4) 197 against 223 s, every box at rest and asleep, by 4.9, 4.2, 5.4 and 5.4 s
/// against 4.0, 3.9, 4.1 and 4.3 s, no energy gained; the towers family (the pile's middle
/// nine columns, seeds 1 to 44, and the corner's, 1 to 8; sleeping off, 8 s) 153 against
/// 187 s, all at rest but seed 28's middle, which topples late in both. A window asking
/// for half (0.5) left the pile of 1000 settling later still (162 against 63 boxes moving
/// at 3 s).
/// Why they stall is friction. In the pile of 1000's first 1.5 s (seed 1) the settling
/// sweeps past 60 cost 9.5 M block solves; the same pile without friction, 0.12 M. They
/// are not a cycle but a crawl: a tilted column of nine boxes (18 line contacts) still
/// moves its summed normal impulse from 3.11 to 3.30 N s between sweeps 60 and 400.
/// Tried and not kept, on the same pile's first 3 s (59 M block solves stalled past 60):
/// friction limits held fixed while sweeping (63 to 72 M); gaps within the tolerance
/// given no speculative target (148 M); a direct solve on the active set the sweeps reach
/// (subspace minimization: it held in 42 of 60,000 tries, since at a stall that set is
/// not a solution). On piles of 1000, seeds 1 to 4, 10 s (519 M block solves in all):
/// the two tangents solved as one 2x2 block, 497 M, from +7% to -15% by seed; that block
/// also projected onto the disk in its own metric, seed 3 never rested. Over-relaxing
/// the sweeps past 60 (each impulse change times omega) comes nearest: at 1.5, 436 M, the
/// stalled part 171 M against 259 M, all four at rest (by 5.4, 3.3, 4.3, 5.1 s against
/// 4.2, 4.4, 4.1, 5.4 s); but at 1.6 seeds 2 and 3 never rest, and at 1.9 the pile of
/// 1000 (seed 1) gained 3e9 J. A setting that close to a cliff is not kept.
/// What a stall is, traced: symmetric sweeps fall into a two-cycle. In a settling column
/// of ten blocks (pile of 125) the forward and backward sweeps leave the bodies 4e-6 m/s
/// apart for good, while the change over a pair of sweeps keeps shrinking by 1.1% a sweep;
/// in a lone line contact, friction slides between its two ends, 1.2e-8 N s a sweep.
/// Measured on solver_bench's replays (the same solves each time, so exact: the pile of
/// 1000 landing and three of piles of 343), not kept: momentum past sweep 60 (nonsmooth
/// conjugate gradients, Silcowitz et al. 2010) -11% to +16% by replay; stopping on a
/// two-cycle (the change over a pair under 1% of one sweep's) -5% to -8%; every sweep past
/// 60 in one direction (bottom-up or top-down) -10% to -19%, yet whole runs, where rest
/// times move by a second either way, read -1% (piles of 1000, seeds 1 to 4, 10 s) and
/// -3% (343, seeds 1 to 6, 6 s) for bottom-up.
/// Where a settling group's sweeps go (pile of 343, seed 1, one group in fifty sampled):
/// its largest change a sweep is 1e-4 to 1e-3 m/s at sweep 60 and hardly less at 200
/// (1.8e-4 against 1.4e-4 in a group of 35 blocks), so most end on the stall rule at 160
/// to 360 sweeps; of that pile's 59 M point solves (shock propagation's included), 24 M
/// are settling sweeps past 60 and 25 M groups stopped at 60 (5.4 M of them resting, the
/// rest moving). Event solves are a fifth of the work (pile of 1000, seed 1, 10 s: 22 M
/// of 148 M point solves in the sweeps, 12 M of 43 M in shock propagation); the rest is
/// the solves at the steps' starts.
/// Event solves' moving groups stopped at 20 sweeps instead of 60 (the steps' starts kept
/// at 60), measured and not kept: the point solves fell by 17% and 11% (piles of 343,
/// seeds 1 to 6 and 7 to 12, 6 s) and by 14% (1000, seeds 1 to 4), every test passing,
/// but CPU by only 12%, 2% and 6%, and the piles of 343 rested later on average (3.56
/// against 3.36 s, 4.13 against 3.58 s).
inline constexpr int kSettlingStallWindow = 100;
inline constexpr double kSettlingLeastGain = 0.1;

/// A solve of at least this many rows sweeps its groups (contacts sharing no moving body)
/// on two threads (contact_sweeps.h): below it, starting a thread costs more than it saves.
inline constexpr int kSharedSweepRows = 32;

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

/// Shock propagation ranks bodies by support (shock_propagation.h): a contact whose
/// normal leans less than this cosine from vertical (more than about 84 degrees from it)
/// holds nothing up and ranks neither body. Ranked by any contact, a static wall a
/// column's top box leaned on ranked the column from the top down as well as from the
/// ground up: the two met half way, a level of the column's middle boxes held the upper
/// ones fixed, and ten-box columns by a wall rocked for good (pile of 1000, seed 11).
inline constexpr double kSupportCosine = 0.1;

/// Two edges crossing at an angle whose sine is below this are taken for a line contact
/// when the solver curves their gap (contact_row.h): the point where they cross slides
/// along them at their relative speed over the sine, and as they turn parallel that
/// point's motion, and the curvature it gives, grow without bound. Above it the point
/// slides at most 10 times their relative speed.
inline constexpr double kCrossingEdgeSine = 0.1;

/// A body moving slower than this (m/s, also for angular speed times its size) is
/// reported at rest.
inline constexpr double kRestSpeed = 1e-3;

/// Sleeping (sleep.h): a body is slow while it, and the farthest point of its spin, move
/// slower than kSleepSpeed (m/s); an island whose bodies have all been slow for
/// kTimeToSleep (s) falls asleep. Box2D and Jolt use 0.05 m/s and 0.5 s; polysim's
/// resting contacts settle to far below 1 mm/s, so a body still moving at 1 cm/s is
/// settling, not resting. The price of any speed rule: a body that starts from rest
/// accelerating at less than kSleepSpeed / kTimeToSleep (0.02 m/s^2) sleeps before it is
/// seen moving. Measured at Box2D's 5 cm/s: piles of 1000 (10 s) 9.6 against 11.0 s of
/// wall time (seed 1) and 11.4 against 9.8 (seed 2), since an island sleeps only once all
/// of it is slow; with kSettlingSolverSweeps at 60 as well, 25% faster and every box
/// asleep by 3.9 s, but 11 tests failed, the tilted towers among them: their columns
/// must rest by the solver, and at 60 sweeps they creep and only sleep stops them.
inline constexpr double kSleepSpeed = 1e-2;
inline constexpr double kTimeToSleep = 0.5;

}  // namespace polysim::dynamics
