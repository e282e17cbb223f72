#include "sim/commands.h"

#include <ostream>

#include "sim/json_output.h"
#include "sim/scene.h"

namespace polysim::sim {
namespace {

std::vector<std::string> bodyNames(const Scene& scene) {
  std::vector<std::string> names;
  for (const BodySpec& b : scene.bodies) names.push_back(b.name);
  return names;
}

}  // namespace

int contactsCommand(const std::string& scenePath, std::ostream& out) {
  const Scene scene = loadScene(scenePath);
  const collision::ObjectDatabase db = buildObjectDatabase(scene);
  const collision::IntersectionResult r = collision::test4Intersection(db);
  out << intersectionToJson(r, bodyNames(scene)).dump() << "\n";
  return 0;
}

}  // namespace polysim::sim
