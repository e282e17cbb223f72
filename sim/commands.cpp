#include "sim/commands.h"

#include <filesystem>
#include <ostream>
#include <sstream>
#include <stdexcept>

#include "collision/time_of_contact.h"
#include "collision/tolerances.h"
#include "sim/json_output.h"
#include "sim/kinematic_motion.h"
#include "sim/ode_baseline.h"
#include "sim/run.h"
#include "sim/scene.h"
#include "sim/scene_generators.h"
#include "sim/sweep.h"
#include "sim/sweep_csv.h"
#include "sim/sweep_plan.h"
#include "sim/view_page.h"
#include "sim/whole_file.h"

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

int runCommand(const std::string& scenePath, const RunOptions& options, std::ostream& out) {
  const Scene scene = loadScene(scenePath);
  std::error_code error;
  if (!options.logPath.empty() && std::filesystem::equivalent(options.logPath, scenePath, error))
    throw std::invalid_argument("--log " + options.logPath + ": is the scene file; the step log would overwrite it");
  out << runScene(scene, options).dump() << "\n";
  return 0;
}

int tocCommand(const std::string& scenePath, double interval, const std::string& method, std::ostream& out) {
  collision::TocOptions options;
  options.method = collision::tocMethodNamed(method);

  const Scene scene = loadScene(scenePath);
  checkInitialState(scene);
  const double T = interval > 0 ? interval : scene.dt;
  collision::ObjectDatabase db = buildObjectDatabase(scene);
  std::vector<KinematicMotion> motions(scene.bodies.size());
  for (size_t i = 0; i < scene.bodies.size(); ++i) {
    const BodySpec& b = scene.bodies[i];
    if (b.isStatic || (b.velocity.isZero() && b.angularVelocity.isZero())) continue;
    motions[i] = {b.pose(), b.velocity, b.angularVelocity, T};
    collision::ObjNode& node = db.objects[i];
    node.ctrans = kinematicPose;
    node.info = &motions[i];
    node.motionBound = kinematicMotionBound(motions[i], *node.mesh);
    node.motionRate = node.motionBound;  // constant speeds: the bound over [0, 1] is the rate
  }
  db.setTime(1.0);  // collisionDetect starts from the poses at the end of the interval
  const collision::TocResult r = collision::collisionDetect(db, options);
  nlohmann::ordered_json j;
  j["time"] = forOutput(r.time * T);
  j["fraction"] = forOutput(r.time);
  j["status"] = collision::toString(r.status);
  j["pairs"] = pairsToJson(r.pairs, bodyNames(scene));
  j["iterations"] = r.iterations;
  j["method"] = collision::toString(options.method);
  j["stopped_by"] = collision::toString(r.stoppedBy);
  j["tunnelling_guarded"] = r.tunnellingGuarded;
  if (!r.tunnellingGuarded)
    j["warning"] = "a body moves farther for its thickness than " + std::to_string(collision::kMaxSubintervals) +
                   " sub-intervals cover: it may pass through another unseen; shorten the interval";
  j["subintervals"] = r.subintervals;
  j["separations"] = r.separations;
  j["crossing"] = crossingToJson(r.crossing, bodyNames(scene));
  j["pairs_meeting"] = r.pairsMeeting;
  j["pairs_watched"] = r.pairsWatched;
  out << j.dump() << "\n";
  return 0;
}

int compareCommand(const std::string& scenePath, const RunOptions& options, const OdeSettings& ode, std::ostream& out) {
  out << compareWithOde(loadScene(scenePath), options, ode).dump() << "\n";
  return 0;
}

int sweepCommand(const SweepOptions& options, const std::string& outPath, std::ostream& out, std::ostream* progress) {
  if (outPath.empty()) {
    writeSweepCsv(runSweep(options, progress), out);
    return 0;
  }
  writeWholeFile(outPath, "the sweep's CSV", [&](std::ostream& file) { writeSweepCsv(runSweep(options, progress), file); });
  return 0;
}

int sweepPlanCommand(const SweepOptions& options, const std::string& planPath, const std::string& resultsDirectory,
                     const std::string& binary) {
  std::ostringstream plan;  // every check (the results folder) before the file is written
  writeSweepPlan(options, resultsDirectory, binary, plan);
  writeWholeFile(planPath, "the sweep's plan", [&](std::ostream& file) { file << plan.str(); });
  return 0;
}

int sweepRunCommand(const SweepOptions& options, const SweepRun& run, const std::string& outPath, std::ostream& note) {
  if (runPlannedSweepRun(options.scenesDirectory, run, outPath) == PlannedRunOutcome::kKept)
    note << outPath << ": kept, it already holds this run's rows\n";
  return 0;
}

int sweepMergeCommand(const std::string& resultsDirectory, bool quick, const std::string& outPath, std::ostream& out,
                      std::ostream& report) {
  const SweepMerge merge = mergeSweep(resultsDirectory, quick);
  if (outPath.empty())
    writeSweepCsv(merge.rows, out);
  else
    writeWholeFile(outPath, "the sweep's CSV", [&](std::ostream& file) { writeSweepCsv(merge.rows, file); });
  if (merge.notMerged.empty()) return 0;
  report << resultsDirectory << ": merged " << merge.merged << " of " << merge.runs << " runs; not merged:\n";
  for (const std::string& line : merge.notMerged) report << "  " << line << "\n";
  return 1;
}

int makeCommand(const MakeOptions& options, const std::string& outPath, std::ostream& out) {
  const nlohmann::ordered_json scene = makeScene(options);  // all checks before anything is written
  if (outPath.empty()) {
    out << scene.dump(1) << "\n";
    return 0;
  }
  writeWholeFile(outPath, "the scene", [&](std::ostream& file) { file << scene.dump(1) << "\n"; });
  return 0;
}

int viewCommand(const ViewOptions& options, std::ostream& out) {
  const ViewPage page = writeViewPage(options);
  nlohmann::ordered_json summary{{"page", page.path}, {"bytes", std::filesystem::file_size(page.path)}};
  if (!page.warnings.empty()) summary["warnings"] = page.warnings;
  out << summary.dump() << "\n";
  return 0;
}

}  // namespace polysim::sim
