#pragma once
// JSON text read with a message that says where it went wrong.

#include <istream>
#include <nlohmann/json.hpp>

namespace polysim::sim {

/// Parses the JSON text in `in`. Throws std::runtime_error holding nlohmann's sentence
/// and the place: "line L, column C" for a syntax error (nlohmann's own), and the
/// field's path (for example `bodies[1].velocity[0]`) for a number too large for a
/// double (1e999), which nlohmann reports without a place.
nlohmann::json parseJsonText(std::istream& in);

}  // namespace polysim::sim
