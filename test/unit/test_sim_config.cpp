// SimConfig: the shipped config/sim.yaml loads and validates; bad values and unknown keys are
// rejected with a message naming the file and the key.
#include <gtest/gtest.h>

#include "reach_trajopt/common/config_yaml.h"
#include "reach_trajopt/sim/sim_config.h"

using namespace reach_trajopt;

TEST(SimConfig, ShippedYamlLoads) {
  const YamlSection file =
      YamlSection::loadFile(std::string(REACH_TRAJOPT_SOURCE_DIR) + "/config/sim.yaml");
  const SimConfig c = SimConfig::fromYaml(file.section("sim"));
  EXPECT_DOUBLE_EQ(c.time_step, 1e-3);
  EXPECT_GT(c.mu, 0.0);
  EXPECT_DOUBLE_EQ(c.gravity.z(), -9.81);
  EXPECT_TRUE(c.contacts);
  EXPECT_EQ(c.left_sole_frame, "l_sole");
  EXPECT_EQ(c.right_sole_frame, "r_sole");
}

TEST(SimConfig, RejectsBadValues) {
  EXPECT_NO_THROW(SimConfig{}.validate());
  SimConfig c;
  c.time_step = -1e-3;
  EXPECT_THROW(c.validate(), ReachError);
  c.time_step = 1e-9;  // 6e10 steps for a minute of walking
  EXPECT_THROW(c.validate(), ReachError);
  c = SimConfig{};
  c.mu = 0.0;
  EXPECT_THROW(c.validate(), ReachError);
  c = SimConfig{};
  c.gravity.x() = std::nan("");
  EXPECT_THROW(c.validate(), ReachError);
  c = SimConfig{};
  c.solver_iterations = 0;
  EXPECT_THROW(c.validate(), ReachError);
  c.solver_iterations = 1000000000;  // a step would take minutes
  EXPECT_THROW(c.validate(), ReachError);
  c = SimConfig{};
  c.right_sole_frame = c.left_sole_frame;
  EXPECT_THROW(c.validate(), ReachError);
}

TEST(SimConfig, YamlErrorsNameTheKey) {
  const YamlSection typo = YamlSection::loadString("sim:\n  time_stpe: 0.001\n", "typo.yaml");
  EXPECT_THROW(SimConfig::fromYaml(typo.section("sim")), ReachError);
  const YamlSection bad = YamlSection::loadString("sim:\n  mu: -1\n", "bad.yaml");
  try {
    SimConfig::fromYaml(bad.section("sim"));
    FAIL() << "expected ReachError";
  } catch (const ReachError& e) {
    EXPECT_NE(std::string(e.what()).find("bad.yaml"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("mu"), std::string::npos) << e.what();
  }
  const YamlSection g = YamlSection::loadString("sim:\n  gravity: [0, 0]\n", "g.yaml");
  EXPECT_THROW(SimConfig::fromYaml(g.section("sim")), ReachError);
}
