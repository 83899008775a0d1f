/// The tools' option tables (common/cli_options.h) and the planner setup every tool and node
/// reads from a config file (step/footstep_planner_setup.h).

#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "reach_trajopt/common/cli_options.h"
#include "reach_trajopt/common/config_yaml.h"
#include "reach_trajopt/common/error.h"
#include "reach_trajopt/step/footstep_planner_setup.h"

using namespace reach_trajopt;

namespace {

const CliTool kTool("tool", "input.json", "What it does.",
                    {{"--grid", "N", "grid size", "7"},
                     {"--flag", "", "a switch"},
                     {"--rpy", "r p y", "three angles", "", 3},
                     {"--policy", "P", "a policy", "", 1, "--mode"}});

CliArgs parse(std::vector<const char*> argv) {
  argv.insert(argv.begin(), "tool");
  return kTool.parse(static_cast<int>(argv.size()), argv.data());
}

std::string errorOf(std::vector<const char*> argv) {
  try {
    parse(argv);
  } catch (const RequestError& e) {
    return e.what();
  }
  return "";
}

}  // namespace

TEST(CliOptions, ValuesDefaultsFlagsAndPositionals) {
  const CliArgs none = parse({});
  EXPECT_FALSE(none.help());
  EXPECT_FALSE(none.given("--grid"));
  EXPECT_EQ(none.value("--grid"), "7");  // the table's default
  EXPECT_EQ(none.value("--policy"), "");
  EXPECT_TRUE(none.values("--rpy").empty());

  const CliArgs a = parse({"in.json", "--grid", "3", "--flag", "-", "--grid", "5", "--rpy", "0.1",
                           "-0.2", "0.3", "--mode", "kinematic"});
  EXPECT_TRUE(a.given("--grid"));
  EXPECT_EQ(a.value("--grid"), "5");  // the last one given
  EXPECT_TRUE(a.given("--flag"));
  EXPECT_EQ(a.values("--rpy"), (std::vector<std::string>{"0.1", "-0.2", "0.3"}));
  EXPECT_EQ(a.value("--policy"), "kinematic");  // the alias fills the table name
  EXPECT_EQ(a.positional(), (std::vector<std::string>{"in.json", "-"}));
  EXPECT_TRUE(parse({"-h"}).help());
  EXPECT_TRUE(parse({"--grid", "2", "--help"}).help());
}

TEST(CliOptions, UnknownOptionsAndMissingValuesAreNamed) {
  EXPECT_EQ(errorOf({"--gird", "3"}), "unknown option '--gird' (see tool --help)");
  EXPECT_EQ(errorOf({"--grid"}), "--grid: missing value");
  EXPECT_EQ(errorOf({"--rpy", "1", "2"}), "--rpy: missing value");
}

TEST(CliOptions, UsageListsEveryOptionWithItsDefault) {
  const std::string u = kTool.usage();
  EXPECT_EQ(u.rfind("usage: tool [options] input.json\n", 0), 0u) << u;
  for (const char* line :
       {"  --grid N ", "  --flag ", "  --rpy r p y ", "  --policy, --mode P ", "  -h, --help "})
    EXPECT_NE(u.find(line), std::string::npos) << line << " missing in\n" << u;
  EXPECT_NE(u.find("grid size (default: 7)"), std::string::npos) << u;
}

TEST(CliOptions, ATableWithARepeatedOrBadNameIsRejected) {
  EXPECT_THROW(CliTool("t", "", "", {{"--a", "", "x"}, {"--a", "", "y"}}), ReachError);
  EXPECT_THROW(CliTool("t", "", "", {{"--help", "", "x"}}), ReachError);
  EXPECT_THROW(CliTool("t", "", "", {{"grid", "N", "x"}}), ReachError);
}

TEST(FootstepPlannerSetup, ContactIsRequiredAndNamedWithTheFile) {
  const YamlSection no_contact = YamlSection::loadString("reach:\n  threads: 1\n", "c.yaml");
  try {
    FootstepPlannerSetup::fromYaml(no_contact);
    FAIL() << "a config without contact: was accepted";
  } catch (const ConfigError& e) {
    EXPECT_EQ(std::string(e.what()), "c.yaml: contact: missing section");
  }
}

TEST(FootstepPlannerSetup, ReadsTheShippedConfigAsThePlannerConfigDoes) {
  const std::string path = std::string(REACH_TRAJOPT_SOURCE_DIR) + "/config/biped.yaml";
  const YamlSection file = YamlSection::loadFile(path);
  const FootstepPlannerSetup s = FootstepPlannerSetup::fromYamlFile(path);
  const ContactConfig contact = ContactConfig::fromYaml(file.section("contact"));
  EXPECT_EQ(s.contact.left_sole_frame, contact.left_sole_frame);
  EXPECT_EQ(s.contact.mu, contact.mu);
  EXPECT_EQ(s.contact.half_length, contact.half_length);
  const FootstepPlannerConfig planner = FootstepPlannerConfig::fromYaml(file);
  EXPECT_EQ(s.planner.reach.horizon, planner.reach.horizon);
  EXPECT_EQ(s.planner.reach.delta, planner.reach.delta);
  EXPECT_EQ(s.planner.ocp.terminal_pelvis_height, s.planner.kinematics.pelvis_height);
  EXPECT_EQ(s.robot.urdf, RobotConfig::fromConfigFile(file).urdf);
}
