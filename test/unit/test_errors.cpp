/// Errors a caller can tell apart: every library error is a ReachError, and its subclass says
/// what was wrong (the robot description, a QP's data, a request), with a message naming it.

#include <gtest/gtest.h>

#include <cmath>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include "reach_trajopt/common/cli_args.h"
#include "reach_trajopt/common/config_yaml.h"
#include "reach_trajopt/common/error.h"
#include "reach_trajopt/common/json_reader.h"
#include "reach_trajopt/common/text_file.h"
#include "reach_trajopt/contact/contact_config.h"
#include "reach_trajopt/model/robot_model.h"
#include "reach_trajopt/planner/lipm.h"
#include "reach_trajopt/planner/tvr_planner.h"
#include "reach_trajopt/qp/dual_active_set_qp.h"
#include "reach_trajopt/reach/reach_config.h"
#include "reach_trajopt/sim/bullet_world.h"
#include "thrown_message.h"

namespace reach_trajopt {
namespace {

using test::thrownMessage;

TEST(Errors, MissingUrdfIsAModelErrorNamingTheFile) {
  const std::string msg =
      thrownMessage<ModelError>([] { RobotModel::fromUrdfFile("/nonexistent/robot_xyz.urdf"); });
  EXPECT_NE(msg.find("robot_xyz.urdf"), std::string::npos) << msg;
}

TEST(Errors, UnknownFrameAndJointAreModelErrorsNamingThem) {
  const auto model = RobotModel::fromUrdfFile(REACH_TRAJOPT_SOURCE_DIR "/urdf/biped.urdf");
  EXPECT_NE(
      thrownMessage<ModelError>([&] { model->frameId("no_such_frame"); }).find("no_such_frame"),
      std::string::npos);
  EXPECT_NE(
      thrownMessage<ModelError>([&] { model->jointIndex("no_such_joint"); }).find("no_such_joint"),
      std::string::npos);
}

TEST(Errors, EmptyQpIsAQpInputError) {
  const std::string msg = thrownMessage<QpInputError>([] { qp::DualActiveSetQp solver(0, 0, 0); });
  EXPECT_NE(msg.find("variables"), std::string::npos) << msg;
}

TEST(Errors, BadConfigurationsAreConfigErrorsNamingTheKey) {
  const std::string unknown = thrownMessage<ConfigError>([] {
    YamlSection::loadString("contact:\n  mu: 0.7\n  mux: 1\n", "t.yaml")
        .section("contact")
        .requireOnlyKeys({"mu"});
  });
  EXPECT_NE(unknown.find("mux"), std::string::npos) << unknown;
  const std::string invalid = thrownMessage<ConfigError>([] {
    ContactConfig::fromYaml(
        YamlSection::loadString("contact:\n  mu: -1\n", "t.yaml").section("contact"));
  });
  EXPECT_NE(invalid.find("mu"), std::string::npos) << invalid;
  // A sample budget of the step planner's passes: the hull pass's own keys, named with their
  // budget.
  for (const char* key : {"children_per_parent", "initial_samples"}) {
    for (const char* value : {"0", "-3", "1000000"}) {
      const std::string hull = thrownMessage<ConfigError>([&] {
        ReachConfig::fromYaml(YamlSection::loadString(std::string("reach:\n  budgets:\n    hull:\n"
                                                                  "      ") +
                                                          key + ": " + value + "\n",
                                                      "t.yaml")
                                  .section("reach"))
            .validate();
      });
      EXPECT_NE(hull.find(std::string("budgets.hull.") + key), std::string::npos)
          << key << " = " << value << ": " << hull;
    }
  }
  // The keys that moved into reach.budgets: an old file gets an error naming the new place.
  for (const auto& [old_key, new_key] : std::vector<std::pair<std::string, std::string>>{
           {"initial_samples", "reach.budgets.full.initial_samples"},
           {"quick_max_boundary", "reach.budgets.quick.max_boundary"},
           {"quick_constraint_margin", "reach.budgets.quick.constraint_margin"},
           {"hull_children_per_parent", "reach.budgets.hull.children_per_parent"},
           {"forward_set_only", "hull pass"}}) {
    const std::string yaml = "reach:\n  " + old_key + ": 1\n";  // clang: no binding in a lambda
    const std::string moved = thrownMessage<ConfigError>([&yaml] {
      ReachConfig::fromYaml(YamlSection::loadString(yaml, "t.yaml").section("reach"));
    });
    EXPECT_NE(moved.find("reach." + old_key), std::string::npos) << moved;
    EXPECT_NE(moved.find(new_key), std::string::npos) << moved;
  }
  // The redraws of thin slices: a bounded number of rounds, a share in [0, 1]; the adaptive
  // budget's give-up gap: >= 0.
  const std::vector<std::pair<std::string, std::string>> bad_keys{
      {"redraw_rounds", "-1"}, {"redraw_rounds", "9"},   {"redraw_below", "-0.1"},
      {"redraw_below", "1.5"}, {"redraw_below", ".nan"}, {"give_up_gap", "-1"},
      {"give_up_gap", ".nan"}};
  for (const auto& bad : bad_keys) {
    const std::string yaml = "reach:\n  " + bad.first + ": " + bad.second + "\n";
    const std::string what = thrownMessage<ConfigError>([&] {
      ReachConfig::fromYaml(YamlSection::loadString(yaml, "t.yaml").section("reach")).validate();
    });
    EXPECT_NE(what.find(bad.first), std::string::npos) << yaml << ": " << what;
  }
}

TEST(Errors, RequestsAndParametersHaveTheirCategories) {
  // A request: its JSON, a tool option, a planner input.
  EXPECT_NE(thrownMessage<RequestError>([] { JsonReader::parse("{", "r.json"); }).find("r.json"),
            std::string::npos);
  EXPECT_NE(
      thrownMessage<RequestError>([] { parseIntOption("--steps", "5x", 0, 10); }).find("--steps"),
      std::string::npos);
  TvrInput in;
  in.stance_yaw = std::nan("");
  EXPECT_NE(thrownMessage<RequestError>([&] { TvrPlanner(TvrConfig{}).plan(in); }).find("yaw"),
            std::string::npos);
  // A parameter: a config struct's value.
  EXPECT_NE(thrownMessage<ConfigError>([] { Lipm(-1.0); }).find("height"), std::string::npos);
  TvrConfig bad;
  bad.t_s = 0.0;
  EXPECT_NE(thrownMessage<ConfigError>([&] { bad.validate(); }).find("t_s"), std::string::npos);
  // The simulator's robot description.
  const auto model = RobotModel::fromUrdfFile(REACH_TRAJOPT_SOURCE_DIR "/urdf/biped.urdf");
  EXPECT_NE(thrownMessage<ModelError>([&] {
              BulletWorld::fromUrdfFile("/nonexistent/sim_xyz.urdf", *model, SimConfig{});
            }).find("sim_xyz.urdf"),
            std::string::npos);
}

TEST(Errors, AnEndlessInputFileIsAnErrorNotAnUnboundedRead) {
  // /dev/zero never ends: every file reader stops at its bound and names the file.
  for (const std::string& msg :
       {thrownMessage<ConfigError>([] { YamlSection::loadFile("/dev/zero"); }),
        thrownMessage<ModelError>([] { RobotModel::fromUrdfFile("/dev/zero"); })}) {
    EXPECT_NE(msg.find("/dev/zero"), std::string::npos) << msg;
    EXPECT_NE(msg.find("larger than"), std::string::npos) << msg;
  }
  // The bound itself: a stream of exactly max_bytes is read, one byte more is refused.
  const std::string text(1000, 'x');
  std::istringstream exact(text), over(text + "y");
  EXPECT_EQ(readBounded<RequestError>(exact, "exact", text.size()), text);
  EXPECT_NE(thrownMessage<RequestError>([&] {
              readBounded<RequestError>(over, "the stream", text.size());
            }).find("the stream: larger than 1000 bytes"),
            std::string::npos);
}

TEST(Errors, EverySubclassIsAReachError) {
  EXPECT_THROW(throw ModelError("m"), ReachError);
  EXPECT_THROW(throw ConfigError("c"), ReachError);
  EXPECT_THROW(throw QpInputError("q"), ReachError);
  EXPECT_THROW(throw RequestError("r"), ReachError);
}

}  // namespace
}  // namespace reach_trajopt
