#pragma once
// The polysim subcommands, as functions: each reads its inputs, writes its JSON result to
// `out` and returns the process exit code. Errors are thrown (SceneError and others) and
// turned into one message on stderr by main().

#include <iosfwd>
#include <string>

namespace polysim::sim {

/// `polysim contacts SCENE`: test4Intersection() on the initial state.
int contactsCommand(const std::string& scenePath, std::ostream& out);

}  // namespace polysim::sim
