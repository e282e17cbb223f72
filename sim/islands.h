#pragma once
// Islands: groups of bodies that can affect each other within a step. Each island steps
// through its own contact events (World::stepIslands), so a scene of independent groups
// costs the sum of the groups, and an event in one never backs up another.
//
// Two dynamic bodies are linked when they touch, or when their paths over the step may
// bring them within the band of each other. Paths are judged relative to each other: two
// boxes falling side by side at one velocity never meet, though the boxes swept by their
// fall overlap. Judged by swept boxes, a landing pile of 1000 boxes (seed 1, at 0.9 s)
// was one island of 682 boxes, and each of the step's 96 events searched and tested all
// of it; judged by paths, its largest island held 18. Static bodies link nothing (a floor
// under two piles does not make them one). An event that turns a body aside may send it
// towards another island's body; the two islands then go on as one from that event
// (World::joinIslandsReached).

#include <Eigen/Geometry>
#include <utility>
#include <vector>

namespace polysim::sim {

/// A body as islands see it over a stretch of a step, in the world frame.
struct SweptBody {
  Eigen::AlignedBox3d start;  // its container's box at the stretch's start, grown by the band (m)
  Eigen::AlignedBox3d swept;  // a box holding it at every pose of its path, grown by the band (m)
  Eigen::Vector3d velocity = Eigen::Vector3d::Zero();  // of its centre of mass along the path (m/s)
  Eigen::Vector3d gravity = Eigen::Vector3d::Zero();   // acceleration along the path (m/s^2)
  double turn = 0.0;  // how far any of its points can move by turning over the stretch (m)
  bool dynamic = false;
};

/// Whether the paths of `a` and `b` over `duration` (s) may bring their start boxes
/// together: the boxes' gap is at most how far their centres' displacements can differ,
/// |dv| T + |dg| T^2 / 2, plus both turns, plus `roundOff` (m). Conservative: two bodies
/// it rejects stay apart by the boxes' growth (twice the band) for the whole duration.
bool pathsMayMeet(const SweptBody& a, const SweptBody& b, double duration, double roundOff);

/// The same body `t` s into its path of `duration` s: its start box carried along the
/// path and grown by the turn so far, its velocity then, and the turn left.
SweptBody alongPath(const SweptBody& body, double t, double duration);

/// The islands of `bodies` over `duration` (s): lists of body indices in increasing order,
/// ordered by their first body; a static body belongs to none. Bodies i and j (both
/// dynamic) share one when `links` holds (i, j) or pathsMayMeet(), or when a chain of
/// such links joins them. Candidates are the pairs whose swept boxes meet, by sweep and
/// prune along x.
std::vector<std::vector<int>> findIslands(const std::vector<SweptBody>& bodies, double duration,
                                          const std::vector<std::pair<int, int>>& links, double roundOff);

}  // namespace polysim::sim
