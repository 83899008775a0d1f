/// Errors a caller can tell apart: every library error is a ReachError, and its subclass says
/// what was wrong (the robot description, a QP's data, a request), with a message naming it.

#include <gtest/gtest.h>

#include <string>

#include "reach_trajopt/common/config_yaml.h"
#include "reach_trajopt/common/error.h"
#include "reach_trajopt/contact/contact_config.h"
#include "reach_trajopt/model/robot_model.h"
#include "reach_trajopt/qp/dual_active_set_qp.h"

namespace reach_trajopt {
namespace {

template <typename Expected, typename F>
std::string thrownMessage(F&& f) {
  try {
    f();
  } catch (const Expected& e) {
    return e.what();
  } catch (const std::exception& e) {
    ADD_FAILURE() << "wrong exception type: " << e.what();
    return "";
  }
  ADD_FAILURE() << "nothing thrown";
  return "";
}

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
}

TEST(Errors, EverySubclassIsAReachError) {
  EXPECT_THROW(throw ModelError("m"), ReachError);
  EXPECT_THROW(throw ConfigError("c"), ReachError);
  EXPECT_THROW(throw QpInputError("q"), ReachError);
  EXPECT_THROW(throw RequestError("r"), ReachError);
}

}  // namespace
}  // namespace reach_trajopt
