#pragma once
// Shock propagation (Guendelman, Bridson and Fedkiw, "Nonconvex rigid bodies with
// stacking", SIGGRAPH 2003), as a last pass over a contact solve whose sweeps stopped at
// their limit. Internal to the contact solver (contact_solver.cpp).
//
// Gauss-Seidel carries a correction one contact per sweep: a column of 20 cups, each
// resting on one corner of the rim below, still changed by 1 mm/s after 600 sweeps, and
// swayed at 8 cm/s for good. Ranked by contact distance from a static body (the ground
// 0, what rests on it 1, what rests on that 2, ...), the bodies are solved again level
// by level from the ground up, each level against the levels below held fixed: their
// velocities as they are, their masses infinite. A level then has only its own bodies
// to settle, and a resting column comes out at rest in one pass. Levels follow support
// only: a contact links a body to the one it rests on (its normal up, against gravity,
// by at least kSupportCosine), not to a wall it leans on.

#include <functional>
#include <vector>

#include "dynamics/contact_row.h"
#include "dynamics/solve_bodies.h"

namespace polysim::dynamics::solver {

/// Re-solves the rows level by level as above, each level's sweeps starting from the
/// rows' accumulated impulses (so each still holds its total: normal >= 0, friction in
/// its disk) and changing only that level's bodies' velocities; the rows keep the
/// impulses found (the next step's warm start). Rows with restitution are left out (their
/// rebound is Poisson's, after this pass), and so are bodies connected to no static body.
/// `up`: the unit vector
/// against gravity (zero without gravity: every contact then links). The lower bodies take
/// no reaction, so momentum is not conserved and kinetic energy may rise (a level resting
/// on a body moving up); the caller checks. Returns the sweeps' work summed over levels.
SolveStats propagateShock(std::vector<Row>& rows, const SolveBodies& bodies, int maxSweeps, const Eigen::Vector3d& up);

/// The ranking behind both passes: calls `solveLevel(sub, picked)` for each level from
/// the ground up, where `picked` are the indices in `rows` of the level's rows (those
/// whose higher body is on it; rows with restitution and rows of unranked bodies are in
/// none) and `sub` their copies, each lower body replaced by a copy of itself marked
/// static as it is at that moment (its velocities and push velocities kept, its masses
/// infinite), axes prepared again. What `solveLevel` applies to `sub` moves only that
/// level's bodies.
void forEachLevel(const std::vector<Row>& rows, const SolveBodies& bodies, const Eigen::Vector3d& up,
                  const std::function<void(std::vector<Row>& sub, const std::vector<int>& picked)>& solveLevel);

}  // namespace polysim::dynamics::solver
