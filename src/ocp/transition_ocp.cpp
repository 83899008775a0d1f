#include "reach_trajopt/ocp/transition_ocp.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <nlopt.hpp>
#include <sstream>
#include <vector>

#include "reach_trajopt/common/cancelled.h"
#include "reach_trajopt/common/error.h"
#include "reach_trajopt/common/stopwatch.h"
#include "reach_trajopt/contact/contact_constraint.h"
#include "reach_trajopt/ocp/transition_check.h"
#include "reach_trajopt/ocp/transition_nlp.h"
#include "reach_trajopt/qp/dual_active_set_qp.h"

namespace reach_trajopt {

namespace {

/// SLSQP's answer violates its own rows by more than this many times the tolerance: far from
/// feasible (TransitionOcp::solveMode refines it only while the violation halves).
constexpr double kFarFromFeasible = 100.0;

const char* nloptResultName(nlopt::result r) {
  switch (r) {
    case nlopt::FAILURE:
      return "FAILURE";
    case nlopt::INVALID_ARGS:
      return "INVALID_ARGS";
    case nlopt::OUT_OF_MEMORY:
      return "OUT_OF_MEMORY";
    case nlopt::ROUNDOFF_LIMITED:
      return "ROUNDOFF_LIMITED";
    case nlopt::FORCED_STOP:
      return "FORCED_STOP";
    case nlopt::SUCCESS:
      return "SUCCESS";
    case nlopt::STOPVAL_REACHED:
      return "STOPVAL_REACHED";
    case nlopt::FTOL_REACHED:
      return "FTOL_REACHED";
    case nlopt::XTOL_REACHED:
      return "XTOL_REACHED";
    case nlopt::MAXEVAL_REACHED:
      return "MAXEVAL_REACHED";
    case nlopt::MAXTIME_REACHED:
      return "MAXTIME_REACHED";
    default:
      return "UNKNOWN";
  }
}

/// runSlsqp's code says the deadline stopped the run.
bool timedOut(const std::string& nlopt_status) {
  return nlopt_status.rfind("MAXTIME_REACHED", 0) == 0;
}

/// The largest violation of the NLP's rows at a point: |equality| and positive inequality.
double nlpViolation(const NlpValues& v) {
  double worst = 0.0;
  if (v.equality.size() > 0) worst = v.equality.cwiseAbs().maxCoeff();
  if (v.inequality.size() > 0) worst = std::max(worst, v.inequality.maxCoeff());
  return worst;
}

/// Evaluates the NLP once per point for the objective and both constraint callbacks.
struct NloptBridge {
  TransitionNlp* nlp = nullptr;
  nlopt::opt* opt = nullptr;
  Eigen::VectorXd x;
  bool valid = false, has_gradients = false;
  NlpValues values;
  int gradient_evaluations = 0;
  int evaluations_before = 0;  ///< of the earlier rounds of this solve (progress reports)
  const OcpProgressCallback* progress = nullptr;
  bool cancelled = false;
  std::string error;
  /// The time limit, checked inside the evaluations (SLSQP's own maxtime test runs only
  /// between them): an evaluation that would start too late stops the run instead.
  SteadyClock::time_point deadline = SteadyClock::time_point::max();
  double reserve_s = 0.0;     ///< kept free for sampling and checking the answer [s]
  double longest_step_s = 0;  ///< the longest wall time between two gradient evaluations [s]
  SteadyClock::time_point last_gradient{};
  bool timed_out = false;
  /// Anytime: the lowest-cost iterate whose NLP rows all hold within `feasible_tolerance`
  /// (every gradient evaluation is at an iterate SLSQP accepted). Empty when none was.
  double feasible_tolerance = 0.0;
  Eigen::VectorXd best_feasible;
  double best_feasible_cost = HUGE_VAL;
  /// The inequality rows SLSQP sees (row screening), all when null.
  const std::vector<int>* rows = nullptr;

  /// True when the next iteration (as long as the longest so far) would end past the
  /// deadline less the reserve: stops the run there. SLSQP's own work between two evaluations
  /// (its dense least-squares subproblem: up to 0.95 s for a 5 s swing) cannot be interrupted,
  /// so the run stops before an iteration it could not finish in time, never after the limit.
  bool outOfTime(bool gradients) {
    const SteadyClock::time_point now = SteadyClock::now();
    if (gradients && last_gradient != SteadyClock::time_point{})
      longest_step_s =
          std::max(longest_step_s, std::chrono::duration<double>(now - last_gradient).count());
    const double left = std::chrono::duration<double>(deadline - now).count() - reserve_s;
    if (left > longest_step_s) return false;
    timed_out = true;
    valid = false;
    opt->force_stop();
    return true;
  }

  bool prepare(unsigned n, const double* xp, bool gradients) {
    if (!error.empty() || timed_out) return false;
    const bool same = valid && std::memcmp(x.data(), xp, n * sizeof(double)) == 0;
    if (same && (has_gradients || !gradients)) return true;
    if (outOfTime(gradients)) return false;
    x = Eigen::Map<const Eigen::VectorXd>(xp, n);
    try {
      nlp->evaluate(x, gradients, values);
      if (!std::isfinite(values.cost) || !values.equality.allFinite() ||
          !values.inequality.allFinite()) {
        throw ReachError("non-finite NLP values");
      }
    } catch (const std::exception& e) {
      error = e.what();
      valid = false;
      opt->force_stop();
      return false;
    }
    valid = true;
    has_gradients = gradients;
    if (gradients) {
      last_gradient = SteadyClock::now();
      ++gradient_evaluations;
      if (nlpViolation(values) <= feasible_tolerance && values.cost < best_feasible_cost) {
        best_feasible_cost = values.cost;
        best_feasible = x;
      }
      if (progress && *progress &&
          !(*progress)({nlp->relaxed(), evaluations_before + gradient_evaluations})) {
        cancelled = true;
        valid = false;
        opt->force_stop();
        return false;
      }
    }
    return true;
  }

  static double objective(unsigned n, const double* x, double* grad, void* data) {
    auto* b = static_cast<NloptBridge*>(data);
    if (!b->prepare(n, x, grad != nullptr)) return HUGE_VAL;
    if (grad) Eigen::Map<Eigen::VectorXd>(grad, n) = b->values.cost_gradient;
    return b->values.cost;
  }
  static void equality(unsigned m, double* result, unsigned n, const double* x, double* grad,
                       void* data) {
    auto* b = static_cast<NloptBridge*>(data);
    if (!b->prepare(n, x, grad != nullptr)) {
      std::fill(result, result + m, HUGE_VAL);
      return;
    }
    Eigen::Map<Eigen::VectorXd>(result, m) = b->values.equality;
    if (grad) Eigen::Map<RowMajorMatrixXd>(grad, m, n) = b->values.equality_jacobian;
  }
  static void inequality(unsigned m, double* result, unsigned n, const double* x, double* grad,
                         void* data) {
    auto* b = static_cast<NloptBridge*>(data);
    if (!b->prepare(n, x, grad != nullptr)) {
      std::fill(result, result + m, HUGE_VAL);
      return;
    }
    if (!b->rows) {
      Eigen::Map<Eigen::VectorXd>(result, m) = b->values.inequality;
      if (grad) Eigen::Map<RowMajorMatrixXd>(grad, m, n) = b->values.inequality_jacobian;
      return;
    }
    for (unsigned k = 0; k < m; ++k) {
      const int r = (*b->rows)[k];
      result[k] = b->values.inequality[r];
      if (grad)
        Eigen::Map<Eigen::RowVectorXd>(grad + static_cast<std::size_t>(k) * n, n) =
            b->values.inequality_jacobian.row(r);
    }
  }
};

/// Runs SLSQP from x (updated in place) until `deadline` less `reserve_s`. Returns NLopt's
/// code name (MAXTIME_REACHED when the deadline stopped it); `error` gets callback failures.
/// `longest_step_s`: the longest SLSQP iteration of the solve so far [s], in and out: a new run
/// starts knowing it (its first iteration is as long as the earlier runs' were; each run
/// starting from zero let the pushed demo walk's plans end up to 13 ms past their deadline).
/// \throws ReachCancelled when `progress` returns false.
std::string runSlsqpOnce(TransitionNlp& nlp, const TransitionOcpConfig& config,
                         SteadyClock::time_point deadline, double reserve_s, Eigen::VectorXd& x,
                         int& evaluations, double& longest_step_s, std::string& error,
                         const OcpProgressCallback& progress, const std::vector<int>* rows) {
  const unsigned n = static_cast<unsigned>(nlp.variableCount());
  nlopt::opt opt(nlopt::LD_SLSQP, n);
  NloptBridge bridge;
  bridge.rows = rows;
  bridge.nlp = &nlp;
  bridge.opt = &opt;
  bridge.progress = &progress;
  bridge.evaluations_before = evaluations;
  bridge.deadline = deadline;
  bridge.reserve_s = reserve_s;
  bridge.longest_step_s = longest_step_s;
  bridge.feasible_tolerance = 0.5 * config.tolerance;
  const double max_time = secondsUntil(deadline);
  auto toStd = [](const Eigen::VectorXd& v) {
    return std::vector<double>(v.data(), v.data() + v.size());
  };
  opt.set_lower_bounds(toStd(nlp.lowerBounds()));
  opt.set_upper_bounds(toStd(nlp.upperBounds()));
  opt.set_min_objective(&NloptBridge::objective, &bridge);
  opt.add_equality_mconstraint(&NloptBridge::equality, &bridge,
                               std::vector<double>(nlp.equalityCount(), 1e-10));
  opt.add_inequality_mconstraint(
      &NloptBridge::inequality, &bridge,
      std::vector<double>(rows ? rows->size() : nlp.inequalityCount(), 1e-10));
  opt.set_ftol_rel(nlp.relaxed() ? config.relaxed_ftol_rel : config.ftol_rel);
  opt.set_xtol_rel(config.xtol_rel);
  opt.set_maxeval(config.max_evaluations);
  opt.set_maxtime(std::max(1e-6, max_time - reserve_s));
  std::vector<double> xv = toStd(x);
  double f = 0.0;
  nlopt::result code = nlopt::FAILURE;
  try {
    code = opt.optimize(xv, f);
  } catch (const nlopt::roundoff_limited&) {
    code = nlopt::ROUNDOFF_LIMITED;
  } catch (const nlopt::forced_stop&) {
    code = nlopt::FORCED_STOP;
  } catch (const std::invalid_argument& e) {
    code = nlopt::INVALID_ARGS;
    error = e.what();
  } catch (const std::bad_alloc&) {
    code = nlopt::OUT_OF_MEMORY;
  } catch (const std::runtime_error&) {
    code = nlopt::FAILURE;
  }
  if (bridge.cancelled)
    throw ReachCancelled("transition OCP cancelled after " +
                         std::to_string(evaluations + bridge.gradient_evaluations) +
                         " evaluations");
  if (!bridge.error.empty()) error = bridge.error;
  const Eigen::VectorXd xn = Eigen::Map<const Eigen::VectorXd>(xv.data(), n);
  if (xn.allFinite()) x = xn;
  evaluations += bridge.gradient_evaluations;
  longest_step_s = bridge.longest_step_s;
  std::string name = bridge.timed_out ? "MAXTIME_REACHED" : nloptResultName(code);
  // Anytime: a run cut short (deadline or evaluation budget) ends where it was, which need not
  // be feasible; the best feasible iterate it passed is the better answer. The 1 ms re-check
  // still decides whether it is accepted.
  const bool cut_short =
      name == "MAXTIME_REACHED" || name == "MAXEVAL_REACHED" || name == "FORCED_STOP";
  if (cut_short && bridge.best_feasible.size() == x.size() && error.empty()) {
    NlpValues at_x;
    nlp.evaluate(x, false, at_x);
    if (nlpViolation(at_x) > bridge.feasible_tolerance) {
      x = bridge.best_feasible;
      name += " (best feasible iterate)";
    }
  }
  return name;
}

/// SLSQP on the inequality rows within `screen` of active (value > -screen) at x, then, while
/// a row left out is violated at its answer, again from there with the rows near active at that
/// point added. SLSQP's subproblem (a dense least-squares problem whose cost grows with the row
/// count) and its merit function do not depend on rows that stay inactive, so the run is the
/// full problem's as long as the rows left out stay away; the final check makes the answer hold
/// every row (TransitionOcpConfig::row_screening). screen <= 0: all rows at once.
std::string runSlsqp(TransitionNlp& nlp, const TransitionOcpConfig& config,
                     SteadyClock::time_point deadline, double reserve_s, Eigen::VectorXd& x,
                     int& evaluations, double& longest_step_s, std::string& error,
                     const OcpProgressCallback& progress) {
  const double screen = config.row_screening;
  if (screen <= 0.0)
    return runSlsqpOnce(nlp, config, deadline, reserve_s, x, evaluations, longest_step_s, error,
                        progress, nullptr);
  const int m = nlp.inequalityCount();
  std::vector<char> kept(m, 0);
  NlpValues v;
  nlp.evaluate(x, false, v);
  for (int r = 0; r < m; ++r) kept[r] = v.inequality[r] > -screen;
  std::string code;
  for (int round = 0;; ++round) {
    std::vector<int> rows;
    for (int r = 0; r < m; ++r)
      if (kept[r]) rows.push_back(r);
    const bool all = static_cast<int>(rows.size()) == m;
    code = runSlsqpOnce(nlp, config, deadline, reserve_s, x, evaluations, longest_step_s, error,
                        progress, all ? nullptr : &rows);
    if (!error.empty() || timedOut(code) || all) break;
    nlp.evaluate(x, false, v);
    bool violated = false;
    for (int r = 0; r < m; ++r) {
      if (kept[r]) continue;
      if (v.inequality[r] > 0.5 * config.tolerance) violated = true;
      if (v.inequality[r] > -screen) kept[r] = 1;
    }
    // The rows left out hold: done, unless the answer breaks a row SLSQP saw (it stopped at an
    // infeasible point), where the full problem has the last word, from there.
    if (!violated && nlpViolation(v) <= 0.5 * config.tolerance) break;
    if (!violated || round >= 2) std::fill(kept.begin(), kept.end(), 1);
  }
  return code;
}

std::string worstFamily(const ConstraintViolations& v) {
  const std::pair<const char*, double> f[] = {
      {"dynamics", v.dynamics},           {"stance_contact", v.stance_contact},
      {"stance_cone", v.stance_cone},     {"new_contact", v.new_contact},
      {"new_cone", v.new_cone},           {"torque", v.torque},
      {"joint_limits", v.joint_limits},   {"reachable_set", v.reachable_set},
      {"leg_clearance", v.leg_clearance}, {"initial_state", v.initial_state},
      {"final_state", v.final_state}};
  const auto* w = std::max_element(
      std::begin(f), std::end(f), [](const auto& a, const auto& b) { return a.second < b.second; });
  std::ostringstream os;
  os << w->first << " violated by " << w->second;
  return os.str();
}

/// A slice whose half-planes A p <= b share no point: the nearest point of the hull to the
/// origin (a QP of 2 variables) is infeasible. An empty slice was solved for the whole time
/// limit and reported as torque violations.
void requireNonEmptyHull(const ReachableSlice& s, const std::string& what) {
  if (s.A.cols() != 2) return;  // sizes are checked by the NLP
  qp::DualActiveSetQp nearest(2, 0, static_cast<int>(s.A.rows()));
  const qp::QpResult& r = nearest.solve(Eigen::Matrix2d::Identity(), Eigen::Vector2d::Zero(),
                                        Eigen::MatrixXd(0, 2), Eigen::VectorXd(0), -s.A, -s.b);
  if (r.status == qp::QpStatus::kInfeasible)
    throw RequestError(what + ": empty hull: its half-planes A p <= b share no point");
}

/// The hull slices of a request: times in [0, T], sizes, finite, no zero normal, not empty.
void validateSlices(const TransitionRequest& r) {
  const double t_tol = 1e-9 + 1e-9 * r.horizon;
  for (size_t i = 0; i < r.slices.size(); ++i) {
    const ReachableSlice& s = r.slices[i];
    const std::string what = "TransitionOcp: slice " + std::to_string(i);
    if (!std::isfinite(s.time) || s.time < -t_tol || s.time > r.horizon + t_tol) {
      std::ostringstream os;
      os << what << ": time " << s.time << " s outside [0, " << r.horizon << "] s";
      throw RequestError(os.str());
    }
    if (s.A.rows() == 0) throw RequestError(what + ": empty hull");
    requireSize((what + ": b").c_str(), s.b.size(), s.A.rows());
    requireFinite((what + ": A").c_str(), s.A);
    requireFinite((what + ": b").c_str(), s.b);
    for (Eigen::Index k = 0; k < s.A.rows(); ++k) {
      if (s.A.row(k).norm() < 1e-12) throw RequestError(what + ": zero normal in A");
    }
    requireNonEmptyHull(s, what);
  }
}

/// The seed path of a request: sizes (nq rows), finite, times increasing in [0, T].
void validateSeed(const TransitionRequest& r, int nq) {
  const double t_tol = 1e-9 + 1e-9 * r.horizon;
  requireSize("TransitionOcp: seed q columns", r.seed.q.cols(), r.seed.time.size());
  requireSize("TransitionOcp: seed q rows", r.seed.q.rows(), nq);
  requireFinite("TransitionOcp: seed time", r.seed.time);
  requireFinite("TransitionOcp: seed q", r.seed.q);
  for (Eigen::Index k = 0; k < r.seed.time.size(); ++k) {
    if (r.seed.time[k] < -t_tol || r.seed.time[k] > r.horizon + t_tol ||
        (k > 0 && r.seed.time[k] < r.seed.time[k - 1])) {
      std::ostringstream os;
      os << "TransitionOcp: seed time " << r.seed.time[k] << " s at index " << k
         << " is outside [0, " << r.horizon << "] s or not increasing";
      throw RequestError(os.str());
    }
  }
}

}  // namespace

TransitionOcp::TransitionOcp(std::shared_ptr<const RobotModel> model,
                             const TransitionOcpConfig& config, const ContactConfig& contact)
    : model_(std::move(model)), config_(config), contact_(contact) {
  if (!model_) throw ModelError("TransitionOcp: null robot model");
  if (!model_->floatingBase()) throw ModelError("TransitionOcp: needs a floating-base model");
  config_.validate();
  contact_.validate();
  model_->frameId(contact_.left_sole_frame);
  model_->frameId(contact_.right_sole_frame);
}

void TransitionOcp::validate(const TransitionRequest& r) const {
  const RobotModel& m = *model_;
  const int nq = m.nq();
  requireSize("TransitionOcp: q0", r.q0.size(), nq);
  requireSize("TransitionOcp: qd0", r.qd0.size(), nq);
  requireSize("TransitionOcp: qf", r.qf.size(), nq);
  requireSize("TransitionOcp: qdf", r.qdf.size(), nq);
  requireFinite("TransitionOcp: q0", r.q0);
  requireFinite("TransitionOcp: qd0", r.qd0);
  requireFinite("TransitionOcp: qf", r.qf);
  requireFinite("TransitionOcp: qdf", r.qdf);
  if (!std::isnan(r.terminal_pelvis_height) &&
      !(std::isfinite(r.terminal_pelvis_height) && r.terminal_pelvis_height > 0.0))
    throw RequestError("TransitionOcp: terminal_pelvis_height must be > 0 (or NaN: the config's)");
  std::ostringstream os;
  if (!std::isfinite(r.horizon) || r.horizon <= 0.0 || r.horizon < config_.output_dt) {
    os << "TransitionOcp: inconsistent horizon " << r.horizon
       << " s: must be finite and at least one output sample (" << config_.output_dt << " s)";
    throw RequestError(os.str());
  }
  if (r.horizon > kMaxTransitionHorizon) {
    // The NLP's size and each evaluation grow with the horizon (output_dt samples): a bound
    // keeps every solve inside its time limit (docs/limits.md).
    os << "TransitionOcp: horizon " << r.horizon << " s is over the limit of "
       << kMaxTransitionHorizon << " s";
    throw RequestError(os.str());
  }
  // Poses: finite, proper rotations (ContactConstraint checks both).
  try {
    ContactConstraint(0, r.heldPose());
    ContactConstraint(0, r.targetPose());
  } catch (const ReachError& e) {
    throw RequestError(std::string("TransitionOcp: stance_pose / swing_target: ") + e.what());
  }
  validateSlices(r);
  if (!r.seed.empty()) validateSeed(r, nq);
  // x_0 on its stance contact.
  Workspace ws(m);
  m.update(ws, r.q0, r.qd0);
  const ContactConstraint stance(m, contact_.soleFrame(r.stance), r.heldPose());
  ContactConstraintTerms terms(nq);
  stance.evaluate(m, ws, terms);
  const double off = std::max(terms.phi.cwiseAbs().maxCoeff(), terms.phidot.cwiseAbs().maxCoeff());
  if (off > config_.input_tolerance) {
    os << "TransitionOcp: x_0 is off its stance contact " << contact_.soleFrame(r.stance)
       << ": max(|phi|, |phidot|) = " << off << " > " << config_.input_tolerance;
    throw RequestError(os.str());
  }
  if (r.relaxation == RelaxationMode::kStrict && !finalStateOnContacts(r)) {
    throw RequestError(
        "TransitionOcp: x_f does not hold both contacts (stance pose and swing target) within "
        "input_tolerance: the strict problem x(t_f) = x_f is inconsistent (use kRelaxed or "
        "kAuto)");
  }
}

bool TransitionOcp::finalStateOnContacts(const TransitionRequest& r) const {
  const RobotModel& m = *model_;
  Workspace ws(m);
  m.update(ws, r.qf, r.qdf);
  ContactConstraintTerms terms(m.nq());
  double off = 0.0;
  for (int k = 0; k < 2; ++k) {
    const Side s = k == 0 ? r.stance : opposite(r.stance);
    const ContactConstraint c(m, contact_.soleFrame(s), k == 0 ? r.heldPose() : r.targetPose());
    c.evaluate(m, ws, terms);
    off = std::max({off, terms.phi.cwiseAbs().maxCoeff(), terms.phidot.cwiseAbs().maxCoeff()});
  }
  return off <= config_.input_tolerance;
}

TransitionResult TransitionOcp::solveMode(const TransitionRequest& request, bool relaxed,
                                          SteadyClock::time_point deadline,
                                          const OcpProgressCallback& progress) const {
  TransitionNlp nlp(model_, config_, contact_, request, relaxed);
  Eigen::VectorXd x = nlp.initialGuess();
  TransitionResult res;
  // x_f is fixed in the strict problem: legs inside their margin there cannot be solved for.
  if (const double legs_at_xf = relaxed ? 0.0 : nlp.legClearanceViolation(request.qf);
      legs_at_xf > 0.5 * config_.tolerance) {
    nlp.sampleSolution(x, config_.output_dt, res);
    res.status = OcpStatus::kFailed;
    res.violation.leg_clearance = legs_at_xf;
    res.reason = "leg_clearance violated by " + std::to_string(legs_at_xf) +
                 " m at x_f (its legs are closer than contact.leg_clearance_margin)";
    return res;
  }
  std::string error;
  double previous = std::numeric_limits<double>::infinity();
  // Kept free for sampling and checking the answer after a run: the last such pass's wall
  // time, twice (a first guess before any: one evaluation of the NLP, timed here).
  double reserve_s = 0.0;
  {
    const SteadyClock::time_point t0 = SteadyClock::now();
    NlpValues probe;
    nlp.evaluate(x, false, probe);
    reserve_s = 2.0 * secondsSince(t0);
  }
  double longest_step_s = 0.0;  // SLSQP's longest iteration in this solve (runSlsqpOnce)
  for (int round = 0;; ++round) {
    const double remaining = secondsUntil(deadline);
    if (remaining <= reserve_s + longest_step_s) {
      res.status = OcpStatus::kFailed;
      res.reason = "time limit reached (the earlier of the caller's deadline and time_limit, " +
                   std::to_string(config_.time_limit) + " s)";
      if (res.time.size() == 0) nlp.sampleSolution(x, config_.output_dt, res);
      break;
    }
    res.nlopt_status = runSlsqp(nlp, config_, deadline, reserve_s, x, res.iterations,
                                longest_step_s, error, progress);
    ++res.solves;
    res.variables = nlp.variableCount();
    res.constraints = nlp.equalityCount() + nlp.inequalityCount();
    const SteadyClock::time_point sampled = SteadyClock::now();
    nlp.sampleSolution(x, config_.output_dt, res);
    const TransitionCheck check =
        checkTransition(*model_, contact_, request, res, 0.5 * config_.tolerance);
    reserve_s = 2.0 * secondsSince(sampled);
    res.violation = check.violation;
    if (!error.empty()) {
      res.status = OcpStatus::kFailed;
      res.reason = "NLP evaluation failed: " + error;
      break;
    }
    if (res.violation.max() <= config_.tolerance) {
      res.status = relaxed ? OcpStatus::kRelaxed : OcpStatus::kConverged;
      res.reason.clear();
      // Stopped by the time limit at a feasible iterate: feasible (re-checked), not optimal.
      if (timedOut(res.nlopt_status))
        res.reason = "time limit reached at a feasible iterate (not optimal)";
      break;
    }
    res.status = OcpStatus::kFailed;
    res.reason = worstFamily(res.violation) + " (tolerance " + std::to_string(config_.tolerance) +
                 ", NLopt " + res.nlopt_status + ", " + std::to_string(res.solves) + " solves)";
    if (timedOut(res.nlopt_status)) {
      res.reason = "time limit reached: " + res.reason;
      break;
    }
    if (round >= config_.max_refinements) break;
    // SLSQP's own rows far from holding at its answer: its problem has no feasible point near
    // there, and more samples only add rows. As for a restart, go on only while the rounds
    // halve the violation (of the demo's TALOS walk's strict solves that ended a round that
    // far, none converged in a later round).
    if (res.violation.max() > 0.5 * previous) {
      NlpValues at_x;
      nlp.evaluate(x, false, at_x);
      if (nlpViolation(at_x) > kFarFromFeasible * config_.tolerance) break;
    }
    // Violations between samples: add those samples. Otherwise (no violation off the NLP's
    // samples, or only at times and slices it holds already) SLSQP stopped at an infeasible
    // point (its tolerance tests do not look at feasibility): restart from there, which resets
    // its quasi-Newton matrix.
    const bool refined = nlp.addSamples(check.violating_times, check.violating_slices);
    if (!refined && res.violation.max() > 0.5 * previous) {
      break;  // a restart that did not halve the violation: give up
    }
    previous = res.violation.max();
  }
  NlpValues values;
  nlp.evaluate(x, false, values);
  res.cost = values.cost;
  return res;
}

TransitionResult TransitionOcp::solve(const TransitionRequest& request,
                                      const OcpProgressCallback& progress) const {
  return solve(request, progress, SteadyClock::time_point::max());
}

SteadyClock::time_point TransitionOcp::deadlineOf(SteadyClock::time_point start,
                                                  SteadyClock::time_point step_deadline) const {
  return std::min(step_deadline, secondsAfter(start, config_.time_limit));
}

TransitionResult TransitionOcp::relaxedAfter(const TransitionRequest& request,
                                             const TransitionResult& strict,
                                             SteadyClock::time_point deadline,
                                             const OcpProgressCallback& progress) const {
  // Out of time: the strict problem's answer (failed, naming the time limit) stands.
  if (SteadyClock::now() >= deadline || timedOut(strict.nlopt_status)) return strict;
  TransitionResult res = solveMode(request, true, deadline, progress);
  res.iterations += strict.iterations;
  res.solves += strict.solves;
  const std::string note = "strict problem failed (" + strict.reason + ")";
  res.reason = res.reason.empty() ? note : note + "; relaxed: " + res.reason;
  return res;
}

TransitionResult TransitionOcp::solveRelaxedAfter(const TransitionRequest& request,
                                                  const TransitionResult& strict,
                                                  const OcpProgressCallback& progress,
                                                  SteadyClock::time_point step_deadline) const {
  const SteadyClock::time_point start = SteadyClock::now();
  validate(request);
  TransitionResult res = relaxedAfter(request, strict, deadlineOf(start, step_deadline), progress);
  res.solve_time = strict.solve_time + secondsSince(start);
  return res;
}

TransitionResult TransitionOcp::solve(const TransitionRequest& request,
                                      const OcpProgressCallback& progress,
                                      SteadyClock::time_point step_deadline) const {
  const SteadyClock::time_point start = SteadyClock::now();
  const SteadyClock::time_point deadline = deadlineOf(start, step_deadline);
  validate(request);
  TransitionResult res;
  switch (request.relaxation) {
    case RelaxationMode::kStrict:
      res = solveMode(request, false, deadline, progress);
      break;
    case RelaxationMode::kRelaxed:
      res = solveMode(request, true, deadline, progress);
      break;
    case RelaxationMode::kAuto: {
      if (finalStateOnContacts(request)) {
        res = solveMode(request, false, deadline, progress);
        if (res.status != OcpStatus::kFailed) break;
        res = relaxedAfter(request, res, deadline, progress);
      } else {
        res = solveMode(request, true, deadline, progress);
        const std::string note = "x_f is off its contacts: solved the relaxed problem";
        res.reason = res.reason.empty() ? note : note + "; " + res.reason;
      }
      break;
    }
  }
  res.solve_time = secondsSince(start);
  return res;
}

}  // namespace reach_trajopt
