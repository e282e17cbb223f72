// The polysim executable: parses the command line and hands over to sim/commands.

#include <CLI/CLI.hpp>
#include <filesystem>
#include <iostream>
#include <nlohmann/json.hpp>
#include <unistd.h>

#include "sim/commands.h"
#include "sim/heap_policy.h"
#include "sim/log_inspect.h"
#include "sim/run.h"
#include "sim/ode_world.h"
#include "sim/scene.h"
#include "sim/scene_generators.h"
#include "sim/sweep.h"
#include "sim/sweep_plan.h"
#include "sim/view_page.h"

namespace {

// Paths end up in JSON (a step log names its scene; summaries and pages name files), and
// JSON text is UTF-8: a path that is not would pass here and fail at the end of a run.
const CLI::Validator kUtf8Path(
    [](std::string& path) -> std::string {
      using nlohmann::json;
      try {
        (void)json(path).dump();
        return "";
      } catch (const json::type_error&) {
        return "the path " + json(path).dump(-1, ' ', false, json::error_handler_t::replace) +
               " is not valid UTF-8; polysim writes paths into JSON, which must be UTF-8: rename it";
      }
    },
    "PATH");

}  // namespace

int main(int argc, char** argv) {
  polysim::sim::keepFreedMemory();
  CLI::App app{"polysim: rigid bodies with polygon-level contact, compared against ODE"};
  app.require_subcommand(1);
  // One line, like every other refusal, and exit status 1.
  app.failure_message([](const CLI::App*, const CLI::Error& e) { return std::string("polysim: ") + e.what() + " (see --help)\n"; });

  std::string scene;
  CLI::App* contacts = app.add_subcommand("contacts", "test4Intersection() on the scene's initial state");
  contacts->add_option("SCENE", scene, "scene file (JSON)")->required()->check(kUtf8Path);

  double interval = 0.0;
  std::string method = "bisection";
  CLI::App* toc = app.add_subcommand("toc", "collisionDetect() over [0, T] with the bodies moving kinematically");
  toc->add_option("SCENE", scene, "scene file (JSON)")->required()->check(kUtf8Path);
  toc->add_option("--interval", interval, "T in seconds (default: the scene's dt)")->check(CLI::PositiveNumber);
  toc->add_option("--method", method, "how the time of contact is guessed")
      ->check(CLI::IsMember({"bisection", "regula-falsi"}));

  polysim::sim::RunOptions runOptions;
  double runDuration = 0.0, runDt = 0.0;
  std::string runMethod = "bisection";
  CLI::App* run = app.add_subcommand("run", "simulate the scene and print a summary");
  run->add_option("SCENE", scene, "scene file (JSON)")->required()->check(kUtf8Path);
  run->add_option("--duration", runDuration, "simulated time in seconds (default: the scene's)");
  run->add_option("--dt", runDt, "step in seconds (default: the scene's)");
  CLI::Option* runLog =
      run->add_option("--log", runOptions.logPath, "write the step log (JSON Lines) to this file")->check(kUtf8Path);
  run->add_flag("--log-contacts", runOptions.logContacts, "the step log also holds each step's contacts (for polysim view)")
      ->needs(runLog);
  run->add_option("--method", runMethod, "time-of-contact method")->check(CLI::IsMember({"bisection", "regula-falsi"}));

  std::string logFile;
  polysim::sim::LogQuery logQuery;
  std::string logBody;
  CLI::App* logCmd = app.add_subcommand("log", "a step log as a per-step or per-event table");
  logCmd->add_option("FILE", logFile, "step log written by 'polysim run --log'")->required()->check(kUtf8Path);
  logCmd->add_option("--body", logBody, "only events touching this body; its position and velocity per step");
  logCmd->add_option("--from", logQuery.from, "earliest time (s)");
  logCmd->add_option("--to", logQuery.to, "latest time (s)");
  logCmd->add_flag("--events", logQuery.events, "one row per contact event");
  logCmd->add_flag("--table", logQuery.table, "aligned text instead of JSON");

  CLI::App* compare = app.add_subcommand("compare", "run the scene in polysim and in ODE and compare");
  compare->add_option("SCENE", scene, "scene file (JSON)")->required()->check(kUtf8Path);
  compare->add_option("--duration", runDuration, "simulated time in seconds (default: the scene's)");
  compare->add_option("--dt", runDt, "step in seconds (default: the scene's)");
  compare->add_option("--log-dir", runOptions.logDirectory, "write both engines' step logs here (polysim.jsonl, ode.jsonl)")
      ->check(CLI::ExistingDirectory & kUtf8Path);
  compare->add_option("--method", runMethod, "polysim's time-of-contact method")
      ->check(CLI::IsMember({"bisection", "regula-falsi"}));
  polysim::sim::OdeSettings ode;
  std::string odeStepper = "quickstep";
  compare->add_option("--ode-stepper", odeStepper, "dWorldQuickStep or dWorldStep")
      ->capture_default_str()
      ->check(CLI::IsMember({"quickstep", "worldstep"}));
  compare->add_option("--ode-iterations", ode.quickStepIterations, "dWorldQuickStep's iterations")
      ->capture_default_str()
      ->check(CLI::PositiveNumber);
  compare->add_option("--ode-erp", ode.erp, "ODE's error reduction parameter")->capture_default_str()->check(CLI::Range(0.0, 1.0));
  compare->add_option("--ode-cfm", ode.cfm, "ODE's constraint force mixing")->capture_default_str()->check(CLI::NonNegativeNumber);

  polysim::sim::SweepOptions sweepOptions;
  std::string sweepOut;
  CLI::App* sweep = app.add_subcommand("sweep", "both engines over their settings on the standard scenes: CSV of cost and error");
  sweep->add_option("--scenes", sweepOptions.scenesDirectory, "directory holding the standard scenes")
      ->capture_default_str()
      ->check(CLI::ExistingDirectory & kUtf8Path);
  sweep->add_flag("--quick", sweepOptions.quick, "two steps, one setting per solver, short runs");
  sweep->add_option("--out", sweepOut, "CSV file (default: standard output)")->check(kUtf8Path);
  std::string sweepPlan, sweepResults = "sweep_runs", sweepMerge, sweepCase, sweepEngine, sweepSolver, sweepParameterName;
  double sweepParameter = 0.0, sweepDt = 0.0;
  CLI::Option* plan = sweep->add_option("--plan", sweepPlan, "write the sweep as a job list to this file; runs nothing")->check(kUtf8Path);
  sweep->add_option("--results", sweepResults, "folder the plan's runs write their rows to")
      ->capture_default_str()
      ->check(kUtf8Path)
      ->needs(plan);
  CLI::Option* merge = sweep->add_option("--merge", sweepMerge, "merge a plan's results folder into the CSV")
                           ->check(kUtf8Path)
                           ->excludes(plan);
  CLI::Option* oneCase = sweep->add_option("--case", sweepCase, "run one run of a plan: this scene of the sweep")
                             ->excludes(plan)
                             ->excludes(merge);
  sweep->add_option("--engine", sweepEngine, "one run: polysim or ode")->needs(oneCase);
  sweep->add_option("--solver", sweepSolver, "one run: bisection, regula-falsi, worldstep or quickstep")->needs(oneCase);
  sweep->add_option("--parameter-name", sweepParameterName, "one run: tolerance_m or solver_sweeps (polysim), iterations (quickstep)")
      ->needs(oneCase);
  sweep->add_option("--parameter", sweepParameter, "one run: tolerance (m), solver sweeps or iterations")->needs(oneCase);
  sweep->add_option("--dt", sweepDt, "one run: the step (s)")->needs(oneCase);

  polysim::sim::ViewOptions viewOptions;
  std::string viewScene;
  CLI::App* view = app.add_subcommand("view", "one self-contained HTML page replaying step logs in the browser");
  view->add_option("LOG", viewOptions.logs, "step log(s) of one scene; several are shown side by side")
      ->required()
      ->check(kUtf8Path);
  view->add_option("--scene", viewScene, "the scene (default: the one the first log names)")->check(kUtf8Path);
  view->add_option("--out", viewOptions.out, "the page to write (default: the first log with .html)")->check(kUtf8Path);

  polysim::sim::MakeOptions makeOptions;
  std::string makeOut;
  int makeCount = 0;
  double makeTilt = -1.0, makeDt = 0.0, makeDuration = 0.0;
  CLI::App* make = app.add_subcommand("make", "write a generated scene: a stack, pyramid, pile, dominoes or cups");
  make->add_option("KIND", makeOptions.kind, "stack, pyramid, pile, dominoes or cups")
      ->required()
      ->check(CLI::IsMember(polysim::sim::sceneKinds()));
  make->add_option("--count", makeCount, "bodies (the base row of a pyramid)")->check(CLI::Range(1, 10000));
  make->add_option("--seed", makeOptions.seed, "seed of the random tilts and offsets")->capture_default_str();
  make->add_option("--tilt", makeTilt, "largest random tilt of each body, rad (pile and cups)")->check(CLI::Range(0.0, 0.3));
  make->add_option("--dt", makeDt, "the scene's step, s (default 1/60)")->check(CLI::PositiveNumber);
  make->add_option("--duration", makeDuration, "the scene's duration, s")->check(CLI::PositiveNumber);
  make->add_option("--out", makeOut, "scene file to write (default: standard output)")->check(kUtf8Path);

  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    return app.exit(e) == 0 ? 0 : 1;  // --help exits 0
  }
  auto takeRunFlags = [&] {  // shared by run and compare; checked by checkRunLength (run.h)
    const CLI::App* command = run->parsed() ? run : compare;
    if (command->count("--duration")) runOptions.duration = runDuration;
    if (command->count("--dt")) runOptions.dt = runDt;
    runOptions.method = polysim::collision::tocMethodNamed(runMethod);
  };
  auto dispatch = [&]() -> int {
    if (contacts->parsed()) return polysim::sim::contactsCommand(scene, std::cout);
    if (run->parsed()) {
      takeRunFlags();
      runOptions.progress = isatty(STDERR_FILENO);
      return polysim::sim::runCommand(scene, runOptions, std::cout);
    }
    if (compare->parsed()) {
      takeRunFlags();
      ode.quickStep = odeStepper == "quickstep";
      return polysim::sim::compareCommand(scene, runOptions, ode, std::cout);
    }
    if (logCmd->parsed()) {
      if (!logBody.empty()) logQuery.body = logBody;
      polysim::sim::inspectLog(logFile, logQuery, std::cout);
      return 0;
    }
    if (sweep->parsed()) {
      if (!sweepPlan.empty())
        return polysim::sim::sweepPlanCommand(sweepOptions, sweepPlan, sweepResults,
                                              std::filesystem::canonical("/proc/self/exe").string());
      if (!sweepMerge.empty())
        return polysim::sim::sweepMergeCommand(sweepMerge, sweepOptions.quick, sweepOut, std::cout, std::cerr);
      if (!sweepCase.empty()) {
        if (sweepOut.empty()) throw std::invalid_argument("--out: one run of a plan needs the file its rows go to");
        const polysim::sim::SweepRun one{polysim::sim::standardSweepCase(sweepCase, sweepOptions.quick),
                                         polysim::sim::sweepSettingFrom(sweepEngine, sweepSolver, sweepParameterName, sweepParameter, sweepDt)};
        return polysim::sim::sweepRunCommand(sweepOptions, one, sweepOut, std::cerr);
      }
      return polysim::sim::sweepCommand(sweepOptions, sweepOut, std::cout, isatty(STDERR_FILENO) ? &std::cerr : nullptr);
    }
    if (view->parsed()) {
      if (!viewScene.empty()) viewOptions.scene = viewScene;
      return polysim::sim::viewCommand(viewOptions, std::cout);
    }
    if (toc->parsed()) return polysim::sim::tocCommand(scene, interval, method, std::cout);
    if (make->parsed()) {
      if (makeCount > 0) makeOptions.count = makeCount;
      if (makeTilt >= 0) makeOptions.tilt = makeTilt;
      if (makeDt > 0) makeOptions.dt = makeDt;
      if (makeDuration > 0) makeOptions.duration = makeDuration;
      return polysim::sim::makeCommand(makeOptions, makeOut, std::cout);
    }
    return 0;
  };
  try {
    const int status = dispatch();
    // A full disk or a closed pipe must not pass for success: the result was not delivered.
    std::cout.flush();
    if (!std::cout) throw std::runtime_error("cannot write to standard output");
    return status;
  } catch (const polysim::sim::SceneError& e) {
    std::cerr << e.what() << "\n";
    return 1;
  } catch (const std::exception& e) {
    std::cerr << "polysim: " << e.what() << "\n";
    return 1;
  }
}
