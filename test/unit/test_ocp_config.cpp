// TransitionOcpConfig: the shipped config/biped.yaml section loads and validates; bad values
// and unknown keys are rejected with the key named.
#include <gtest/gtest.h>

#include <string>

#include "reach_trajopt/common/config_yaml.h"
#include "reach_trajopt/common/error.h"
#include "reach_trajopt/ocp/ocp_config.h"

using namespace reach_trajopt;

TEST(TransitionOcpConfig, ShippedYamlLoads) {
  const YamlSection yaml =
      YamlSection::loadFile(std::string(REACH_TRAJOPT_SOURCE_DIR) + "/config/biped.yaml");
  const TransitionOcpConfig c = TransitionOcpConfig::fromYaml(yaml.section("ocp"));
  const TransitionOcpConfig d;
  EXPECT_EQ(c.segments, 4);  // the walking check's 0.2 s horizon: 50 ms knots
  EXPECT_GE(d.segments, 2);
  EXPECT_DOUBLE_EQ(c.check_interval, d.check_interval);
  EXPECT_DOUBLE_EQ(c.tolerance, 1e-4);
  EXPECT_DOUBLE_EQ(c.output_dt, 0.001);
}

TEST(TransitionOcpConfig, RejectsBadValues) {
  TransitionOcpConfig c;
  EXPECT_NO_THROW(c.validate());
  c.segments = 1;
  EXPECT_THROW(c.validate(), ReachError);
  c = TransitionOcpConfig();
  c.torque_margin = 1.0;
  EXPECT_THROW(c.validate(), ReachError);
  c = TransitionOcpConfig();
  c.time_limit = -1.0;
  EXPECT_THROW(c.validate(), ReachError);
  // Sizes that would allocate without bound (a 1e-9 s output grid: 5e9 samples over the longest
  // horizon) are refused by name.
  const auto refusedNaming = [](const std::string& key, const auto& set) {
    TransitionOcpConfig bad;
    set(bad);
    try {
      bad.validate();
      ADD_FAILURE() << key << " accepted";
    } catch (const ReachError& e) {
      EXPECT_NE(std::string(e.what()).find(key), std::string::npos) << e.what();
    }
  };
  refusedNaming("segments", [](TransitionOcpConfig& b) { b.segments = 201; });
  refusedNaming("check_interval", [](TransitionOcpConfig& b) { b.check_interval = 1e-6; });
  refusedNaming("output_dt", [](TransitionOcpConfig& b) { b.output_dt = 1e-9; });
  refusedNaming("threads", [](TransitionOcpConfig& b) { b.threads = 1000000000; });
  try {
    TransitionOcpConfig::fromYaml(YamlSection::loadString("segmentz: 3\n", "test.yaml"));
    ADD_FAILURE() << "unknown key accepted";
  } catch (const ReachError& e) {
    EXPECT_NE(std::string(e.what()).find("segmentz"), std::string::npos) << e.what();
  }
  EXPECT_THROW(TransitionOcpConfig::fromYaml(YamlSection::loadString("w_eps: -1\n", "t.yaml")),
               ReachError);
}
