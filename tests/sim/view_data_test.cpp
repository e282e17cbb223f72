// What `polysim view` reads (sim/view_data.h): the log's poses frame by frame, checked
// against the log, and every way a log can be unfit for the page refused by line and
// field. The page itself is tested in headless Chromium (view_test.py).

#include "sim/view_data.h"

#include <gtest/gtest.h>

#include <cstring>
#include <fstream>
#include <string>
#include <vector>

#include "sim/run.h"
#include "tests/test_support.h"

namespace polysim::sim {
namespace {

std::string base64Of(const std::string& text) {
  return base64(reinterpret_cast<const unsigned char*>(text.data()), text.size());
}

TEST(ViewData, Base64IsRfc4648) {  // the RFC's own test vectors
  EXPECT_EQ(base64Of(""), "");
  EXPECT_EQ(base64Of("f"), "Zg==");
  EXPECT_EQ(base64Of("fo"), "Zm8=");
  EXPECT_EQ(base64Of("foo"), "Zm9v");
  EXPECT_EQ(base64Of("foob"), "Zm9vYg==");
  EXPECT_EQ(base64Of("fooba"), "Zm9vYmE=");
  EXPECT_EQ(base64Of("foobar"), "Zm9vYmFy");
  EXPECT_EQ(base64Of(std::string("\xff\xfe\x00", 3)), "//4A");
}

std::vector<float> decoded(const std::string& text) {
  static const std::string digits = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::vector<unsigned char> bytes;
  for (size_t i = 0; i + 3 < text.size(); i += 4) {
    unsigned v = 0;
    int pad = 0;
    for (int k = 0; k < 4; ++k) {
      const char c = text[i + static_cast<size_t>(k)];
      v = (v << 6) | (c == '=' ? (++pad, 0u) : static_cast<unsigned>(digits.find(c)));
    }
    for (int k = 0; k < 3 - pad; ++k) bytes.push_back(static_cast<unsigned char>((v >> (16 - 8 * k)) & 255));
  }
  std::vector<float> floats(bytes.size() / sizeof(float));
  std::memcpy(floats.data(), bytes.data(), floats.size() * sizeof(float));
  return floats;
}

class ViewLog : public ::testing::Test {
 protected:
  void SetUp() override {
    scene_ = loadScene(std::string(POLYSIM_SCENES_DIR) + "/tilted_drop.json");
    log_ = ::polysim::test::tempPath("polysim_view_data.jsonl");
    RunOptions options;
    options.logPath = log_;
    options.logContacts = true;
    options.duration = 1.0;
    runScene(scene_, options);
    std::ifstream in(log_);
    for (std::string line; std::getline(in, line);) lines_.push_back(line);
  }
  // The log with line `n` (1-based) replaced.
  std::string withLine(size_t n, const std::string& text) {
    const std::string path = ::polysim::test::tempPath("polysim_view_data_bad.jsonl");
    std::ofstream out(path);
    for (size_t k = 0; k < lines_.size(); ++k) out << (k + 1 == n ? text : lines_[k]) << "\n";
    return path;
  }
  std::string errorFor(const std::string& path) {
    try {
      logToViewJson(path, scene_);
    } catch (const std::runtime_error& e) {
      return e.what();
    }
    return "";
  }
  Scene scene_;
  std::string log_;
  std::vector<std::string> lines_;
};

TEST_F(ViewLog, FramesAreTheInitialStateThenEveryLoggedStep) {
  const nlohmann::ordered_json run = logToViewJson(log_, scene_);
  ASSERT_EQ(run["frames"].get<size_t>(), lines_.size() + 1);
  EXPECT_EQ(run["label"], std::filesystem::path(log_).stem().string());  // the file name without .jsonl
  EXPECT_EQ(run["dynamic"], nlohmann::ordered_json::array({1}));
  const std::vector<float> poses = decoded(run["poses"].get<std::string>());
  ASSERT_EQ(poses.size(), (lines_.size() + 1) * 10);
  const BodySpec& box = scene_.bodies[1];
  EXPECT_FLOAT_EQ(poses[2], static_cast<float>(box.position.z()));
  EXPECT_FLOAT_EQ(poses[3], static_cast<float>(box.orientation.w()));
  EXPECT_FLOAT_EQ(poses[4], static_cast<float>(box.orientation.x()));
  for (size_t n : {size_t{1}, lines_.size() / 2, lines_.size()}) {
    const nlohmann::ordered_json line = nlohmann::ordered_json::parse(lines_[n - 1]);
    const nlohmann::ordered_json& body = line["bodies"][0];
    std::vector<double> expected;
    for (const char* key : {"position", "orientation", "velocity"})
      for (const auto& x : body[key]) expected.push_back(x.get<double>());
    for (size_t f = 0; f < 10; ++f) EXPECT_FLOAT_EQ(poses[n * 10 + f], static_cast<float>(expected[f])) << "line " << n << " float " << f;
    EXPECT_DOUBLE_EQ(run["times"][n].get<double>(), line["t"].get<double>());
    const nlohmann::ordered_json& drawn = run["contactSets"][run["contactSetOf"][n].get<size_t>()];
    ASSERT_EQ(drawn.size(), line["contacts"].size());
    for (size_t p = 0; p < drawn.size(); ++p) {
      EXPECT_EQ(drawn[p]["a"], line["contacts"][p]["a"]);
      for (size_t c = 0; c < drawn[p]["contacts"].size(); ++c)
        EXPECT_EQ(drawn[p]["contacts"][c]["points"].dump(), line["contacts"][p]["contacts"][c]["points"].dump());
    }
  }
  // The box rests from about 0.6 s: its frames share one set of contacts.
  EXPECT_LT(run["contactSets"].size(), lines_.size() / 2);
  EXPECT_EQ(sceneNamedByLog(log_), std::filesystem::absolute(scene_.file).string());
}

TEST_F(ViewLog, AnUnfitLogIsRefusedByLineAndField) {
  EXPECT_NE(errorFor(withLine(3, "{\"step\": 3")).find("line 3: not JSON"), std::string::npos);
  EXPECT_NE(errorFor(withLine(2, R"({"step": 2, "events": [], "bodies": []})")).find("line 2: no \"t\""), std::string::npos);
  EXPECT_NE(errorFor(withLine(2, R"({"step": 2, "t": 0.1, "events": [], "bodies": []})")).find("line 2: no body \"box\""),
            std::string::npos);
  EXPECT_NE(errorFor(withLine(2, R"({"step": 2, "t": 0.1, "events": [], "bodies": [{"name": "crate"}]})"))
                .find("line 2: body 0: \"crate\" is not a dynamic body of"),
            std::string::npos);
  EXPECT_NE(errorFor(withLine(2, R"({"step": 2, "t": 0.1, "events": [], "bodies": [{"name": "box", "position": [0, 0]}]})"))
                .find("line 2: body 0: \"position\" is not 3 numbers"),
            std::string::npos);
  const std::string empty = ::polysim::test::tempPath("polysim_view_data_empty.jsonl");
  std::ofstream(empty) << "";
  EXPECT_NE(errorFor(empty).find("holds no step"), std::string::npos);
}

// A run killed while writing a line leaves it without its end of line: the page shows the
// steps before it, and says which line it left out.
TEST_F(ViewLog, ALastLineCutShortIsLeftOutAndNamed) {
  const std::string cut = ::polysim::test::tempPath("polysim_view_data_cut.jsonl");
  std::ofstream(cut) << lines_[0] << "\n" << lines_[1] << "\n" << lines_[2].substr(0, lines_[2].size() / 2);
  const nlohmann::ordered_json run = logToViewJson(cut, scene_);
  EXPECT_EQ(run["frames"], 3);  // the initial state and the two whole steps
  ASSERT_TRUE(run["cutShort"].is_string());
  EXPECT_NE(run["cutShort"].get<std::string>().find("line 3: cut short"), std::string::npos) << run["cutShort"];
  EXPECT_TRUE(logToViewJson(log_, scene_)["cutShort"].is_null());
}

}  // namespace
}  // namespace polysim::sim
