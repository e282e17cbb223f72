#pragma once
// What `polysim view` draws: a scene's polygon meshes and one or more step logs of it,
// read back and checked, as the JSON the page (sim/viewer/) plays.

#include <nlohmann/json.hpp>
#include <string>

#include "sim/scene.h"

namespace polysim::sim {

/// The scene as the page draws it: name, and per body its name, whether it is static,
/// its mesh (vertices in the body frame, flat [x, y, z, ...]; faces as vertex indices,
/// counter-clockwise seen from outside) and its initial pose (position, [w, x, y, z]).
nlohmann::ordered_json sceneToViewJson(const Scene& scene);

/// One step log of `scene` as the page plays it:
/// - label (the log's file name without its extension), frames (steps + 1: the scene's
///   initial state, then every step's end), times (s), energy (J), penetration (m; null
///   where a line holds none), events (the times of its contact events, s);
/// - dynamic: the scene indices of the dynamic bodies, in the order of
/// - poses: base64 of little-endian float32, per frame and dynamic body: position (3),
///   orientation [w, x, y, z] (4), velocity (3);
/// - contactSets: the distinct sets of contacts the log holds (`contacts`, written by
///   `polysim run --log-contacts`; per pair a, b and per contact type, normal, points),
///   or null when it holds none; contactSetOf: per frame, the index of its set (a resting
///   scene repeats one set, so a 1000-box log stays small).
/// - cutShort: null, or (a run stopped while writing its last line: killed, or a full
///   disk) which line was cut short and left out.
/// Throws std::runtime_error naming the log, the line and the field when a line is not a
/// step, when the log has no whole step, and when its bodies are not the scene's dynamic
/// bodies (naming the body and the scene).
nlohmann::ordered_json logToViewJson(const std::string& logPath, const Scene& scene);

/// The scene file a step log names on its first line (`scene`), or "" when it names none.
std::string sceneNamedByLog(const std::string& logPath);

/// RFC 4648 base64 of `size` bytes.
std::string base64(const unsigned char* bytes, size_t size);

}  // namespace polysim::sim
