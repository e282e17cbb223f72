#include "sim/ode_baseline.h"

#include <chrono>
#include <cmath>
#include <iomanip>
#include <memory>
#include <sstream>

#include "sim/contact_agreement.h"
#include "sim/json_output.h"
#include "sim/polysim_engine.h"
#include "sim/run_record.h"
#include "sim/step_log.h"

namespace polysim::sim {
namespace {

// What `findings` calls a problem.
constexpr double kFindingPenetrationFactor = 10.0;  // overlap beyond this many tolerances
constexpr double kFindingPositionDifference = 0.01; // m between the engines' final positions
constexpr double kFindingEnergyGain = 1e-6;         // J per J of initial energy (or per J when it is 0)

nlohmann::ordered_json settingsToJson(const OdeSettings& s) {
  return {{"stepper", s.quickStep ? "quickstep" : "worldstep"},
          {"iterations", s.quickStepIterations},
          {"erp", s.erp},
          {"cfm", s.cfm}};
}

std::string number(double x) {
  std::ostringstream s;
  s << std::setprecision(3) << x;
  return s.str();
}

// The lowest point (along up) of every static body: below it, a body has fallen through.
double lowestStaticHeight(const Scene& scene) {
  const Eigen::Vector3d up = scene.up();
  double lowest = std::numeric_limits<double>::infinity();
  for (const BodySpec& b : scene.bodies)
    if (b.isStatic)
      for (const Eigen::Vector3d& v : b.mesh.vertices) lowest = std::min(lowest, (b.pose() * v).dot(up));
  return lowest;
}

void addFindings(const std::string& engine, const Scene& scene, const RunRecord& r, std::vector<std::string>& out) {
  const double tolerance = scene.contact.tolerance;
  if (r.maxPenetration > kFindingPenetrationFactor * tolerance)
    out.push_back(engine + ": contacts overlapped by up to " + number(r.maxPenetration) + " m, " +
                  number(r.maxPenetration / tolerance) + " times the contact tolerance");
  if (r.maxEnergyIncrease > kFindingEnergyGain * std::max(1.0, std::abs(r.initialEnergy)))
    out.push_back(engine + ": energy rose " + number(r.maxEnergyIncrease) + " J above its initial value");
  const double floor = lowestStaticHeight(scene);
  for (const BodyState& end : r.final)
    if (end.position.dot(r.up) < floor)
      out.push_back(engine + ": " + end.name + " ended at height " + number(end.position.dot(r.up)) +
                    " m, below every static body (it fell off or through)");
}

// polysim's run, with every contact state handed to ODE for comparison.
// Its wall time leaves out the time spent asking ODE.
RunRecord runPolysimComparingContacts(const Scene& scene, const RunOptions& options, ContactAgreement& agreement) {
  PolysimEngine engine(scene, options.method);
  OdeContactProbe probe(scene);
  const double press = kOdePressFactor * scene.contact.tolerance;
  std::chrono::steady_clock::duration probing{};
  std::unique_ptr<StepLog> log;
  if (!options.logDirectory.empty()) log = std::make_unique<StepLog>(options.logDirectory + "/polysim.jsonl", true);
  RunRecord record = recordRun(engine, options.stepsFor(scene), options.dtFor(scene), scene.up(), [&] {
    const World& world = engine.world();
    if (log) log->write(world, engine.lastReport());
    if (world.contacts().empty()) return;
    const auto start = std::chrono::steady_clock::now();
    agreement.countState();
    for (const collision::PairResult& pair : world.contacts()) {
      if (pair.status != collision::Status::Contact) continue;
      Eigen::Isometry3d X_WA = world.bodies()[pair.a].pose();
      X_WA.pretranslate(-press * pressDirection(pair));
      const auto ode = probe.contacts(pair.a, pair.b, X_WA, world.bodies()[pair.b].pose());
      agreement.add(world.time(), scene.bodies[pair.a].name, scene.bodies[pair.b].name, pair, ode,
                    comparePairContacts(pair, ode, press, scene.contact.tolerance));
    }
    probing += std::chrono::steady_clock::now() - start;
  });
  record.wallTime -= std::chrono::duration<double>(probing).count();
  return record;
}

// Dynamic body i in both runs, which started from the same state.
nlohmann::ordered_json bodyComparison(size_t i, const RunRecord& mine, const RunRecord& ode) {
  const BodyState& a = mine.final[i];
  const BodyState& b = ode.final[i];
  return {{"name", a.name},
          {"position_difference", forOutput((a.position - b.position).norm())},
          {"orientation_difference_rad", forOutput(a.orientation.angularDistance(b.orientation))},
          {"at_rest", {a.atRest, b.atRest}},
          {"drift", {forOutput(mine.drift(i)), forOutput(ode.drift(i))}},
          {"height_change", {forOutput(mine.heightChange(i)), forOutput(ode.heightChange(i))}}};
}

nlohmann::ordered_json odeSummary(const Scene& scene, const RunRecord& record, const OdeWorld& world,
                                  const OdeSettings& settings) {
  nlohmann::ordered_json summary = {{"engine", "ode"}};
  summary.update(summaryToJson(scene.name, record));
  summary["settings"] = settingsToJson(settings);
  summary["sleeping_bodies"] = world.sleepingBodies();
  summary["ode_messages"] = {{"count", world.messages()},
                             {"last", world.messages() > 0 ? nlohmann::ordered_json(odeMessages().last) : nullptr}};
  return summary;
}

}  // namespace

nlohmann::ordered_json runOde(const Scene& scene, const RunOptions& options, const OdeSettings& settings) {
  OdeWorld world(scene, settings);
  const RunRecord record = recordRun(world, options.stepsFor(scene), options.dtFor(scene), scene.up());
  return odeSummary(scene, record, world, settings);
}

nlohmann::ordered_json compareWithOde(const Scene& scene, const RunOptions& options, const OdeSettings& settings) {
  checkRunLength(scene, options);
  ContactAgreement agreement;
  const RunRecord mine = runPolysimComparingContacts(scene, options, agreement);
  OdeWorld odeWorld(scene, settings);
  std::unique_ptr<StepLog> odeLog;
  if (!options.logDirectory.empty()) odeLog = std::make_unique<StepLog>(options.logDirectory + "/ode.jsonl");
  long odeSteps = 0;
  const RunRecord ode = recordRun(odeWorld, options.stepsFor(scene), options.dtFor(scene), scene.up(), [&] {
    ++odeSteps;
    if (odeLog) odeLog->write(engineStepToJson(odeWorld, odeSteps, static_cast<double>(odeSteps) * options.dtFor(scene)), scene.file);
  });

  nlohmann::ordered_json bodies = nlohmann::ordered_json::array();
  for (size_t i = 0; i < mine.final.size(); ++i) bodies.push_back(bodyComparison(i, mine, ode));
  std::vector<std::string> findings;
  addFindings("polysim", scene, mine, findings);
  addFindings("ode", scene, ode, findings);
  if (odeWorld.messages() > 0)
    findings.push_back("ode: " + std::to_string(odeWorld.messages()) + " solver warnings, the last \"" + odeMessages().last + "\"");
  for (size_t i = 0; i < mine.final.size(); ++i) {
    const double apart = (mine.final[i].position - ode.final[i].position).norm();
    if (apart > kFindingPositionDifference)
      findings.push_back(mine.final[i].name + " ends " + number(apart) + " m apart in the two engines");
    if (mine.final[i].atRest != ode.final[i].atRest)
      findings.push_back(mine.final[i].name + " is at rest at the end in " + (mine.final[i].atRest ? "polysim" : "ode") +
                         " only");
  }

  auto both = [](const auto& a, const auto& b) { return nlohmann::ordered_json::array({a, b}); };
  auto time = [](const std::optional<double>& t) { return t ? nlohmann::ordered_json(forOutput(*t)) : nlohmann::ordered_json(nullptr); };
  nlohmann::ordered_json comparison;
  comparison["first_contact_time"] = both(time(mine.firstContactTime), time(ode.firstContactTime));
  comparison["max_penetration"] = both(forOutput(mine.maxPenetration), forOutput(ode.maxPenetration));
  comparison["energy_final"] = both(forOutput(mine.finalEnergy), forOutput(ode.finalEnergy));
  comparison["time_to_rest"] = both(time(mine.timeToRest), time(ode.timeToRest));
  comparison["wall_time_s"] = both(mine.wallTime, ode.wallTime);
  comparison["bodies"] = bodies;
  comparison["contacts"] = agreement.toJson();
  comparison["findings"] = findings;

  nlohmann::ordered_json polysimSummary = {{"engine", "polysim"}};
  polysimSummary.update(summaryToJson(scene.name, mine));
  return {{"polysim", polysimSummary}, {"ode", odeSummary(scene, ode, odeWorld, settings)}, {"comparison", comparison}};
}

}  // namespace polysim::sim
