// What a user gets wrong, run through the polysim binary as a user runs it: one message on
// stderr naming the file, line or option and the field, exit status 1 (never a signal),
// nothing on stdout, and no file damaged. Each case crashed or passed silently before.

#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include <filesystem>
#include <functional>
#include <fstream>
#include <sstream>
#include <string>
#include <sys/wait.h>

namespace polysim::sim {
namespace {

namespace fs = std::filesystem;

struct Outcome {
  int status = -1;  // exit status; -1 when killed by a signal
  std::string out, err;
};

std::string slurp(const fs::path& path) {
  std::ifstream in(path);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

class BadInput : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::path(testing::TempDir()) / ("polysim-bad-input-" + std::string(testing::UnitTest::GetInstance()->current_test_info()->name()));
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }

  // Runs `polysim ARGS` from dir_; `stdoutTo` replaces the captured stdout when given.
  Outcome polysim(const std::string& args, const std::string& stdoutTo = "") const {
    const fs::path out = dir_ / "stdout", err = dir_ / "stderr";
    const std::string command = "cd " + dir_.string() + " && " + POLYSIM_BINARY + " " + args + " >" +
                                (stdoutTo.empty() ? out.string() : stdoutTo) + " 2>" + err.string();
    const int raw = std::system(command.c_str());
    Outcome o;
    o.status = WIFEXITED(raw) ? WEXITSTATUS(raw) : -1;
    o.out = stdoutTo.empty() ? slurp(out) : "";
    o.err = slurp(err);
    return o;
  }
  void write(const std::string& name, const std::string& text) const { std::ofstream(dir_ / name) << text; }
  // Exit 1, nothing on stdout, one line on stderr holding each of `parts`.
  void expectOneError(const Outcome& o, const std::vector<std::string>& parts) const {
    EXPECT_EQ(o.status, 1) << o.err;
    EXPECT_EQ(o.out, "");
    EXPECT_EQ(std::count(o.err.begin(), o.err.end(), '\n'), 1) << o.err;
    for (const std::string& p : parts) EXPECT_NE(o.err.find(p), std::string::npos) << "no \"" << p << "\" in: " << o.err;
  }
  fs::path dir_;
  const std::string scene_ = std::string(POLYSIM_SCENES_DIR) + "/drop_box.json";
};

TEST_F(BadInput, StepLogLinesMissingAFieldAreNamedNotCrashedOn) {
  const std::string good = R"({"step":2,"t":0.5,"events":[]})";
  write("event.jsonl", "{\"step\":1,\"t\":0,\"events\":[{}]}\n" + good + "\n");
  expectOneError(polysim("log event.jsonl"), {"event.jsonl line 1: event 0: no \"iterations\""});
  write("pair.jsonl", "{\"step\":1,\"t\":0,\"events\":[{\"time\":0.1,\"iterations\":3,\"pairs\":[{}]}]}\n" + good + "\n");
  expectOneError(polysim("log pair.jsonl --events"), {"pair.jsonl line 1: event 0: pair 0: no \"a\""});
  write("type.jsonl", "{\"step\":1,\"t\":\"soon\",\"events\":[]}\n");
  expectOneError(polysim("log type.jsonl"), {"type.jsonl line 1: \"t\" is not a number"});
  write("array.jsonl", "[1,2]\n" + good + "\n");
  expectOneError(polysim("log array.jsonl"), {"array.jsonl line 1: not a JSON object"});
}

TEST_F(BadInput, WhatIsNotAStepLogIsSaidToBeNone) {
  expectOneError(polysim("log ."), {".: not a file"});
  write("empty.jsonl", "");
  expectOneError(polysim("log empty.jsonl"), {"empty.jsonl: holds no step"});
  expectOneError(polysim("log " + scene_), {"drop_box.json line 1: not JSON"});  // a scene file, several lines
  // A garbage line that ends with a newline is not a run cut short.
  write("garbage.jsonl", R"({"step":1,"t":0.5,"events":[]})" "\nnot json\n");
  expectOneError(polysim("log garbage.jsonl"), {"garbage.jsonl line 2: not JSON"});
  // A last line cut short (no newline) is the run killed mid-write: the rest is read.
  write("cut.jsonl", R"({"step":1,"t":0.5,"events":[]})" "\n{\"step\":2,\"t\":");
  const Outcome cut = polysim("log cut.jsonl");
  EXPECT_EQ(cut.status, 0) << cut.err;
  EXPECT_NE(cut.out.find("\"step\":1"), std::string::npos) << cut.out;
}

TEST_F(BadInput, ABodyThatIsInNoStepIsNamed) {
  ASSERT_EQ(polysim("run " + scene_ + " --duration 0.05 --log drop.jsonl").status, 0);
  expectOneError(polysim("log drop.jsonl --body nobody"), {"drop.jsonl: no body named \"nobody\""});
  EXPECT_EQ(polysim("log drop.jsonl --body box").status, 0);
}

TEST_F(BadInput, WritesThatFailAreErrors) {
  expectOneError(polysim("run " + scene_ + " --duration 0.05 --log /dev/full"), {"/dev/full: writing the step log failed"});
  const Outcome full = polysim("run " + scene_ + " --duration 0.05", "/dev/full");
  EXPECT_EQ(full.status, 1);
  EXPECT_NE(full.err.find("cannot write to standard output"), std::string::npos) << full.err;
}

TEST_F(BadInput, ALogNamingTheSceneLeavesTheSceneAlone) {
  fs::copy_file(scene_, dir_ / "scene.json");
  const std::string before = slurp(dir_ / "scene.json");
  expectOneError(polysim("run scene.json --duration 0.05 --log ./scene.json"), {"--log ./scene.json: is the scene file"});
  EXPECT_EQ(slurp(dir_ / "scene.json"), before);
}

TEST_F(BadInput, StepsAndDurationsThatMakeNoRunAreRefused) {
  expectOneError(polysim("run " + scene_ + " --dt nan --duration 0.1"), {"--dt", "nan"});
  expectOneError(polysim("run " + scene_ + " --dt -0.01"), {"--dt", "-0.01"});
  expectOneError(polysim("run " + scene_ + " --dt 1e-300 --duration 0.1"), {"--duration / --dt", "more than 1e+08"});
  expectOneError(polysim("run " + scene_ + " --duration 0.001"), {"--duration: 0.001 s is shorter than one step"});
  expectOneError(polysim("run " + scene_ + " --duration 1e9 --dt 0.001"), {"1e+12 steps"});
  expectOneError(polysim("compare " + scene_ + " --duration inf"), {"--duration", "inf"});
}

TEST_F(BadInput, ScenesThatCannotBeSimulatedAreRefusedByName) {
  nlohmann::json base;
  std::ifstream(scene_) >> base;
  auto variant = [&](const std::string& name, const std::function<void(nlohmann::json&)>& change) {
    nlohmann::json s = base;
    change(s);
    write(name, s.dump());
    return name;
  };
  expectOneError(polysim("run " + variant("unnamed.json", [](nlohmann::json& s) { s["bodies"][1]["name"] = ""; })),
                 {"unnamed.json: body 1: name must not be empty"});
  expectOneError(polysim("run " + variant("tiny.json", [](nlohmann::json& s) { s["bodies"][1]["shape"]["size"] = {5e-5, 1, 1}; })),
                 {"tiny.json: body \"box\": shape: is 5e-05 m thick", "twice the contact tolerance"});
  fs::create_directories(dir_ / "folder.json");
  expectOneError(polysim("run folder.json"), {"folder.json: not a file"});
  // Finite numbers whose products overflow: the run stops with the body and the time.
  const std::string dense = variant("dense.json", [](nlohmann::json& s) {
    s["bodies"][1].erase("mass");
    s["bodies"][1]["density"] = 1e308;
  });
  expectOneError(polysim("run " + dense + " --duration 0.1"), {"dense.json: body \"box\": its state overflowed at t ="});
  const std::string fast = variant("fast.json", [](nlohmann::json& s) { s["bodies"][1]["velocity"] = {1e308, 0, 0}; });
  expectOneError(polysim("run " + fast + " --duration 0.1"), {"fast.json: body \"box\": its state overflowed"});
}

// Paths go into JSON (the step log names its scene), and JSON is UTF-8: a path that is
// not used to run to the end and fail there with a library's message.
TEST_F(BadInput, APathThatIsNotUtf8IsRefusedBeforeTheRun) {
  const std::string latin1 = "sc\xe8ne.json";
  fs::copy_file(scene_, dir_ / latin1);
  expectOneError(polysim("run '" + latin1 + "' --log out.jsonl"), {"SCENE: the path \"sc\xef\xbf\xbdne.json\" is not valid UTF-8"});
  EXPECT_FALSE(fs::exists(dir_ / "out.jsonl"));
  expectOneError(polysim("run " + scene_ + " --log 'l\xe8g.jsonl'"), {"--log: the path", "is not valid UTF-8"});
  expectOneError(polysim("make stack --out 'st\xe8" "ck.json'"), {"--out: the path", "is not valid UTF-8"});
  // A UTF-8 name runs.
  fs::copy_file(scene_, dir_ / "sc\xc3\xa8ne.json");
  EXPECT_EQ(polysim("run 'sc\xc3\xa8ne.json' --duration 0.05 --log 'l\xc3\xa8g.jsonl'").status, 0);
}

TEST_F(BadInput, AFileThatIsNotAnObjMeshIsSaidToBeNone) {
  auto sceneWith = [&](const std::string& obj) {
    const std::string name = "scene_" + std::to_string(std::hash<std::string>{}(obj)) + ".json";
    write(name, R"({"bodies": [{"name": "ground", "static": true, "shape": {"type": "box", "size": [10, 10, 1]},
                                 "position": [0, 0, -0.5]},
                               {"name": "cup", "shape": {"type": "obj", "file": ")" + obj + R"("}, "position": [0, 0, 2]}]})");
    return polysim("run " + name + " --duration 0.05");
  };
  const std::string prefix = "body \"cup\": shape: file \"";
  write("empty.obj", "");
  expectOneError(sceneWith("empty.obj"), {prefix + "empty.obj\": not an OBJ mesh: it has no vertex"});
  write("binary.obj", std::string("v 0 0 0\n\x7f" "ELF\x02\x01\x01\0\0", 17));
  expectOneError(sceneWith("binary.obj"), {prefix + "binary.obj\": line 2: binary data, not OBJ text"});
  fs::create_directories(dir_ / "folder.obj");
  expectOneError(sceneWith("folder.obj"), {prefix + "folder.obj\": not a file, so not an OBJ mesh"});
  write("passwd", "root:x:0:0:root:/root:/bin/bash\n");  // any text file a path may reach
  expectOneError(sceneWith("passwd"), {prefix + "passwd\": line 1: \"root:x:0:0:root:/root:/bin/bash\" is not an OBJ statement"});
  const std::string tetrahedron = "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nf 1 3 2\nf 1 2 4\nf 1 4 3\n";
  write("back.obj", tetrahedron + "f -3 -2 -9\n");
  expectOneError(sceneWith("back.obj"), {prefix + "back.obj\": line 8: face index -9 reaches back past the first vertex (4 read so far)"});
  write("ahead.obj", tetrahedron + "f 2 3 5\n");
  expectOneError(sceneWith("ahead.obj"), {prefix + "ahead.obj\": face 4 uses vertex 5, but the file has 4"});
  write("nofaces.obj", "# vertices only\nv 0 0 0\nv 1 0 0\nv 0 1 0\n");
  expectOneError(sceneWith("nofaces.obj"), {prefix + "nofaces.obj\": not an OBJ mesh: it has no face"});
  // A real OBJ with the statements a modeller writes (groups, materials, normals) is read.
  write("real.obj", "mtllib cup.mtl\no tet\n" + tetrahedron + "vn 0 0 1\nusemtl steel\ns off\nf 2//1 3//1 4//1\n");
  const Outcome real = sceneWith("real.obj");
  EXPECT_EQ(real.status, 0) << real.err;
}

}  // namespace
}  // namespace polysim::sim
