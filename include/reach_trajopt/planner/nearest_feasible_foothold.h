#pragma once
/// \file nearest_feasible_foothold.h
/// The fallback of a foothold that fails the kinematic check of Sec. III-B (e.g. a TVR step
/// that puts one sole through the other): the closest kinematically feasible foothold, searched
/// on rings of growing radius around the target (`rings` rings `ring_step` apart, `directions`
/// points per ring, the first direction along +x, counter-clockwise). The first feasible point
/// found is returned with its IK posture; none within rings * ring_step is a result, not an
/// error. Not in the paper (its planner never proposes such steps); see docs/method.md.
/// The candidates of one ring are independent IK problems: they are checked as one batch by a
/// CandidateCheck, in this process by default or elsewhere (e.g. by worker nodes, in parallel);
/// the first feasible one in direction order is the answer either way, so where the batch ran
/// does not change the result.

#include <Eigen/Core>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "reach_trajopt/planner/kinematic_feasibility.h"

namespace reach_trajopt {

class YamlSection;
template <typename Config>
class ConfigFields;

/// Parameters of the ring search. Defaults: 15 rings of 2 cm (0.3 m), 12 directions.
struct NearestFootholdConfig {
  double ring_step = 0.02;  ///< radius increment between rings [m]
  int rings = 15;           ///< rings searched
  int directions = 12;      ///< points per ring
  /// on_fail nearest_reachable (step/footstep_transition_planner.h): kinematically feasible
  /// candidates the reachability check may examine per step, nearest first.
  int max_checked = 4;
  /// on_fail nearest_reachable, the retreat: reachability checks of points on the segment from
  /// the target to the swing sole's position at x_0 (where the foot comes from), by bisection
  /// for the certified point nearest the target (0: none); after the rings' candidates, or
  /// before them for a kinematically infeasible target.
  int retreat_checks = 3;
  /// The retreat from a kinematically infeasible target: evenly spaced points of that segment
  /// the kinematic check alone (an IK each) examines, nearest the target first, for the first
  /// that passes it; the reachability checks start there (0: the bisection starts at the middle).
  int retreat_kinematic_points = 32;
  /// on_fail nearest_reachable: wall-clock seconds the candidates (the rings' and the
  /// retreat's) may take together after the target's own plan, or the request's deadline when
  /// earlier [s]. A safety net: the counts above end the search first (the biped's slowest
  /// steps of its push envelope plan for up to about 30 s on one thread: a target and 7
  /// candidates, none certified), so that a walk that pauses for its plans does not depend on
  /// the machine; a walk that pays for them has the step's deadline.
  double time_limit = 120.0;
  /// \throws ConfigError naming the first bad field.
  void validate() const;
  /// The YAML keys of section `nearest_foothold:` (the member names), units and meaning.
  static const ConfigFields<NearestFootholdConfig>& fields();
  /// Reads fields() from a YAML section, then validates.
  static NearestFootholdConfig fromYaml(const YamlSection& section);
  double searchRadius() const { return rings * ring_step; }  ///< [m]
};

/// One ring's candidate footholds, each checked with the same stance and IK start.
struct FootholdCandidates {
  Side stance = Side::kLeft;            ///< the held sole
  FlatContact stance_contact;           ///< where it is held [m, rad]
  std::vector<FlatContact> candidates;  ///< the swing sole's candidate footholds [m, rad]
  Eigen::VectorXd q_init;               ///< IK start (size n_q)
  std::optional<Eigen::Vector3d> pelvis_position;  ///< see KinematicFeasibility::check [m]
};

/// The check of one candidate: the IK's result, or the message of the error its check threw
/// (e.g. a candidate outside the workspace); `error` empty means `kinematics` holds.
struct CandidateOutcome {
  KinematicFeasibilityResult kinematics;
  std::string error;
  /// The candidate was checked and passed the kinematic check.
  bool feasible() const { return error.empty() && kinematics.feasible; }
};

/// Checks a batch of candidates; returns one outcome per candidate in order, or a prefix that
/// ends at the first feasible or failed one (what the search needs; the rest is not looked at).
/// \throws ReachError when the batch could not be checked at all.
using CandidateCheck = std::function<std::vector<CandidateOutcome>(const FootholdCandidates&)>;

/// Checks `batch` in this process, in order, with `kinematics`. `stop_at_first_decisive`: stop
/// after the first feasible or failed candidate (the search's own use); false: every candidate
/// (a worker answering part of a ring).
std::vector<CandidateOutcome> checkFootholdCandidates(const KinematicFeasibility& kinematics,
                                                      const FootholdCandidates& batch,
                                                      bool stop_at_first_decisive);

/// A feasible foothold found near the target.
struct NearestFoothold {
  FlatContact foothold;                   ///< the feasible foothold [m, rad]
  KinematicFeasibilityResult kinematics;  ///< its IK posture q_f
};

/// @brief Ring search for the closest kinematically feasible foothold to a target.
class NearestFeasibleFoothold {
 public:
  NearestFeasibleFoothold(std::shared_ptr<const KinematicFeasibility> kinematics,
                          const NearestFootholdConfig& config);
  /// \param stance, stance_contact  the held sole
  /// \param target     the infeasible foothold (its yaw is kept)
  /// \param q_init     IK start (size n_q)
  /// \param pelvis_position  passed to KinematicFeasibility::check
  /// \param check    where each ring's candidates are checked; empty: in this process
  /// \return the first feasible ring point, or none.
  /// \throws ReachError when a candidate's check fails before a feasible one is found (the
  ///     message of that check), or when `check` answers fewer candidates than it must.
  std::optional<NearestFoothold> find(Side stance, const FlatContact& stance_contact,
                                      const FlatContact& target, const Eigen::VectorXd& q_init,
                                      const std::optional<Eigen::Vector3d>& pelvis_position,
                                      const CandidateCheck& check = {}) const;
  /// The candidates of ring `ring` (1-based) around `target`, the first along +x,
  /// counter-clockwise (each keeps the target's yaw).
  std::vector<FlatContact> ringCandidates(const FlatContact& target, int ring) const;
  const NearestFootholdConfig& config() const { return config_; }

 private:
  std::shared_ptr<const KinematicFeasibility> kinematics_;
  NearestFootholdConfig config_;
};

}  // namespace reach_trajopt
