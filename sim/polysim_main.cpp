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

  double interval = 0.0;
  std::string method = "bisection";
  CLI::App* toc = app.add_subcommand("toc", "collisionDetect() over [0, T] with the bodies moving kinematically");
  toc->add_option("SCENE", scene, "scene file (JSON)")->required();
  toc->add_option("--interval", interval, "T in seconds (default: the scene's dt)")->check(CLI::PositiveNumber);
  toc->add_option("--method", method, "how the time of contact is guessed")
      ->check(CLI::IsMember({"bisection", "regula-falsi"}));

  CLI11_PARSE(app, argc, argv);
  try {
    if (contacts->parsed()) return polysim::sim::contactsCommand(scene, std::cout);
    if (toc->parsed()) return polysim::sim::tocCommand(scene, interval, method, std::cout);
  } catch (const polysim::sim::SceneError& e) {
    std::cerr << e.what() << "\n";
    return 1;
  } catch (const std::exception& e) {
    std::cerr << "polysim: " << e.what() << "\n";
    return 1;
  }
  return 0;
}
