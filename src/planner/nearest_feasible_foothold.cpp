/// \file nearest_feasible_foothold.cpp
/// Ring search for the closest kinematically feasible foothold (see the header).

#include "reach_trajopt/planner/nearest_feasible_foothold.h"

#include <cmath>

#include "reach_trajopt/common/config_fields.h"
#include "reach_trajopt/common/error.h"

namespace reach_trajopt {

void NearestFootholdConfig::validate() const { fields().checkRanges(*this); }

const ConfigFields<NearestFootholdConfig>& NearestFootholdConfig::fields() {
  using C = NearestFootholdConfig;
  static const ConfigFields<C> f =
      ConfigFields<C>("NearestFootholdConfig", "nearest_foothold",
                      "include/reach_trajopt/planner/nearest_feasible_foothold.h",
                      "Ring search for the closest kinematically feasible foothold when the TVR "
                      "one fails the kinematic check (not in config/biped.yaml: the defaults).")
          .add("ring_step", &C::ring_step, "m", Range::positive(), "radius increment between rings")
          .add("rings", &C::rings, "", Range::between(1, 1000), "rings searched")
          .add("directions", &C::directions, "", Range::between(1, 360),
               "points per ring, first along +x")
          .add("max_checked", &C::max_checked, "", Range::between(1, 100),
               "on_fail nearest_reachable: feasible candidates the reachability check examines "
               "per step, nearest first")
          .add("retreat_checks", &C::retreat_checks, "", Range::between(0, 20),
               "on_fail nearest_reachable, the retreat: checks of points on the segment from "
               "the target to the swing sole at x_0, by bisection for the certified point "
               "nearest the target (0: none); after the rings' candidates, before them for a "
               "kinematically infeasible target")
          .add("retreat_kinematic_points", &C::retreat_kinematic_points, "",
               Range::between(0, 1000),
               "on_fail nearest_reachable, the retreat from a kinematically infeasible target: "
               "evenly spaced points of the segment the kinematic check alone examines, nearest "
               "the target first; the retreat's checks start at the first that passes it (0: "
               "the bisection starts at the middle)")
          .add("time_limit", &C::time_limit, "s", Range::positive(),
               "on_fail nearest_reachable: wall-clock time the candidates (the rings' and the "
               "retreat's) take together at most, after the target's own plan (or the "
               "request's deadline when earlier); a safety net, the counts end the search "
               "first");
  return f;
}

NearestFootholdConfig NearestFootholdConfig::fromYaml(const YamlSection& s) {
  return fields().read(s);
}

NearestFeasibleFoothold::NearestFeasibleFoothold(
    std::shared_ptr<const KinematicFeasibility> kinematics, const NearestFootholdConfig& config)
    : kinematics_(std::move(kinematics)), config_(config) {
  if (!kinematics_) throw ReachError("NearestFeasibleFoothold: null kinematic check");
  config_.validate();
}

std::vector<CandidateOutcome> checkFootholdCandidates(const KinematicFeasibility& kinematics,
                                                      const FootholdCandidates& batch,
                                                      bool stop_at_first_decisive) {
  std::vector<CandidateOutcome> outcomes;
  outcomes.reserve(batch.candidates.size());
  for (const FlatContact& p : batch.candidates) {
    CandidateOutcome o;
    try {
      o.kinematics = kinematics.check(batch.stance, batch.stance_contact, p, batch.q_init,
                                      batch.pelvis_position);
    } catch (const ReachError& e) {
      o.error = e.what();
    }
    const bool decisive = !o.error.empty() || o.kinematics.feasible;
    outcomes.push_back(std::move(o));
    if (decisive && stop_at_first_decisive) break;
  }
  return outcomes;
}

std::vector<FlatContact> NearestFeasibleFoothold::ringCandidates(const FlatContact& target,
                                                                 int ring) const {
  std::vector<FlatContact> candidates;
  candidates.reserve(config_.directions);
  for (int d = 0; d < config_.directions; ++d) {
    const double angle = 2.0 * M_PI * d / config_.directions;
    FlatContact p = target;
    p.position = target.position +
                 ring * config_.ring_step * Eigen::Vector3d(std::cos(angle), std::sin(angle), 0);
    candidates.push_back(p);
  }
  return candidates;
}

std::optional<NearestFoothold> NearestFeasibleFoothold::find(
    Side stance, const FlatContact& stance_contact, const FlatContact& target,
    const Eigen::VectorXd& q_init, const std::optional<Eigen::Vector3d>& pelvis_position,
    const CandidateCheck& check) const {
  FootholdCandidates batch{stance, stance_contact, {}, q_init, pelvis_position};
  for (int ring = 1; ring <= config_.rings; ++ring) {
    batch.candidates = ringCandidates(target, ring);
    std::vector<CandidateOutcome> outcomes =
        check ? check(batch) : checkFootholdCandidates(*kinematics_, batch, true);
    for (size_t i = 0; i < outcomes.size(); ++i) {
      if (!outcomes[i].error.empty()) throw ReachError(outcomes[i].error);
      if (outcomes[i].kinematics.feasible)
        return NearestFoothold{batch.candidates[i], std::move(outcomes[i].kinematics)};
    }
    if (outcomes.size() != batch.candidates.size())
      throw ReachError("nearest feasible foothold: the candidate check answered " +
                       std::to_string(outcomes.size()) + " of " +
                       std::to_string(batch.candidates.size()) + " candidates of ring " +
                       std::to_string(ring));
  }
  return std::nullopt;
}

}  // namespace reach_trajopt
