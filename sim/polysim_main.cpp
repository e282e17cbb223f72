// The polysim executable: parses the command line and hands over to sim/commands.

#include <CLI/CLI.hpp>
#include <iostream>

#include "sim/commands.h"
#include "sim/scene.h"

int main(int argc, char** argv) {
  CLI::App app{"polysim: rigid bodies with polygon-level contact, compared against ODE"};
  app.require_subcommand(1);

  std::string scene;
  CLI::App* contacts = app.add_subcommand("contacts", "test4Intersection() on the scene's initial state");
  contacts->add_option("SCENE", scene, "scene file (JSON)")->required();

  CLI11_PARSE(app, argc, argv);
  try {
    if (contacts->parsed()) return polysim::sim::contactsCommand(scene, std::cout);
  } catch (const polysim::sim::SceneError& e) {
    std::cerr << e.what() << "\n";
    return 1;
  } catch (const std::exception& e) {
    std::cerr << "polysim: " << e.what() << "\n";
    return 1;
  }
  return 0;
}
