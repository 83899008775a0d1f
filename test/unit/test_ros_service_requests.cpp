// ROS layer, service request validation (no master): every malformed request is rejected with
// its reason, a valid one is filled from the model's forward kinematics.

#include <cmath>
#include <functional>
#include <limits>

#include <gtest/gtest.h>

#include "reach_trajopt/ros/service_requests.h"
#include "reach_trajopt/walk/standing_pose.h"

using namespace reach_trajopt;
namespace rb = reach_trajopt::ros_bridge;

namespace {

const std::string kUrdf = std::string(REACH_TRAJOPT_SOURCE_DIR) + "/urdf/biped.urdf";

struct Fixture {
  std::shared_ptr<const RobotModel> model = RobotModel::fromUrdfFile(kUrdf);
  ContactConfig contact;
  Eigen::VectorXd standing = standingConfiguration(*model, 0.6, "l_sole");
  geometry_msgs::Point foothold = [] {
    geometry_msgs::Point p;
    p.x = 0.1;
    p.y = -0.2;
    return p;
  }();

  rb::FootholdRequest parse(const std::string& frame, const std::string& mode,
                            const std::vector<double>& q, const std::vector<double>& qd,
                            double duration = 0.0) const {
    return rb::parseFootholdRequest(*model, contact, frame, mode, q, qd, foothold, duration, 0.08,
                                    standing);
  }
};

void expectReason(const std::function<void()>& f, const std::string& reason) {
  try {
    f();
    ADD_FAILURE() << "no error; expected '" << reason << "'";
  } catch (const ReachError& e) {
    EXPECT_NE(std::string(e.what()).find(reason), std::string::npos) << e.what();
  }
}

}  // namespace

TEST(RosServiceRequests, RejectsMalformedRequestsWithTheReason) {
  Fixture f;
  const int nq = f.model->nq();
  const double nan = std::numeric_limits<double>::quiet_NaN();
  expectReason([&] { f.parse("map", "SS-L", {}, {}); }, "unknown frame 'map'");
  expectReason([&] { f.parse("world", "", {}, {}); }, "empty contact set");
  expectReason([&] { f.parse("world", "flight", {}, {}); }, "empty contact set");
  expectReason([&] { f.parse("world", "DS", {}, {}); }, "no swing sole");
  expectReason([&] { f.parse("world", "SS-Q", {}, {}); }, "SS-Q");
  expectReason([&] { f.parse("world", "SS-L", std::vector<double>(3, 0.0), {}); },
               "expected size");
  std::vector<double> q(f.standing.data(), f.standing.data() + nq), qd(nq, 0.0);
  q[7] = nan;
  expectReason([&] { f.parse("world", "SS-L", q, qd); }, "non-finite");
  expectReason([&] { f.parse("world", "SS-L", {}, {}, -0.1); }, "must be positive");
  f.foothold.x = INFINITY;
  expectReason([&] { f.parse("world", "SS-L", {}, {}); }, "non-finite");
  f.foothold.x = 0.1;
  f.foothold.z = 0.25;
  expectReason([&] { f.parse("world", "SS-L", {}, {}); }, "must lie on the ground");
}

TEST(RosServiceRequests, ValidRequestTakesTheStanceSoleFromTheModel) {
  Fixture f;
  const rb::FootholdRequest r = f.parse("", "SS-R", {}, {});  // "" means "world"
  EXPECT_EQ(r.stance, Side::kRight);
  EXPECT_EQ(r.q, f.standing);
  EXPECT_TRUE(r.qd.isZero());
  EXPECT_DOUBLE_EQ(r.duration, 0.08);
  Workspace ws(*f.model);
  f.model->update(ws, f.standing, Eigen::VectorXd::Zero(f.model->nq()));
  const Eigen::Vector3d sole = f.model->framePose(ws, f.model->frameId("r_sole")).translation();
  EXPECT_LT((r.stance_contact.position - sole).norm(), 1e-12);
  EXPECT_NEAR(r.stance_contact.yaw, 0.0, 1e-9);
  EXPECT_EQ(r.target.position, Eigen::Vector3d(0.1, -0.2, 0.0));
  const rb::FootholdRequest r2 = f.parse("world", "SS-L", {}, {}, 0.3);
  EXPECT_EQ(r2.stance, Side::kLeft);
  EXPECT_DOUBLE_EQ(r2.duration, 0.3);
}

TEST(RosServiceRequests, TrajectoryMessageIsKnotMajor) {
  Fixture f;
  TransitionResult r;
  r.status = OcpStatus::kRelaxed;
  r.nlopt_status = "FTOL_REACHED";
  r.time = Eigen::VectorXd::LinSpaced(3, 0.0, 0.002);
  r.q = Eigen::MatrixXd::Zero(f.model->nq(), 3);
  r.q(1, 2) = 7.0;  // coordinate 1 at knot 2
  r.qd = r.q;
  r.u = Eigen::MatrixXd::Zero(f.model->nu(), 3);
  r.lambda = Eigen::MatrixXd::Zero(12, 3);
  r.lambda(8, 1) = 5.0;  // right sole fz at knot 1
  r.eps = Eigen::Vector2d(0.01, -0.02);
  const auto m = rb::toTransitionTrajectoryMsg(r, *f.model, {"l_sole", "r_sole"}, ros::Time(2.0));
  EXPECT_EQ(m.status, "relaxed");
  EXPECT_EQ(m.header.frame_id, "world");
  EXPECT_EQ(m.time.size(), 3u);
  EXPECT_EQ(m.q.size(), static_cast<size_t>(3 * f.model->nq()));
  EXPECT_EQ(m.q[2 * f.model->nq() + 1], 7.0);
  EXPECT_EQ(m.lambda[1 * 12 + 8], 5.0);
  EXPECT_EQ(m.actuated_joint_names.size(), static_cast<size_t>(f.model->nu()));
  EXPECT_DOUBLE_EQ(m.relaxation.y, -0.02);
  EXPECT_NE(m.message.find("FTOL_REACHED"), std::string::npos);
}
