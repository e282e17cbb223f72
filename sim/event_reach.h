#pragma once
// What an event's solve must cover (World::stepIsland). The contacts of a step are solved
// at its start; each contact event inside the step solves again. Contacts fall into
// groups linked through dynamic bodies (as the solver's sweeps group them): a group none
// of whose bodies the event touched is as the last solve left it, and solving it again
// only repeats that solve's sweeps. A landing pile of 1000 boxes (seed 1, first 1.5 s)
// has 6,733 event solves of 660 contact points on average, of which the event's own
// group held 5%; every event re-swept the rest, and each unconverged group paid its
// sweep limit and shock propagation again: 116 M points solved, against 37 M with only
// the reached groups. A settling group is still swept at every event: sweeps are what
// rest it (dynamics/settings.h, kSettlingSolverSweeps).

#include <cstdint>
#include <unordered_map>
#include <utility>
#include <vector>

#include "collision/contact.h"
#include "dynamics/rigid_body.h"

namespace polysim::sim {

class EventReach {
 public:
  explicit EventReach(int bodyCount);

  /// Forgets every solve: a step starts.
  void newStep();

  /// A solve of `pairs` (body indices) has just ended: each pair's bodies' velocities are
  /// what it left.
  void noteSolved(const std::vector<collision::PairResult>& pairs, const std::vector<dynamics::RigidBody>& bodies);

  /// The pairs of `contacts` (body indices) in a group that holds a body disturbed since
  /// its last solve: one of a pair in `crossing` (the event's cause), one whose velocity
  /// or spin is not, bit for bit, what its last solve in this step left (gravity given on
  /// landing; never solved in this step), or one of a pair that no solve of this step held
  /// with as many contacts (new to the band, or a point that became a line as a box
  /// turned); and the pairs of a settling group: every body slower than kSettlingSpeed
  /// (m/s, its spin times its size `sizes` (m) counted), not every one at rest after its
  /// last solve. The others are left out; their order is kept. Taken by value: the
  /// pairs kept are moved, not copied.
  std::vector<collision::PairResult> reached(std::vector<collision::PairResult> contacts,
                                             const std::vector<std::pair<int, int>>& crossing,
                                             const std::vector<dynamics::RigidBody>& bodies,
                                             const std::vector<double>& sizes) const;

 private:
  static std::uint64_t key(int a, int b);
  bool disturbed(int body, const dynamics::RigidBody& state) const;

  struct Solved {
    long stamp = -1;  // the step it was last solved in
    Eigen::Vector3d velocity, angularVelocity;
  };
  std::vector<Solved> solved_;                 // per body
  std::unordered_map<std::uint64_t, size_t> pairs_;  // pairs solved in this step: their contacts' count
  long stamp_ = 0;
};

}  // namespace polysim::sim
