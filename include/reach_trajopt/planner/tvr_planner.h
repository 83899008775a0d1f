#pragma once
/// \file tvr_planner.h
/// The Time-to-Velocity-Reversal (TVR) footstep planner of eq. (11)-(12), in the sign
/// convention of docs/method.md Sec. 3 (the paper's printed (11) drops a minus sign, and its bias
/// sign with kappa = -0.66 would be unstable). Per horizontal axis, the next contact point
///   a = p + (pd / omega) coth(omega t_s) + kappa (p_des - p)
/// makes the LIPM's CoM velocity reverse t_s seconds after the switch when kappa = 0; kappa < 0
/// pulls the CoM towards p_des. The heuristic bounds of Sec. IV-A (foot offset limits relative
/// to the stance sole, CoM speed limits) can be switched on (the baseline) or off (the
/// proposed method, which checks reachability instead).

#include <Eigen/Core>
#include <complex>
#include <string>

#include "reach_trajopt/contact/contact_mode.h"
#include "reach_trajopt/planner/lipm.h"

namespace reach_trajopt {

class YamlSection;
template <typename Config>
class ConfigFields;

/// TVR parameters; defaults are the shipped ones (config/biped.yaml, section `planner:`), the
/// paper's (Sec. IV-A) except kappa_x.
struct TvrConfig {
  double com_height = 1.0;  ///< h [m] of the LIPM (> 0)
  double gravity = 9.81;    ///< g [m/s^2] (> 0)
  double t_s = 0.15;        ///< time to velocity reversal [s] (> 0)
  /// Sagittal bias kappa_1 (< 0 stabilizes): the authors' code value; with the paper's -0.66
  /// our biped walks in place but not forward.
  double kappa_x = -0.16;
  double kappa_y = -0.66;  ///< lateral bias kappa_2 (the paper's)
  /// Clip the step and the CoM speed (baseline of Sec. IV-A). Not a YAML key: the walk mode
  /// sets it (WalkingExperiment, tvr_planner_node: baseline on, proposed off).
  bool heuristic_bounds = true;
  double foot_offset_x_min = -0.42;  ///< next sole x offset from the stance sole [m] (heading)
  double foot_offset_x_max = 0.42;   ///< [m]
  double foot_offset_y_min = 0.25;   ///< |y| offset towards the swing side, lower bound [m]
  double foot_offset_y_max = 0.65;   ///< upper bound [m]
  double com_speed_min = 0.0;        ///< bounds on the horizontal CoM speed used by the planner
  double com_speed_max = 1.3;        ///< [m/s]

  /// Throws ConfigError naming the first bad value (non-finite, non-positive h, g, t_s, or a
  /// bound interval with min > max, or negative |y| / speed bounds).
  void validate() const;
  /// The YAML keys of section `planner:` (the member names), their units and meaning.
  static const ConfigFields<TvrConfig>& fields();
  /// Reads fields() from a YAML section, then validates.
  static TvrConfig fromYaml(const YamlSection& section);
};

/// What the planner is given at the start of a step (the CoM state x_{p,k}).
struct TvrInput {
  LipmState com;                                     ///< CoM position [m] and velocity [m/s]
  Eigen::Vector2d p_des = Eigen::Vector2d::Zero();   ///< target of the bias term [m]
  Eigen::Vector2d stance = Eigen::Vector2d::Zero();  ///< stance sole centre (x, y) [m]
  double stance_yaw = 0.0;   ///< stance sole heading [rad]; offsets are measured in it
  Side swing = Side::kLeft;  ///< the sole that steps; y offsets are signed towards it
};

/// The planned next contact.
struct TvrStep {
  Eigen::Vector2d alpha_tvr = Eigen::Vector2d::Zero();  ///< eq. (11), no bounds [m]
  Eigen::Vector2d alpha = Eigen::Vector2d::Zero();      ///< returned contact (bounded if on)
  Eigen::Vector2d offset = Eigen::Vector2d::Zero();     ///< alpha - stance, heading frame [m]
  Eigen::Vector2d com_velocity_used = Eigen::Vector2d::Zero();  ///< after speed bounds [m/s]
  bool speed_clipped = false;   ///< the CoM speed bound changed the velocity
  bool offset_clipped = false;  ///< the foot offset bound moved the contact
};

/// Eigenvalues of the closed-loop step map (12), x_{p,k+1} = (A(T) + B(T) K) x_{p,k}.
struct TvrStabilityReport {
  Eigen::Matrix4d closed_loop;  ///< A(T) + B(T) K
  Eigen::Matrix<std::complex<double>, 4, 1> eigenvalues;
  double spectral_radius = 0.0;
  bool stable = false;          ///< spectral radius < 1 - 1e-9 (asymptotically stable step map)
  std::string summary() const;  ///< one line: T, t_s, kappas, |lambda|_max, verdict
};

/// TVR planner of eq. (11) and its step map (12). Immutable.
class TvrPlanner {
 public:
  /// Validates the config (throws ReachError).
  explicit TvrPlanner(const TvrConfig& config);

  const TvrConfig& config() const { return config_; }
  const Lipm& lipm() const { return lipm_; }

  /// The next contact point of eq. (11) (bounded when config.heuristic_bounds).
  /// Throws RequestError on a non-finite input.
  TvrStep plan(const TvrInput& input) const;

  /// Eq. (11) from a measured CoM state, as the walking loop and tvr_planner_node plan: the
  /// state predicted `remaining` seconds ahead (the nominal touchdown) with the LIPM about the
  /// stance sole (eq. 9-10), toward p_des = (x_start + forward_speed (t + remaining), y_mid).
  /// \param measured  CoM position [m] and velocity [m/s] at time t [s] of the run
  /// \param stance    stance sole centre (x, y) [m], heading 0; `swing` the sole that steps
  /// \param[out] input  the TvrInput used (for recorders and messages), if not null
  TvrStep planFromMeasured(const LipmState& measured, const Eigen::Vector2d& stance, Side swing,
                           double t, double remaining, double x_start, double forward_speed,
                           double y_mid, TvrInput* input = nullptr) const;

  /// A contact `alpha` [m] clipped to the foot offset bounds about the stance sole (centre [m],
  /// heading [rad]; y offsets signed towards `swing`), whatever config.heuristic_bounds says:
  /// the bounded step of Sec. IV-A. `clipped` (if not null): the bounds moved it.
  Eigen::Vector2d boundedContact(const Eigen::Vector2d& alpha, const Eigen::Vector2d& stance,
                                 double stance_yaw, Side swing, bool* clipped = nullptr) const;

  /// The feedback K (2 x 4) of a = K x_p + diag(kappa) p_des: [(I - diag(kappa)), coth I/omega].
  Eigen::Matrix<double, 2, 4> gain() const;
  /// Closed-loop matrix A(T) + B(T) K of eq. (12) for step duration T [s].
  Eigen::Matrix4d closedLoopMatrix(double step_duration) const;
  /// Stability report of (12) at step duration T [s] (the walk's period:
  /// WalkConfig::single_support_duration + double_support_duration).
  TvrStabilityReport stability(double step_duration) const;

 private:
  TvrConfig config_;
  Lipm lipm_;
};

}  // namespace reach_trajopt
