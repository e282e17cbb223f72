#pragma once
// Independent pieces of work shared between the calling thread and one more. Internal to
// the solver: its groups of contacts that share no moving body are such pieces.

#include <functional>

namespace polysim::dynamics::solver {

/// Calls work(0) .. work(count - 1), each once, in some order. With `shared`, on the
/// calling thread and one more, each taking the next piece as it finishes one (pieces
/// given largest first finish together); without it, or where no second thread can be
/// started, all on the calling thread. The pieces must touch disjoint data: the results
/// are then the same, to the bit, however the pieces fall. Returns once all are done.
void forEachPiece(int count, bool shared, const std::function<void(int)>& work);

}  // namespace polysim::dynamics::solver
