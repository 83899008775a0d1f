/// \file footstep_plan_request_json.cpp
/// FootstepPlanRequest to and from JSON (see the header).

#include "reach_trajopt/step/footstep_plan_request_json.h"

#include <sstream>
#include <vector>

#include "reach_trajopt/ocp/transition_request.h"

namespace reach_trajopt {

namespace {

std::vector<double> asVector(const Eigen::Ref<const Eigen::VectorXd>& v) {
  return std::vector<double>(v.data(), v.data() + v.size());
}

}  // namespace

nlohmann::json footstepPlanRequestJson(const FootstepPlanRequest& r) {
  // The stance sole as a flat pose (the planner reads its position and heading only).
  const Eigen::Matrix<double, 3, 3, Eigen::RowMajor> R = r.stance_contact.pose().linear();
  nlohmann::json j = {{"stance", r.stance == Side::kLeft ? "left" : "right"},
                      {"stance_pose",
                       {{"position", asVector(r.stance_contact.position)},
                        {"rotation", std::vector<double>(R.data(), R.data() + 9)}}},
                      {"target", asVector(r.target.position)},
                      {"target_yaw", r.target.yaw},
                      {"q", asVector(r.q0)},
                      {"qd", asVector(r.qd0)}};
  if (r.touchdown_com)
    j["touchdown_com"] = {{"p", asVector(r.touchdown_com->p)},
                          {"pd", asVector(r.touchdown_com->pd)}};
  if (r.reach) j["reach_horizon"] = r.reach->horizon;
  return j;
}

FootstepPlanRequest readFootstepPlanRequest(const JsonReader& r, int nq,
                                            const ReachConfig& base_reach,
                                            const FootstepPlanRequest& base) {
  try {
    r.requireObject("a footstep request object");
    r.requireOnlyKeys({"stance", "stance_pose", "target", "target_yaw", "q", "qd", "touchdown_com",
                       "reach_horizon"});
    FootstepPlanRequest out = base;
    out.stance = r.at("stance").choice({"left", "right"}) == "left" ? Side::kLeft : Side::kRight;
    const JsonReader pose = r.at("stance_pose");
    pose.requireObject("{\"position\": [x, y, z], \"rotation\": [9 numbers]}");
    pose.requireOnlyKeys({"position", "rotation"});
    const Eigen::VectorXd p = pose.vector("position", 3);
    const Eigen::VectorXd rot = pose.vector("rotation", 9);
    const Eigen::Matrix3d R =
        Eigen::Map<const Eigen::Matrix<double, 3, 3, Eigen::RowMajor>>(rot.data());
    if (!(R.transpose() * R).isApprox(Eigen::Matrix3d::Identity(), 1e-6) || R.determinant() < 0.0)
      pose.at("rotation").fail("expected a rotation matrix (orthonormal, determinant 1)");
    Eigen::Isometry3d stance_pose = Eigen::Isometry3d::Identity();
    stance_pose.linear() = R;
    stance_pose.translation() = p;
    out.stance_contact = FlatContact::fromPose(stance_pose);
    out.target.position = r.vector("target", 3);
    out.target.yaw = out.stance_contact.yaw;  // none: the stance sole's heading
    r.optionalNumber("target_yaw", out.target.yaw);
    out.q0 = r.vector("q", nq);
    out.qd0 = r.vector("qd", nq);
    if (r.has("touchdown_com")) {
      const JsonReader c = r.at("touchdown_com");
      c.requireObject("{\"p\": [x, y], \"pd\": [vx, vy]}");
      c.requireOnlyKeys({"p", "pd"});
      out.touchdown_com = LipmState{c.vector("p", 2), c.vector("pd", 2)};
    }
    double horizon = 0.0;
    if (r.optionalNumber("reach_horizon", horizon)) {
      if (!(horizon > 0.0) || horizon > kMaxTransitionHorizon) {
        std::ostringstream os;
        os << "expected a horizon in (0, " << kMaxTransitionHorizon << "] s, got " << horizon;
        r.at("reach_horizon").fail(os.str());
      }
      ReachConfig reach = base_reach;
      reach.horizon = horizon;
      reach.validate();
      out.reach = reach;
    }
    return out;
  } catch (const RequestError&) {
    throw;
  } catch (const ReachError& e) {
    throw RequestError(e.what());
  }
}

}  // namespace reach_trajopt
