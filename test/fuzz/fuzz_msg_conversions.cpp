/// \file fuzz_msg_conversions.cpp
/// Fuzzes the service request -> core conversions of src/ros/ (parseFootholdRequest, the
/// duration's ReachConfig and its resource check, footstepProblem) with the fields of a
/// CheckReachability / PlanTransition request drawn from the input: any frame and mode string,
/// q / qd of any length, any doubles (NaN, inf, huge) and sample counts.

#include <fuzzer/FuzzedDataProvider.h>

#include "fuzz_common.h"
#include "reach_trajopt/ros/conversions.h"
#include "reach_trajopt/ros/service_requests.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  using namespace reach_trajopt;
  namespace rb = reach_trajopt::ros_bridge;
  static const ContactConfig contact;
  const auto& model = reach_fuzz::biped();
  static const Eigen::VectorXd standing = [&] {
    Eigen::VectorXd q = model->neutralConfiguration();
    q[2] = 1.0;
    return q;
  }();
  FuzzedDataProvider in(data, size);
  const std::string frame = in.ConsumeBool() ? "world" : in.ConsumeRandomLengthString(16);
  const std::string mode =
      in.ConsumeBool() ? (in.ConsumeBool() ? "SS-L" : "SS-R") : in.ConsumeRandomLengthString(16);
  auto vec = [&] {
    std::vector<double> v(in.ConsumeBool() ? model->nq() : in.ConsumeIntegralInRange(0, 40));
    for (double& x : v)
      x = in.ConsumeBool() ? in.ConsumeFloatingPointInRange(-2.0, 2.0)
                           : in.ConsumeFloatingPoint<double>();
    return v;
  };
  const std::vector<double> q = vec(), qd = vec();
  geometry_msgs::Point p;
  p.x = in.ConsumeFloatingPoint<double>();
  p.y = in.ConsumeFloatingPoint<double>();
  p.z = in.ConsumeBool() ? 0.0 : in.ConsumeFloatingPoint<double>();
  const double duration = in.ConsumeFloatingPoint<double>();
  const uint32_t samples = in.ConsumeIntegral<uint32_t>();
  try {
    const ContactTransition r =
        rb::parseFootholdRequest(*model, contact, frame, mode, q, qd, p, duration, 0.4, standing);
    ReachConfig config = rb::reachConfigForDuration(ReachConfig{}, r.horizon);
    if (samples > 0 && samples <= static_cast<uint32_t>(ReachLimits::kMaxInitialSamples))
      config.budgets.full.initial_samples = static_cast<int>(samples);
    config.validate();
    config.requireResourcesWithinLimits(model->nq());
    KinematicFeasibilityResult ik;
    ik.q_f = r.q0;
    ik.qd_f = r.qd0;
    (void)footstepProblem(r, ik.q_f, ik.qd_f);
    (void)rb::fromPointMsg(p);
  } catch (const ReachError&) {
  }
  return 0;
}
