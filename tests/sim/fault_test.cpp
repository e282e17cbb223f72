// Runs killed with SIGKILL, as a crash, an out-of-memory kill or a cluster's time limit
// kills them: what they leave must be usable (a step log of whole lines) or untouched
// (outputs written whole or not at all). The polysim binary is killed as a user's run
// would be, at seeded moments while it writes.

#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include <algorithm>
#include <chrono>
#include <csignal>
#include <filesystem>
#include <fstream>
#include <functional>
#include <random>
#include <sstream>
#include <string>
#include <sys/wait.h>
#include <thread>
#include <unistd.h>

#include "tests/test_support.h"

namespace polysim::sim {
namespace {

namespace fs = std::filesystem;

std::string slurp(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

size_t lineEnds(const fs::path& path) {
  const std::string text = slurp(path);
  return static_cast<size_t>(std::count(text.begin(), text.end(), '\n'));
}

class Killed : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::path(test::tempPath("dir"));
    fs::remove_all(dir_);
    fs::create_directories(dir_);
    // A busy scene, so every step writes a long line (contacts of 27 tumbling boxes).
    ASSERT_EQ(run("make pile --count 27 --seed 3 --duration 60 --out pile.json"), 0);
  }
  void TearDown() override { fs::remove_all(dir_); }

  // Runs `polysim ARGS` in dir_ to its end; its exit status.
  int run(const std::string& args) const {
    const std::string command = "cd " + dir_.string() + " && " + POLYSIM_BINARY + " " + args + " >out.txt 2>err.txt";
    const int raw = std::system(command.c_str());
    return WIFEXITED(raw) ? WEXITSTATUS(raw) : -1;
  }
  // Starts `polysim ARGS` in dir_, stdout to `stdoutFile`, waits until `ready` holds (or
  // 60 s pass), waits `delay` more, and kills it with SIGKILL. False if it ended by itself.
  bool killWhen(const std::string& args, const std::function<bool()>& ready, std::chrono::microseconds delay,
                const std::string& stdoutFile = "killed_out.txt") const {
    const pid_t pid = fork();
    if (pid == 0) {
      const std::string command = "cd " + dir_.string() + " && exec " + POLYSIM_BINARY + " " + args + " >" + stdoutFile + " 2>/dev/null";
      execl("/bin/sh", "sh", "-c", command.c_str(), static_cast<char*>(nullptr));
      _exit(127);
    }
    const auto giveUp = std::chrono::steady_clock::now() + std::chrono::seconds(60);
    int status = 0;
    while (!ready() && std::chrono::steady_clock::now() < giveUp) {
      if (waitpid(pid, &status, WNOHANG) == pid) return false;
      std::this_thread::sleep_for(std::chrono::milliseconds(1));
    }
    std::this_thread::sleep_for(delay);
    kill(pid, SIGKILL);
    waitpid(pid, &status, 0);
    return WIFSIGNALED(status) && WTERMSIG(status) == SIGKILL;
  }
  // Every line that has its end is a whole step, numbered from 1; what follows the last
  // end (a line cut inside its write) is returned.
  std::string expectWholeSteps(const fs::path& log, size_t& steps) const {
    const std::string text = slurp(log);
    size_t start = 0;
    steps = 0;
    for (size_t end = text.find('\n'); end != std::string::npos; start = end + 1, end = text.find('\n', start)) {
      const auto line = nlohmann::json::parse(text.substr(start, end - start), nullptr, false);
      EXPECT_FALSE(line.is_discarded()) << log << " line " << steps + 1 << " is not whole";
      if (line.is_discarded()) return "";
      EXPECT_EQ(line.value("step", 0), static_cast<int>(++steps));
    }
    return text.substr(start);
  }
  fs::path dir_;
};

TEST_F(Killed, ARunLeavesAStepLogOfWholeLinesThatItsReadersRead) {
  std::mt19937 random(18);
  for (int kill = 0; kill < 6; ++kill) {
    const fs::path log = dir_ / "run.jsonl";
    fs::remove(log);
    const size_t wait = 2 + random() % 20;
    ASSERT_TRUE(killWhen("run pile.json --log run.jsonl --log-contacts", [&] { return fs::exists(log) && lineEnds(log) >= wait; },
                         std::chrono::microseconds(random() % 20000)));
    size_t steps = 0;
    const std::string rest = expectWholeSteps(log, steps);
    ASSERT_GE(steps, wait);
    // polysim log reads every whole step; polysim view shows them and names a cut line.
    ASSERT_EQ(run("log run.jsonl"), 0) << slurp(dir_ / "err.txt");
    EXPECT_EQ(nlohmann::json::parse(slurp(dir_ / "out.txt")).size(), steps);
    ASSERT_EQ(run("view run.jsonl --out run.html"), 0) << slurp(dir_ / "err.txt");
    const auto view = nlohmann::json::parse(slurp(dir_ / "out.txt"));
    EXPECT_EQ(view.contains("warnings"), !rest.empty()) << view.dump() << " after " << rest.size() << " cut bytes";
  }
}

TEST_F(Killed, CompareLeavesNoSummaryAndStepLogsOfWholeLines) {
  fs::create_directories(dir_ / "logs");
  const fs::path log = dir_ / "logs" / "polysim.jsonl";
  ASSERT_TRUE(killWhen("compare pile.json --log-dir logs", [&] { return fs::exists(log) && lineEnds(log) >= 5; },
                       std::chrono::microseconds(3000), "compare.json"));
  EXPECT_EQ(slurp(dir_ / "compare.json"), "");  // the summary is written at the end, whole
  size_t steps = 0;
  expectWholeSteps(log, steps);
  EXPECT_GE(steps, 5u);
}

// An output that a killed command was replacing keeps its earlier content to the byte.
// (Every output file but the step log is written through writeWholeFile, whole_file.h.)
TEST_F(Killed, AnOutputBeingReplacedIsLeftWhole) {
  const std::string earlier = "the sweep of an earlier run\n";
  std::ofstream(dir_ / "sweep.csv") << earlier;
  // The whole sweep takes seconds; it is killed one second into writing its CSV.
  ASSERT_TRUE(killWhen("sweep --scenes " + std::string(POLYSIM_SCENES_DIR) + " --out sweep.csv",
                       [&] { return fs::exists(dir_ / "sweep.csv.partial"); }, std::chrono::seconds(1)));
  EXPECT_EQ(slurp(dir_ / "sweep.csv"), earlier);
}

}  // namespace
}  // namespace polysim::sim
