/// \file walking_policy.cpp
/// The walking policies and their presets (see the header).

#include "reach_trajopt/walk/walking_policy.h"

#include <sstream>
#include <utility>

#include "reach_trajopt/common/enum_names.h"
#include "reach_trajopt/common/error.h"
#include "reach_trajopt/step/footstep_transition_planner.h"

namespace reach_trajopt {
namespace {

using Check = WalkingPolicy::FootholdCheck;
using OnFail = WalkingPolicy::OnFailedCheck;
using Swing = WalkingPolicy::SwingSource;

template <typename E>
using Names = EnumNames<E>;

const Names<bool>& boundNames() {
  static const Names<bool> n = {{"on", true}, {"off", false}};
  return n;
}
const Names<Check>& checkNames() {
  static const Names<Check> n = {{"none", Check::kNone},
                                 {"kinematic", Check::kKinematic},
                                 {"reachability", Check::kReachability}};
  return n;
}
const Names<OnFail>& onFailNames() {
  static const Names<OnFail> n = {{"clip_to_bounds", OnFail::kClipToBounds},
                                  {"nearest_feasible", OnFail::kNearestFeasible},
                                  {"relaxed_ocp", OnFail::kRelaxedOcp},
                                  {"nearest_reachable", OnFail::kNearestReachable}};
  return n;
}
const Names<Swing>& swingNames() {
  static const Names<Swing> n = {{"interpolation", Swing::kInterpolation}, {"ocp", Swing::kOcp}};
  return n;
}

/// The value of `part=value` from its name table. \throws RequestError listing the names.
template <typename E>
E partValue(const Names<E>& names, const std::string& part, const std::string& value) {
  for (const auto& n : names)
    if (value == n.first) return n.second;
  throw RequestError("walking policy: " + part + "=" + value + ": expected " + part + "=" +
                     namesList(names));
}

WalkingPolicy make(const char* name, bool bounds, Check check, OnFail on_fail, Swing swing) {
  WalkingPolicy p;
  p.name = name;
  p.heuristic_bounds = bounds;
  p.check = check;
  p.on_failed_check = on_fail;
  p.swing = swing;
  return p;
}

const std::vector<WalkingPolicy>& presets() {
  static const std::vector<WalkingPolicy> p = {
      make("baseline", true, Check::kNone, OnFail::kClipToBounds, Swing::kInterpolation),
      make("unbounded", false, Check::kNone, OnFail::kClipToBounds, Swing::kInterpolation),
      make("kinematic", false, Check::kKinematic, OnFail::kNearestReachable, Swing::kOcp),
      make("proposed", false, Check::kReachability, OnFail::kNearestReachable, Swing::kOcp),
  };
  return p;
}

}  // namespace

const std::vector<std::string>& WalkingPolicy::presetNames() {
  static const std::vector<std::string> names = [] {
    std::vector<std::string> n;
    for (const WalkingPolicy& p : presets()) n.push_back(p.name);
    return n;
  }();
  return names;
}

WalkingPolicy WalkingPolicy::preset(const std::string& name) {
  std::string known;
  for (const WalkingPolicy& p : presets()) {
    if (p.name == name) return p;
    known += std::string(known.empty() ? "" : ", ") + p.name;
  }
  throw RequestError("walking policy: unknown preset '" + name + "' (presets: " + known + ")");
}

WalkingPolicy WalkingPolicy::parse(const std::string& spec) {
  std::vector<std::string> tokens;
  std::stringstream ss(spec);
  for (std::string t; std::getline(ss, t, ',');) tokens.push_back(t);
  if (tokens.empty() || tokens.front().empty())
    throw RequestError("walking policy: empty; expected <preset>[,part=value...]");
  WalkingPolicy p = preset(tokens.front());
  for (std::size_t i = 1; i < tokens.size(); ++i) {
    const std::string& t = tokens[i];
    const auto eq = t.find('=');
    if (eq == std::string::npos)
      throw RequestError("walking policy: '" + t + "': expected part=value after the preset");
    const std::string part = t.substr(0, eq), value = t.substr(eq + 1);
    if (part == "bounds")
      p.heuristic_bounds = partValue(boundNames(), part, value);
    else if (part == "check")
      p.check = partValue(checkNames(), part, value);
    else if (part == "on_fail")
      p.on_failed_check = partValue(onFailNames(), part, value);
    else if (part == "swing")
      p.swing = partValue(swingNames(), part, value);
    else
      throw RequestError("walking policy: unknown part '" + part +
                         "' (parts: bounds, check, on_fail, swing)");
  }
  // A changed part makes it another policy, unless it equals a preset.
  p.name = "custom";
  for (const WalkingPolicy& known : presets())
    if (known == p) p.name = known.name;
  p.validate();
  return p;
}

const char* WalkingPolicy::actionName(OnFailedCheck action) {
  return nameOf(onFailNames(), action);
}

std::string WalkingPolicy::definition() const {
  std::ostringstream os;
  os << "bounds=" << nameOf(boundNames(), heuristic_bounds)
     << " check=" << nameOf(checkNames(), check)
     << " on_fail=" << (checksFoothold() ? nameOf(onFailNames(), on_failed_check) : "-")
     << " swing=" << nameOf(swingNames(), swing);
  return os.str();
}

bool WalkingPolicy::clipsFailedStep(const FootstepTransition& step) const {
  if (on_failed_check == OnFail::kClipToBounds) return true;
  if (step.foothold_source == FootholdSource::kTarget && !step.usable()) return true;
  if (check != Check::kReachability || step.reachable) return false;
  // The planner's fields are the stand-in's; the target's own verdict is kept beside them
  // (nearest_reachable), or they are the target's (nearest_feasible's kinematic ring search).
  const bool target_kinematically_infeasible =
      !step.kinematically_feasible || step.target_verdict == StepVerdict::kKinematicallyInfeasible;
  return step.foothold_source == FootholdSource::kNearestFeasible ||
         (step.foothold_source == FootholdSource::kRelaxed && target_kinematically_infeasible);
}

void WalkingPolicy::validate() const {
  if (swing == Swing::kOcp && check == Check::kNone)
    throw ConfigError(
        "walking policy: swing=ocp needs check=kinematic or check=reachability (the OCP's "
        "x_f is the check's IK posture)");
}

}  // namespace reach_trajopt
