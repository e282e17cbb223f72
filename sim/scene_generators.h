#pragma once
// `polysim make`: scene files for the busy scenes people build (stacks, pyramids, piles,
// dominoes, columns of cups), so that nobody writes a 1000-body JSON file by hand. The
// same options give the same file, byte for byte: randomness comes from a seeded
// generator whose raw output is turned into numbers by this code, not by the standard
// library's distributions (whose results differ between library versions).

#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

namespace polysim::sim {

struct MakeOptions {
  std::string kind;               // one of sceneKinds()
  std::optional<int> count;       // bodies (stack, pile, dominoes, cups) or the base row (pyramid)
  unsigned long long seed = 1;    // for the random tilts and offsets
  std::optional<double> tilt;     // rad, largest random tilt of each body (pile: 0.3, others: 0)
  std::optional<double> dt;       // s (default 1/60)
  std::optional<double> duration;  // s (default per kind)
};

/// The kinds `polysim make` knows: stack, pyramid, pile, dominoes, cups.
const std::vector<std::string>& sceneKinds();

/// The scene file (SPEC.md's format) for the options; throws std::invalid_argument naming
/// the option when the kind is unknown or a value is out of range. Unit boxes unless said:
/// - stack: `count` boxes resting on each other on the ground (default 10, 60 s);
/// - pyramid: a base row of `count` boxes (default 10), each row one box shorter and
///   resting on the one below, centres 1.05 m apart along the row (10 s);
/// - pile: `count` boxes (default 125) on a grid 1.5 m apart, each turned by a random
///   angle up to `tilt` about a random axis, dropped into a 16 x 16 m pen with 10 m
///   walls (20 s);
/// - dominoes: `count` slabs 0.2 x 1 x 2 m standing 1 m apart along x, the first one
///   tipped towards the others at 1.5 rad/s (10 s);
/// - cups: a column of `count` open square cups (non-convex meshes, 1 m wide, 0.6 m
///   high) dropped from 0.2 m above each other, each shifted sideways by up to 5 cm at
///   random (10 s).
nlohmann::ordered_json makeScene(const MakeOptions& options);

}  // namespace polysim::sim
