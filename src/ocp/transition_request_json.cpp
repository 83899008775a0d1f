/// \file transition_request_json.cpp
/// Strict reading of plan_transition requests (transition_request_json.h).

#include "reach_trajopt/ocp/transition_request_json.h"

#include <cmath>
#include <limits>
#include <sstream>

#include "reach_trajopt/reach/reach_request_json.h"

namespace reach_trajopt {

TransitionRequestJson readTransitionRequest(const JsonReader& r, int nq) {
  r.requireObject("a request object");
  r.requireOnlyKeys({"stance", "stance_pose", "swing_target", "horizon", "q0", "qd0", "qf", "qdf",
                     "relaxation", "slices", "seed"});
  TransitionRequestJson out;
  TransitionRequest& q = out.request;
  q.stance = r.at("stance").choice({"left", "right"}) == "left" ? Side::kLeft : Side::kRight;
  q.stance_contact = readFoothold(r.at("stance_pose"));
  q.target = readFoothold(r.at("swing_target"));
  const JsonReader h = r.at("horizon");
  q.horizon = h.number();
  if (!(q.horizon > 0.0) || q.horizon > kMaxTransitionHorizon) {
    std::ostringstream os;
    os << "expected a swing duration in (0, " << kMaxTransitionHorizon << "] s, got " << q.horizon;
    h.fail(os.str());
  }
  q.q0 = r.vector("q0", nq);
  q.qd0 = Eigen::VectorXd::Zero(nq);
  r.optionalVector("qd0", nq, q.qd0);
  out.has_qf = r.optionalVector("qf", nq, q.qf);
  if (out.has_qf) {
    q.qdf = Eigen::VectorXd::Zero(nq);
    r.optionalVector("qdf", nq, q.qdf);
  } else if (r.has("qdf")) {
    r.at("qdf").fail("given without \"qf\"");
  }
  std::string mode = "auto";
  r.optionalChoice("relaxation", {"auto", "strict", "relaxed"}, mode);
  q.relaxation = mode == "auto"     ? RelaxationMode::kAuto
                 : mode == "strict" ? RelaxationMode::kStrict
                                    : RelaxationMode::kRelaxed;
  if (r.has("slices")) {
    const JsonReader slices = r.at("slices");
    const std::size_t n = slices.requireArray(0, kMaxRequestSlices);
    for (std::size_t k = 0; k < n; ++k) {
      const JsonReader s = slices.at(k);
      s.requireObject("{\"time\": t, \"A\": [[ax, ay], ...], \"b\": [...]}");
      s.requireOnlyKeys({"time", "A", "b"});
      ReachableSlice slice;
      slice.time = s.number("time");
      const JsonReader A = s.at("A");
      const std::size_t m = A.requireArray(1, kMaxSliceRows);
      slice.A = A.matrix(static_cast<Eigen::Index>(m), 2);
      slice.b = s.vector("b", static_cast<Eigen::Index>(m));
      q.slices.push_back(slice);
    }
  }
  if (r.has("seed")) {
    const JsonReader s = r.at("seed");
    s.requireObject("{\"time\": [...], \"q\": [[n_q numbers], ...]}");
    s.requireOnlyKeys({"time", "q"});
    const JsonReader t = s.at("time");
    const std::size_t n = t.requireArray(1, kMaxSeedSamples);
    q.seed.time = t.vector(static_cast<Eigen::Index>(n));
    q.seed.q = s.at("q").matrix(static_cast<Eigen::Index>(n), nq).transpose();
  }
  return out;
}

namespace {

nlohmann::json flatPose(const Eigen::Isometry3d& pose) {
  const Eigen::Vector3d p = pose.translation();
  return {{"position", {p.x(), p.y(), p.z()}},
          {"yaw", std::atan2(pose.linear()(1, 0), pose.linear()(0, 0))}};
}

std::vector<double> values(const Eigen::VectorXd& v) {
  return std::vector<double>(v.data(), v.data() + v.size());
}

}  // namespace

nlohmann::json transitionRequestToJson(const TransitionRequest& r) {
  nlohmann::json j;
  j["stance"] = r.stance == Side::kLeft ? "left" : "right";
  j["stance_pose"] = flatPose(r.heldPose());
  j["swing_target"] = flatPose(r.targetPose());
  j["horizon"] = r.horizon;
  j["q0"] = values(r.q0);
  j["qd0"] = values(r.qd0);
  if (r.qf.size() > 0) {
    j["qf"] = values(r.qf);
    j["qdf"] = values(r.qdf);
  }
  j["relaxation"] = r.relaxation == RelaxationMode::kAuto     ? "auto"
                    : r.relaxation == RelaxationMode::kStrict ? "strict"
                                                              : "relaxed";
  if (!r.slices.empty()) {
    nlohmann::json slices = nlohmann::json::array();
    for (const ReachableSlice& s : r.slices) {
      nlohmann::json A = nlohmann::json::array();
      for (Eigen::Index i = 0; i < s.A.rows(); ++i) A.push_back({s.A(i, 0), s.A(i, 1)});
      slices.push_back({{"time", s.time}, {"A", A}, {"b", values(s.b)}});
    }
    j["slices"] = slices;
  }
  return j;
}

}  // namespace reach_trajopt
