#pragma once
// Islands: groups of bodies that can affect each other within a step. Two dynamic bodies
// are linked when they touch or when their swept bounds over the step overlap; static
// bodies link nothing (a floor under two piles does not make them one). Each island
// steps through its own contact events, so a scene of independent groups costs the sum
// of the groups, and an event in one never backs up another.

#include <Eigen/Geometry>
#include <utility>
#include <vector>

namespace polysim::sim {

/// The islands of `bounds.size()` bodies: each a list of body indices in increasing
/// order, the islands ordered by their first body. A body with `isDynamic` false belongs
/// to none. Bodies i and j (both dynamic) share an island when `links` holds (i, j) or
/// their boxes `bounds` (world frame, each grown by how far the body can move in the
/// step) intersect, or when a chain of such links joins them.
std::vector<std::vector<int>> findIslands(const std::vector<Eigen::AlignedBox3d>& bounds,
                                          const std::vector<char>& isDynamic,
                                          const std::vector<std::pair<int, int>>& links);

}  // namespace polysim::sim
