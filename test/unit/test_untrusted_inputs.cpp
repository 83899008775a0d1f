// Inputs from outside that used to cost minutes or pass silently (issue 43):
//  - YAML aliases nine levels deep (306 bytes, 2^9-fold walks: 31 s in a config file, 55 s as a
//    service's reach_config string) are refused at once, naming the source and the line; an
//    anchor that no alias uses is harmless YAML and still reads;
//  - one joint holding two leg roles is a config error naming both keys;
//  - an asymmetric G of qp_solve is reported as not symmetric, naming the entries.
#include <gtest/gtest.h>

#include <chrono>
#include <cstdio>
#include <fstream>
#include <functional>
#include <string>

#include "reach_trajopt/common/config_yaml.h"
#include "reach_trajopt/common/json_reader.h"
#include "reach_trajopt/model/robot_config.h"
#include "reach_trajopt/qp/qp_problem_json.h"
#include "reach_trajopt/reach/reach_config.h"
#include "thrown_message.h"

using namespace reach_trajopt;

namespace {

/// `levels` levels of nine aliases each to the level below (the issue's 306-byte document).
std::string aliasBomb(int levels) {
  std::string y = "l0: &l0 [1, 1, 1, 1, 1, 1, 1, 1, 1]\n";
  for (int i = 1; i <= levels; ++i) {
    const std::string prev = "*l" + std::to_string(i - 1);
    y += "l" + std::to_string(i) + ": &l" + std::to_string(i) + " [";
    for (int k = 0; k < 9; ++k) y += (k ? ", " : "") + prev;
    y += "]\n";
  }
  return y;
}

/// The message of the ConfigError `f` throws ("" and a test failure when none).
template <typename F>
std::string configError(F f) {
  return test::thrownMessage<ConfigError>(f);
}

double secondsOf(const std::function<void()>& f) {
  const auto t0 = std::chrono::steady_clock::now();
  f();
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

}  // namespace

TEST(YamlAliases, RefusedInAStringNamingSourceAndLine) {
  std::string message;
  const double s = secondsOf([&] {
    message = configError([] { YamlSection::loadString(aliasBomb(9), "reach_config"); });
  });
  EXPECT_NE(message.find("reach_config"), std::string::npos) << message;
  EXPECT_NE(message.find("line 2"), std::string::npos) << message;  // the first alias
  EXPECT_NE(message.find("alias"), std::string::npos) << message;
  EXPECT_LT(s, 5.0);  // refused before any expansion (was 55 s); generous for a loaded machine
}

TEST(YamlAliases, RefusedInAConfigFile) {
  const std::string path = ::testing::TempDir() + "/alias_bomb.yaml";
  {
    std::ofstream f(path);
    f << "reach:\n  initial_samples: 100\n" << aliasBomb(9);
  }
  const std::string message = configError([&] { YamlSection::loadFile(path); });
  EXPECT_NE(message.find(path), std::string::npos) << message;
  EXPECT_NE(message.find("line 4"), std::string::npos) << message;
  std::remove(path.c_str());
}

TEST(YamlAliases, OneAliasInsideASectionIsRefusedToo) {
  const std::string message =
      configError([] { YamlSection::loadString("base: &b 0.001\nreach:\n  dt: *b\n", "cfg"); });
  EXPECT_NE(message.find("cfg: line 3"), std::string::npos) << message;
}

TEST(YamlAliases, AnchorsWithoutAliasesStillRead) {
  const YamlSection y = YamlSection::loadString("reach:\n  dt: &b 0.002\n  horizon: 0.08\n", "s");
  double dt = 0.0;
  EXPECT_TRUE(y.section("reach").read("dt", dt));
  EXPECT_EQ(dt, 0.002);
}

TEST(YamlAliases, TheAliasScanEndsOnMalformedText) {
  // ",:" (found by fuzz_yaml_config): the scan for aliases looped over documents forever.
  for (const char* text : {",:", ",", ":,", "- ,:", "? ,\n: ,"}) {
    try {
      YamlSection::loadString(text, "fuzzed");
    } catch (const ConfigError&) {
    }
  }
  EXPECT_THROW(YamlSection::loadString(",:", "fuzzed"), ConfigError);
}

TEST(RobotConfigRoles, OneJointInTwoRolesNamesBothKeys) {
  const YamlSection y = YamlSection::loadString(
      "robot:\n  urdf: urdf/biped.urdf\n  left_knee: r_knee\n  right_knee: r_knee\n", "c.yaml");
  const std::string message = configError([&] { RobotConfig::fromConfigFile(y); });
  EXPECT_NE(message.find("robot.left_knee"), std::string::npos) << message;
  EXPECT_NE(message.find("robot.right_knee"), std::string::npos) << message;
  EXPECT_NE(message.find("r_knee"), std::string::npos) << message;
}

TEST(QpProblemJson, AsymmetricGIsNamedNotSymmetric) {
  const auto doc = JsonReader::parse(R"({"G": [[2, 1], [0, 2]], "g": [1, 1]})", "p.json");
  try {
    qp::readQpProblem(JsonReader(doc, "p.json"));
    ADD_FAILURE() << "an asymmetric G was read";
  } catch (const RequestError& e) {
    const std::string m = e.what();
    EXPECT_NE(m.find("not symmetric"), std::string::npos) << m;
    EXPECT_NE(m.find("G[1][0]"), std::string::npos) << m;
  }
  // Symmetric to rounding (a product A A^T): read.
  const auto ok =
      JsonReader::parse(R"({"G": [[2, 0.1], [0.10000000000000002, 2]], "g": [1, 1]})", "p.json");
  EXPECT_NO_THROW(qp::readQpProblem(JsonReader(ok, "p.json")));
}
