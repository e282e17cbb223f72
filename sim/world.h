#pragma once
// The step loop: the user's design, a minimal integrator whose every step calls
// collisionDetect(), backs up to the contact time, resolves the contacts and goes on.

#include <algorithm>
#include <functional>
#include <memory>
#include <set>
#include <string>
#include <utility>
#include <vector>

#include "collision/time_of_contact.h"
#include "dynamics/rigid_body.h"
#include "sim/body_path.h"
#include "sim/islands.h"
#include "sim/contact_points.h"
#include "sim/event_reach.h"
#include "sim/scene.h"

namespace polysim::sim {

/// Most contact events (collisionDetect() returning before the end of the remaining
/// step, TocResult::crossing naming the pairs) one body takes part in within one step. A
/// box bouncing ever lower has infinitely many bounces in finite time; when one of its
/// bodies reaches this bound the island's clock stops for the rest of the
/// step (poses stay, and so do velocities: a free body gains no gravity for time it did
/// not fly, or it would gain energy every such step), and the step records that it hit
/// the bound. An island whose every event fell at the step's start did not move at all:
/// its bodies that touch something stop (World::stopTouchingBodies), or the gravity they
/// were given for the step stays in their speed without their falling, every such step.
/// One that moved part way gives back the gravity for the rest
/// (World::takeBackUnflownGravity). Per body, not per island: a settling pile's island
/// of 800 boxes has a landing of a different box in it a dozen times a step, and a
/// bound on the island's events (8, before) stopped its clock in 112 of the first 180
/// steps of a 1000-box pile, 74 boxes at rest at 3 s; counted per body, in 4 steps, and
/// 821 at rest.
inline constexpr int kMaxEventsPerStep = 8;

/// An event that makes no progress (collisionDetect() returns the very state it started
/// from) has its contacts pushed apart to this fraction of the tolerance as a gap. It
/// happens when the solver's view and the detector's disagree: an edge crossing an edge
/// has its gap measured along the edges' common normal, while the polygons' test measures
/// the cut through a face, deeper by up to the secant of the angle between the two; at
/// the band's edge the first finds nothing approaching and the second an interpenetration
/// at once, and every event would return to the same state.
inline constexpr double kStalledGapFraction = 0.5;

/// The solver's contacts of a pair with a body that is not convex are found in a band
/// this many tolerances wide, not one. Such a pair is judged by its polygons' depth, and
/// what that verdict holds within the band its contacts may not report: a cup's rim edge
/// 100.9 um behind the wall of the cup in it is 99.5 um inside the rim by the verdict (in
/// contact at a tolerance of 100 um), yet its plane gap is past the band and no contact
/// held it. The solver let it sink at 0.13 m/s, 4 us later the verdict found it
/// interpenetrating, and each event of the step fell at its start. In the wider band that
/// edge has a contact the solver holds. Convex pairs are judged by the separating axis
/// test, which their contacts' gaps follow, and speculate further anyway.
inline constexpr double kWideBandFactor = 2.0;

/// Round-off allowed (m) when two bodies' paths are judged apart (islands.h,
/// pathsMayMeet): a body's path carried along to an event's time is the same sum as its
/// committed pose, taken in another order.
inline constexpr double kBoundsRoundOff = 1e-9;

/// Pairs of body indices, the smaller first.
using BodyPairs = std::set<std::pair<int, int>>;
inline std::pair<int, int> bodyPair(int a, int b) { return {std::min(a, b), std::max(a, b)}; }

/// One contact event inside a step.
struct StepEvent {
  double time = 0.0;  // s, simulation time of the contact
  collision::TocResult toc;
};

/// One island's share of a step (islands.h).
struct IslandReport {
  int bodies = 0;  // dynamic bodies in the island
  int events = 0;  // contact events it stepped through
};

/// What happened in one step, for the step log.
struct StepReport {
  long step = 0;
  double time = 0.0;  // s, at the step's end
  std::vector<StepEvent> events;
  std::vector<IslandReport> islands;  // in the order they stepped
  bool eventLimitHit = false;
  /// Times an event turned a body towards another island's, so that the two islands went
  /// on as one from that event (World::joinIslandsReached).
  int islandsJoined = 0;
  double penetration = 0.0;  // m, deepest overlap among the committed states
  int solverIterations = 0;  // the contact solver's sweeps, summed over the step's solves
  int shockSweeps = 0;       // and shock propagation's (dynamics/shock_propagation.h)
  std::vector<int> fellAsleep, woke;  // body indices that fell asleep / woke in this step
  int sleeping = 0;                   // bodies asleep at the step's end
};

class World {
 public:
  explicit World(const Scene& scene, collision::TocMethod method = collision::TocMethod::Bisection);
  // Not copied or moved: the database's objects point at the bodies' paths inside it.
  World(const World&) = delete;
  World& operator=(const World&) = delete;

  /// Advances the world by the scene's dt (or `dt` when given) and reports the step.
  const StepReport& step(double dt);

  double time() const { return time_; }
  const Scene& scene() const { return scene_; }
  const std::vector<dynamics::RigidBody>& bodies() const { return bodies_; }
  /// The contacts at the current state (pairs not separate, scene body indices).
  const std::vector<collision::PairResult>& contacts() const { return contacts_; }
  /// Kinetic plus gravitational potential energy of the dynamic bodies (J).
  double energy() const;
  bool atRest(int body) const;
  /// The body is asleep (scene "sleep"): it keeps its pose exactly and costs nothing
  /// until a body that moves can reach it.
  bool asleep(int body) const { return asleep_[body] != 0; }
  /// Pairs whose contacts were reused rather than tested, over the world's life (scene
  /// "reuse_contacts", collision/contact_reuse.h).
  long contactsReused() const { return workspace_.reuse.reused(); }
  /// Moves dynamic body `body` between steps to `pose` (body frame to world) with the
  /// given velocities (m/s, rad/s, world), as a user refilling a pile or respawning a body
  /// would. The body and every body it touched wake; its old contacts and their warm
  /// starts are dropped. Throws std::invalid_argument, changing nothing, when `body` is
  /// static or the pose interpenetrates another body beyond the tolerance.
  void placeBody(int body, const Eigen::Isometry3d& pose, const Eigen::Vector3d& velocity,
                 const Eigen::Vector3d& angularVelocity);
  /// The first time a pair was in contact (s), or a negative value if none yet.
  double firstContactTime() const { return firstContact_; }

  /// What one contact solve is given (dynamics::solveContacts()'s arguments, copied):
  /// enough to solve it again on its own, as the solver's benchmark does
  /// (tests/bench/solver_bench.cpp), where the same problems are solved again and again
  /// without the chaos of a whole run, in which one bit of difference sends a pile
  /// elsewhere.
  struct SolveProblem {
    std::vector<dynamics::RigidBody> bodies;
    std::vector<dynamics::ContactPoint> points;
    double horizon = 0.0;         // s
    double allowedOverlap = 0.0;  // m
    int maxSweeps = 0;
    Eigen::Vector3d up = Eigen::Vector3d::Zero();
    bool stepStart = false;       // the step's first solve (warm-started), not an event's
  };
  /// Called after each solve with its problem (the bodies as they were before it) and the
  /// bodies as it left them; empty (the default): none, and nothing is copied.
  using SolveObserver = std::function<void(const SolveProblem& problem, const std::vector<dynamics::RigidBody>& solved)>;
  void observeSolves(SolveObserver observer) { solveObserver_ = std::move(observer); }

 private:
  /// Bodies touching something at this point of the step (in `contacts`) that were
  /// flying free get gravity for the next `duration` seconds into their velocity now and
  /// move in a straight line from here (semi-implicit Euler); the others keep flying their
  /// exact parabola (dynamics/integrator.h). A pair about to bounce (in `bouncing`,
  /// judged before the solve that bounces it) supports neither body: it would bounce with
  /// a step's gravity more speed, and then fly free anyway. True when any body changed so.
  bool supportTouchingBodies(const std::vector<collision::PairResult>& contacts, const BodyPairs& bouncing,
                             double duration);
  /// The island's supported bodies (given gravity for the whole step, or the rest of it
  /// from their landing) lose the part for the `unflown` seconds (s) the island's clock
  /// stopped short of, as far as they still move down with it: an island stopped at the
  /// event bound part way through its step. Never raises kinetic energy; without it a
  /// frictionless column of cups that had fallen apart gained 10 J a step at the bound.
  void takeBackUnflownGravity(const std::vector<int>& island, double unflown);
  /// Bodies touching something (in `contacts`) lose their velocities and push velocities:
  /// an island stalled at the event bound at its step's start (kMaxEventsPerStep). A
  /// frictionless column of 20 cups so stalled (seed 2) kept the step's gravity every step
  /// and gained 196 kJ in 20 s.
  void stopTouchingBodies(const std::vector<collision::PairResult>& contacts);
  /// The pair has restitution and some contact point approaches faster than
  /// kBounceThreshold: the solve will bounce it.
  bool bounces(const collision::PairResult& pair) const;
  /// `contacts`, with the pairs of awake bodies in `db` that have a body that is not
  /// convex (and do not bounce) tested again in a band kWideBandFactor tolerances wide
  /// (objects mapped to bodies by `bodyOf`, empty: the same).
  /// Taken by value: with no such body (most scenes) the list is handed back, not copied.
  std::vector<collision::PairResult> withWideBand(const collision::ObjectDatabase& db, const std::vector<int>& bodyOf,
                                                  std::vector<collision::PairResult> contacts);
  /// What the solver is given for `touching` (the contacts within the tolerance): with
  /// the speculative contacts of settled bodies (speculative_contacts.h) found in `db`
  /// (objects mapped to bodies by `bodyOf`, empty: the same), and the pairs with a body
  /// that is not convex found in the wide band (kWideBandFactor).
  /// `only`, when given (per body) after an earlier event of the same island: the
  /// speculative test covers only the pairs with a body it marks, the others keep their
  /// last one (the bodies an event reaches; see takeEvent()).
  std::vector<collision::PairResult> solverContacts(const collision::ObjectDatabase& db, const std::vector<int>& bodyOf,
                                                    const std::vector<collision::PairResult>& touching,
                                                    const std::vector<char>* only = nullptr);
  /// solverContacts() again for the same poses after bodies landed (free_ cleared since
  /// the last solverContacts() or this): only the landed bodies' pairs are tested again,
  /// as they may now speculate; the others' are the last test's. A landing pile of 1000
  /// landed a body in 2,713 of the 3,937 events of its first 1.5 s.
  std::vector<collision::PairResult> solverContactsOnceLanded(const collision::ObjectDatabase& db,
                                                              const std::vector<int>& bodyOf,
                                                              const std::vector<collision::PairResult>& touching);
  /// `touching` with the speculative contacts of settled bodies (speculative_contacts.h): pairs
  /// of convex bodies, and of a body that is not convex with a static convex one;
  /// `onceLanded`: as solverContactsOnceLanded() says.
  std::vector<collision::PairResult> speculativeContacts(const collision::ObjectDatabase& db, const std::vector<int>& bodyOf,
                                                         const std::vector<collision::PairResult>& touching,
                                                         bool onceLanded = false, const std::vector<char>* only = nullptr);
  /// Solves `contacts` over `horizon` seconds; contacts overlapping deeper than
  /// `allowedOverlap` (m) are pushed apart (contact_solver.h). `stepStart`: the solve at
  /// the step's start, which holds the step's whole gravity; it warm-starts from the last
  /// such solve and is kept for the next. A solve after an event starts from zero.
  /// `bouncing`, when given: the only pairs that may bounce (restitution), judged before
  /// the bodies in contact were given gravity. Any other pair's approach is that gravity's
  /// (the semi-implicit step of a supported body), not an impact: a box that had just
  /// bounced, still within the band at a step's start, was given a whole step's gravity
  /// and bounced off it (at dt 2 s it gained 200 J). Without it, every pair approaching
  /// faster than kBounceThreshold bounces (an event's impact).
  void resolveContacts(const std::vector<collision::PairResult>& contacts, double horizon, bool stepStart,
                       double allowedOverlap, const BodyPairs* bouncing = nullptr);
  /// The pairs of `contacts` that bounce (bounces()), as body pairs.
  BodyPairs bouncingPairs(const std::vector<collision::PairResult>& contacts) const;
  /// The islands of this step (islands.h): bodies linked by contacts or by paths that may
  /// meet over `duration`; keeps each body's path as judged in sweptBodies_.
  std::vector<std::vector<int>> islandsOfStep(double duration);
  /// Steps the islands through their contact events in the order of the events' times,
  /// whichever island each falls in; an island that is all asleep waits (its sleeping
  /// bodies are woken where another island's steps). When an event turns a body aside
  /// towards another island's, the two go on as one (joinIslandsReached). Marks each
  /// stepped body in `stepped` and appends the islands' contacts at the step's end to
  /// `contactsAfter`, island after island.
  void stepIslands(const std::vector<std::vector<int>>& islands, double dt, std::vector<collision::PairResult>& contactsAfter,
                   std::vector<char>& stepped);
  /// One island's progress through a step (stepIslands).
  struct IslandRun {
    std::vector<int> bodies;  // increasing
    double remaining = 0.0;   // s of the step its clock has still to go
    collision::TocResult toc;  // its next contact event (or the step's end), over `remaining`
    double elapsed = 0.0;      // s from its clock to that event: toc.time * remaining
    std::vector<collision::PairResult> contacts;  // as last tested, body indices
    int reportEntry = -1;  // its entry in report_.islands
    long serial = 0;       // islandSerial_ while it is its island (speculativeContacts)
    std::vector<collision::PairResult> speculativeFound;  // its last speculative test (speculativeFound_)
    long speculativeSerial = -1;                           // and the serial it was made for
    enum class State { Asleep, Stepping, Stopped, Joined } state = State::Asleep;
  };
  /// The island wakes and starts the step: its contacts, its report entry, its bodies'
  /// event counts and their marks in `stepped`.
  void startIsland(IslandRun& run, std::vector<char>& stepped);
  /// Finds the island's next contact event over the rest of its step (run.toc, run.elapsed).
  void findNextEvent(IslandRun& run);
  /// Moves the island's clock to its next event and takes it: the contacts the event
  /// reaches tested again and solved, bodies that landed supported (the body of the old
  /// single-island loop). Returns the island's bodies whose path the event changed.
  std::vector<int> takeEvent(IslandRun& run, double dt);
  /// Moves the island's clock to the step's end, where it found no event, and keeps its
  /// contacts there.
  void finishIsland(IslandRun& run, double dt);
  /// Body `i`'s path over the next `duration` s from its box `start` (islands.h): its
  /// velocity, gravity and turn as predictMotion() moves it; `swept` is left as `start`.
  SweptBody pathFrom(int i, const Eigen::AlignedBox3d& start, double duration) const;
  /// Where body `i` is along its path at `t` s into the step of `dt`, and its path from
  /// there (islands.h), whatever island holds it and wherever that island's clock stands.
  SweptBody pathAt(int i, double t, double dt) const;
  /// After an event of island `k` at `t` s into the step of `dt`: each body of
  /// `turned` (its path changed) that may now meet a body of another island brings that
  /// island into island k, its clock moved to t. A refilled pen: a box kicked into a
  /// resting one of another island, found interpenetrating at the next step's start.
  void joinIslandsReached(int k, const std::vector<int>& turned, double t, double dt, std::vector<char>& stepped);
  /// The database collisionDetect() is given for an island: the world's own when the
  /// island holds every dynamic body, else islandDb_ filled with the island's bodies and
  /// every static one (islandIds_ maps its objects to body indices).
  collision::ObjectDatabase& databaseFor(const std::vector<int>& island);
  void predictMotion(const std::vector<int>& island, double duration);
  collision::TocResult detectCollisions(collision::ObjectDatabase& db);
  /// The bodies of `island` an event reaches (world_event_reach.cpp), marked by body
  /// index: those in a group of `contacts` (joined by contacts between dynamic bodies)
  /// with a body of a crossing pair of `toc`, or of a pair of toc.nearing that `contacts`
  /// holds none for. With `everyBody` (the island's clock stops, or the event came with
  /// no time elapsed) every body of the island.
  std::vector<char> bodiesAnEventReaches(const std::vector<int>& island,
                                         const std::vector<collision::PairResult>& contacts,
                                         const collision::TocResult& toc, bool everyBody) const;
  /// An event's contacts: `contacts` (the island's, body indices, each as last tested)
  /// with every pair of `db` that has a body `want` marks and none `tested` marks tested
  /// again at the current poses; those bodies are then marked in `tested`. Returns the
  /// pairs so tested that are not separate.
  std::vector<collision::PairResult> retestPairsOf(const collision::ObjectDatabase& db, const std::vector<char>& want,
                                                   std::vector<char>& tested,
                                                   std::vector<collision::PairResult>& contacts);
  /// The pairs of `solverContacts` in the groups an event reaches (EventReach::reached),
  /// every one of them tested at the event's time: while a reached group holds a body
  /// whose pairs were not (retestPairsOf()), they are, and `remake` gives the solver's
  /// contacts again from the island's contacts. The event's pairs (report_.events.back())
  /// gain each pair tested.
  std::vector<collision::PairResult> reachedAtEvent(
      const collision::ObjectDatabase& db, std::vector<collision::PairResult> solverContacts,
      const std::vector<std::pair<int, int>>& crossing, std::vector<char>& tested,
      std::vector<collision::PairResult>& contacts,
      const std::function<std::vector<collision::PairResult>(const std::vector<collision::PairResult>&)>& remake);
  /// Counts an event against the dynamic bodies of the pairs that caused it (`crossing`,
  /// body indices); true when one of them has reached kMaxEventsPerStep in this step.
  bool countEventOfBodies(const std::vector<std::pair<int, int>>& crossing);
  void commitPoses(const std::vector<int>& island, double elapsed);
  void noteContacts(const std::vector<collision::PairResult>& contacts, double at);
  void wake(int body);
  /// The island's bodies' slow times after a step of `dt`; when all have been slow for
  /// the scene's sleep time, the island falls asleep (velocities zeroed, poses kept).
  void sleepIfSettled(const std::vector<int>& island, double dt);
  /// The body moves this step: dynamic and not asleep.
  bool awake(int body) const { return !bodies_[body].isStatic && !asleep_[body]; }

  Scene scene_;
  collision::TocOptions tocOptions_;
  collision::ObjectDatabase db_;
  collision::ObjectDatabase islandDb_;  // one island's share of db_ (databaseFor)
  std::vector<int> islandIds_;          // islandDb_'s objects as body indices; empty: db_ itself
  std::vector<int> staticBodies_;       // the static bodies' indices, in order
  collision::IntersectionWorkspace workspace_;  // reused by every collisionDetect() call
  std::vector<dynamics::RigidBody> bodies_;
  std::vector<BodyPath> paths_;
  std::vector<char> free_;  // per body: gravity acts along its path this step (no contacts yet)
  std::vector<PairMaterial> materials_;  // per body: its restitution and friction
  std::vector<double> sizes_;            // per body: farthest vertex from the centre of mass (m)
  std::vector<collision::PairResult> contacts_;
  std::vector<double> slowFor_;  // per body: how long it has been slow (s), dynamics/sleep.h
  std::vector<char> asleep_;     // per body
  std::vector<int> eventsOf_;    // per body: contact events it took part in this step (kMaxEventsPerStep)
  std::vector<char> still_;      // per body: at rest at the step's start (atRest)
  /// The last speculative test's pairs (body indices) and free_ as it saw it, for
  /// solverContactsOnceLanded(): valid only for the poses it tested.
  std::vector<collision::PairResult> speculativeFound_;
  std::vector<char> speculatedFree_;
  long islandSerial_ = 0;        // the serial of the island taking an event (IslandRun::serial)
  long islandsNumbered_ = 0;     // serials given out this run: each island started or joined gets the next
  long speculativeIsland_ = -1;  // the call whose whole island speculativeFound_ was last tested for
  std::vector<SweptBody> sweptBodies_;  // per body: its path over the step, as islandsOfStep() judged it
  std::vector<IslandRun> runs_;         // this step's islands (stepIslands)
  std::vector<int> runOf_;              // per body: its island in runs_, -1 for a static one
  /// Per body: a box holding it from its island's clock to the step's end, grown by the
  /// tolerance (findNextEvent); where another island's body may meet it.
  std::vector<Eigen::AlignedBox3d> reachBoxes_;
  /// The step-start solve's impulses as forces (N): impulse / dt, and those of sleeping
  /// pairs from the step they fell asleep. Only the step-start solve is kept:
  /// an event's solve is mostly a collision impulse over what remains of the step, and
  /// divided by that short horizon it would warm-start the next step with many times the
  /// impulse, for the sweeps to take back.
  std::vector<dynamics::ContactPoint> lastSolved_;
  EventReach reach_;  // what each solve of this step covered, for an event's solve to cover less
  double time_ = 0.0;
  double timeCompensation_ = 0.0;  // Kahan summation: 14400 steps of 1/240 add up to 60 exactly
  double firstContact_ = -1.0;
  StepReport report_;
  SolveObserver solveObserver_;
};

}  // namespace polysim::sim
