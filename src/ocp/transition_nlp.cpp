#include "reach_trajopt/ocp/transition_nlp.h"

#include <omp.h>

#include <algorithm>
#include <cmath>
#include <exception>
#include <limits>

#include "reach_trajopt/common/error.h"
#include "reach_trajopt/ocp/spline_fit.h"

namespace reach_trajopt {

namespace {

/// The NLP's leg clearance rows ask this much more than the margin [m] (but never more than
/// the distance at x_0), so that the legs' distance between two samples, which the 1 ms
/// re-check sees, rarely dips below the margin (each dip costs a refinement round,
/// transition_ocp.h).
constexpr double kLegRowPad = 1e-3;

}  // namespace

TransitionNlp::TransitionNlp(std::shared_ptr<const RobotModel> model,
                             const TransitionOcpConfig& config, const ContactConfig& contact,
                             const TransitionRequest& request, bool relaxed)
    : model_(std::move(model)),
      config_(config),
      request_(request),
      relaxed_(relaxed),
      nq_(model_->nq()),
      nu_(model_->nu()),
      basis_(request.horizon, config.segments),
      pelvis_posture_(relaxed && config.terminal_pelvis_height > 0.0),
      pelvis_height_target_(
          0.5 * (request.heldPose().translation().z() + request.targetPose().translation().z()) +
          (std::isnan(request.terminal_pelvis_height) ? config.terminal_pelvis_height
                                                      : request.terminal_pelvis_height)) {
  const RobotModel& m = *model_;
  const Side swing = opposite(request.stance);
  dyn_ = std::make_unique<StanceReducedDynamics>(
      model_, m.frameId(contact.soleFrame(request.stance)), request.heldPose(),
      m.frameId(contact.soleFrame(swing)), request.targetPose(), request.q0[3]);
  scratch_ = std::make_unique<StanceReducedDynamics::Scratch>(*dyn_);
  const ContactWrenchCone cone(contact);
  C_stance_ = cone.worldMatrix(request.heldPose().linear());
  C_new_ = cone.worldMatrix(request.targetPose().linear());
  weight_ = m.totalMass() * m.gravity().norm();
  u_max_inv_ = m.effortLimits().cwiseInverse();

  layOutVariables();
  // Ground clearance floor: the target height, or lower when x_0's swing sole is lower.
  Eigen::VectorXd q_start(nq_);
  dyn_->configuration(*scratch_, request.q0.tail(nu_), q_start);
  ground_clearance_ = config.ground_clearance;
  ground_floor_ = std::min(request.targetPose().translation().z(), scratch_->swing_position.z());

  // Leg clearance (eq. 4's h_state): the margin, or the legs' distance at x_0 when smaller.
  if (contact.leg_clearance) {
    legs_ = LegClearance(m, contact.left_sole_frame, contact.right_sole_frame);
    if (!legs_.empty()) {
      const double start = legs_.distanceAt(m, request.q0);
      leg_margin_ = contact.legMarginFrom(start);
      leg_row_bound_ = std::min(leg_margin_ + kLegRowPad, start);
    }
  }

  prepareSlices();
  rebuildSamples();

  input_.resize(dyn_->inputCount());
  signals_.resize(dyn_->signalCount());
  u_scaled_.resize(nu_);
  jloc_.resize(dyn_->signalCount(), 4 * nu_ + 6);
}

void TransitionNlp::layOutVariables() {
  const RobotModel& m = *model_;
  // Fixed control points: x_0 always, x_f in the strict problem.
  const int K = basis_.controlPoints();
  fixed_points_ = Eigen::MatrixXd::Zero(K, nu_);
  Eigen::VectorXd c0, c1, c2, c3;
  CubicBSplineBasis::boundaryControlPoints(basis_.knotSpacing(), request_.q0.tail(nu_),
                                           request_.qd0.tail(nu_), request_.qf.tail(nu_),
                                           request_.qdf.tail(nu_), c0, c1, c2, c3);
  fixed_points_.row(0) = c0.transpose();
  fixed_points_.row(1) = c1.transpose();
  if (!relaxed_) {
    fixed_points_.row(K - 2) = c2.transpose();
    fixed_points_.row(K - 1) = c3.transpose();
  }
  first_free_ = 2;
  last_free_ = relaxed_ ? K - 1 : K - 3;
  const int n_free = last_free_ - first_free_ + 1;
  lambda_index_ = n_free * nu_;
  eps_index_ = lambda_index_ + 6;
  n_x_ = eps_index_ + (relaxed_ ? 2 : 0);

  const double inf = std::numeric_limits<double>::infinity();
  lower_ = Eigen::VectorXd::Constant(n_x_, -inf);
  upper_ = Eigen::VectorXd::Constant(n_x_, inf);
  const Eigen::VectorXd q_lo = m.positionLowerLimits().tail(nu_);
  const Eigen::VectorXd q_hi = m.positionUpperLimits().tail(nu_);
  for (int k = 0; k < n_free; ++k) {
    lower_.segment(k * nu_, nu_) = q_lo;
    upper_.segment(k * nu_, nu_) = q_hi;
  }
}

void TransitionNlp::prepareSlices() {
  // Hulls with unit normals (violations in metres).
  for (const ReachableSlice& s : request_.slices) {
    Eigen::MatrixX2d A = s.A;
    Eigen::VectorXd b = s.b;
    for (Eigen::Index r = 0; r < A.rows(); ++r) {
      const double n = A.row(r).norm();
      A.row(r) /= n;
      b[r] /= n;
    }
    slice_A_.push_back(A);
    slice_b_.push_back(b);
  }
  // Initially, the slice nearest to each grid time.
  const int grid = static_cast<int>(std::ceil(basis_.duration() / config_.check_interval - 1e-9));
  for (int j = 0; j <= grid && !request_.slices.empty(); ++j) {
    const double t = basis_.duration() * j / grid;
    int best = -1;
    double best_dt = 0.5 * config_.check_interval + 1e-12;
    for (size_t i = 0; i < request_.slices.size(); ++i) {
      const double dt = std::abs(request_.slices[i].time - t);
      if (dt <= best_dt) {
        best_dt = dt;
        best = static_cast<int>(i);
      }
    }
    if (best >= 0 && std::find(enforced_slices_.begin(), enforced_slices_.end(), best) ==
                         enforced_slices_.end()) {
      enforced_slices_.push_back(best);
    }
  }
}

void TransitionNlp::rebuildSamples() {
  const double T = basis_.duration();
  const int grid = static_cast<int>(std::ceil(T / config_.check_interval - 1e-9));
  std::vector<double> times;
  for (int j = 0; j <= grid; ++j) times.push_back(T * j / grid);
  for (double t : extra_times_) times.push_back(t);
  for (int s : enforced_slices_) times.push_back(request_.slices[s].time);
  for (double& t : times) t = std::min(std::max(t, 0.0), T);
  std::sort(times.begin(), times.end());
  const double merge = 1e-9 + 1e-9 * T;
  std::vector<double> unique;
  for (double t : times) {
    if (unique.empty() || t - unique.back() > merge) unique.push_back(t);
  }
  unique.back() = T;    // t_f in single support (just before touchdown)
  unique.push_back(T);  // t_f in double support
  sample_times_ = unique;
  sample_times_.pop_back();
  const int n = static_cast<int>(unique.size());
  samples_.assign(n, Sample());
  for (int i = 0; i < n; ++i) {
    samples_[i].t = unique[i];
    samples_[i].final = i + 1 == n;
    const double lo = i > 0 ? unique[i - 1] : unique[i];
    const double hi = i + 1 < n ? unique[i + 1] : unique[i];
    samples_[i].weight = 0.5 * (hi - lo) / T;
  }
  // The trapezoid end weight of t_f is shared by its two samples.
  samples_[n - 2].weight = samples_[n - 1].weight = 0.25 * (unique[n - 2] - unique[n - 3]) / T;
  for (int s : enforced_slices_) {
    const double t = request_.slices[s].time;
    int best = 0;
    for (int i = 1; i + 1 < n; ++i) {
      if (std::abs(unique[i] - t) < std::abs(unique[best] - t)) best = i;
    }
    samples_[best].slices.push_back(s);
  }
  inequality_count_ = 0;
  for (int i = 0; i < n; ++i) {
    inequality_count_ += ContactWrenchCone::kRows + 2 * nu_;
    if (ground_clearance_ && i > 0 && samples_[i].t < T) inequality_count_ += 1;
    if (hasLegRow(samples_[i], i)) inequality_count_ += 1;
    for (int s : samples_[i].slices) inequality_count_ += static_cast<int>(slice_b_[s].size());
  }
  inequality_count_ += ContactWrenchCone::kRows;  // new contact's cone at t_f
}

bool TransitionNlp::addSamples(const std::vector<double>& times, const std::vector<int>& slices) {
  const std::size_t samples_before = samples_.size(), slices_before = enforced_slices_.size();
  for (double t : times) extra_times_.push_back(t);
  for (int s : slices) {
    if (s < 0 || s >= static_cast<int>(request_.slices.size())) {
      throw ReachError("TransitionNlp::addSamples: slice index out of range");
    }
    if (std::find(enforced_slices_.begin(), enforced_slices_.end(), s) == enforced_slices_.end())
      enforced_slices_.push_back(s);
  }
  rebuildSamples();
  return samples_.size() != samples_before || enforced_slices_.size() != slices_before;
}

int TransitionNlp::freeIndex(int k) const {
  if (k < first_free_ || k > last_free_) return -1;
  return (k - first_free_) * nu_;
}

double TransitionNlp::controlPoint(const Eigen::VectorXd& x, int k, int joint) const {
  const int i = freeIndex(k);
  return i < 0 ? fixed_points_(k, joint) : x[i + joint];
}

void TransitionNlp::splineInput(const Eigen::VectorXd& x, const CubicBSplineBasis::Row& row,
                                Eigen::Ref<Eigen::VectorXd> input) const {
  input.head(3 * nu_).setZero();
  for (int j = 0; j < 4; ++j) {
    const int k = row.first + j;
    for (int a = 0; a < nu_; ++a) {
      const double c = controlPoint(x, k, a);
      input[a] += row.value[j] * c;
      input[nu_ + a] += row.d1[j] * c;
      input[2 * nu_ + a] += row.d2[j] * c;
    }
  }
}

Eigen::Vector2d TransitionNlp::eps(const Eigen::VectorXd& x) const {
  return relaxed_ ? Eigen::Vector2d(x.segment<2>(eps_index_)) : Eigen::Vector2d::Zero();
}

Vector6d TransitionNlp::lambdaNew(const Eigen::VectorXd& x) const {
  return weight_ * x.segment<6>(lambda_index_);
}

double TransitionNlp::legClearanceViolation(const Eigen::VectorXd& q) const {
  if (!(leg_margin_ > -HUGE_VAL)) return 0.0;
  return std::max(0.0, leg_margin_ - legs_.distanceAt(*model_, q));
}

bool TransitionNlp::hasLegRow(const Sample& smp, int i) const {
  // Not at t_0 (fixed), nor at t_f in the strict problem (x_f fixed, checked by the caller).
  return leg_margin_ > -HUGE_VAL && i > 0 && !smp.final && (relaxed_ || smp.t < basis_.duration());
}

double TransitionNlp::groundFloor(double t) const {
  const double ramp = basis_.duration() / 3.0;
  const double a = std::min(1.0, std::min(t, basis_.duration() - t) / ramp);
  return ground_floor_ + config_.swing_clearance * a * a;
}

Eigen::VectorXd TransitionNlp::initialGuess() const {
  const double T = basis_.duration();
  Eigen::VectorXd times;
  Eigen::MatrixXd samples;
  if (!request_.seed.empty()) {
    times = request_.seed.time;
    samples = request_.seed.q.bottomRows(nu_).transpose();
  } else {
    // Cubic Hermite x_0 -> x_f in the joints.
    const int n = std::max(2, static_cast<int>(std::ceil(T / config_.output_dt)) + 1);
    times.resize(n);
    samples.resize(n, nu_);
    const Eigen::VectorXd p0 = request_.q0.tail(nu_), v0 = request_.qd0.tail(nu_);
    const Eigen::VectorXd p1 = request_.qf.tail(nu_), v1 = request_.qdf.tail(nu_);
    for (int i = 0; i < n; ++i) {
      const double t = T * i / (n - 1), s = t / T;
      const double h00 = 2 * s * s * s - 3 * s * s + 1, h10 = s * s * s - 2 * s * s + s;
      const double h01 = -2 * s * s * s + 3 * s * s, h11 = s * s * s - s * s;
      times[i] = t;
      samples.row(i) = (h00 * p0 + h10 * T * v0 + h01 * p1 + h11 * T * v1).transpose();
    }
  }
  const int K = basis_.controlPoints();
  std::vector<bool> fixed(K, false);
  for (int k = 0; k < K; ++k) fixed[k] = freeIndex(k) < 0;
  const Eigen::MatrixXd c = fitSplineControlPoints(basis_, times, samples, fixed, fixed_points_,
                                                   config_.fit_regularization);
  Eigen::VectorXd x = Eigen::VectorXd::Zero(n_x_);
  for (int k = first_free_; k <= last_free_; ++k) {
    x.segment(freeIndex(k), nu_) = c.row(k).transpose();
  }
  return x.cwiseMax(lower_).cwiseMin(upper_);
}

void TransitionNlp::state(const Eigen::VectorXd& x, double t, TransitionSampleState& out) {
  requireSize("TransitionNlp::state x", x.size(), n_x_);
  const double T = basis_.duration();
  const bool final = t >= T - 1e-12;
  splineInput(x, basis_.evaluate(t), input_);
  input_.tail<6>() = final ? lambdaNew(x) : Vector6d::Zero();
  dyn_->evaluate(*scratch_, input_, signals_);
  const StanceReducedDynamics& d = *dyn_;
  out.q = scratch_->q;
  out.qd = scratch_->qd;
  out.qdd = scratch_->qdd;
  out.u = signals_.segment(d.uOffset(), nu_);
  out.lambda_stance = signals_.segment<6>(d.lambdaOffset());
  out.lambda_new = input_.tail<6>();
  out.swing_position = signals_.segment<3>(d.swingPositionOffset());
  out.phi2 = signals_.segment<6>(d.phi2Offset());
  out.phidot2 = signals_.segment<6>(d.phidot2Offset());
  out.phiddot2 = signals_.segment<6>(d.phiddot2Offset());
}

/// The scratch of one evaluate() call, shared by its per-sample parts.
struct TransitionNlp::EvalState {
  EvalState(const Eigen::VectorXd& x_in, bool gradients_in, NlpValues& out_in, int lcols,
            int signals)
      : x(x_in),
        gradients(gradients_in),
        out(out_in),
        grow(lcols),
        coeff(signals),
        cone_rows(ContactWrenchCone::kRows, lcols) {}
  const Eigen::VectorXd& x;
  const bool gradients;
  NlpValues& out;
  int row = 0;                  ///< next inequality row
  CubicBSplineBasis::Row brow;  ///< spline row of the current sample
  Eigen::RowVectorXd grow, coeff;
  Eigen::Matrix<double, ContactWrenchCone::kRows, Eigen::Dynamic> cone_rows;
};

void TransitionNlp::scatter(const EvalState& e, Eigen::Ref<Eigen::RowVectorXd> target,
                            const StridedRow& local, bool final) const {
  for (int j = 0; j < 4; ++j) {
    const int idx = freeIndex(e.brow.first + j);
    if (idx >= 0) target.segment(idx, nu_) += local.segment(j * nu_, nu_);
  }
  if (final) target.segment(lambda_index_, 6) += local.tail(6);
}

void TransitionNlp::evaluate(const Eigen::VectorXd& x, bool gradients, NlpValues& out) {
  requireSize("TransitionNlp::evaluate x", x.size(), n_x_);
  const int m_eq = equalityCount(), m_in = inequalityCount();
  out.cost = 0.0;
  out.equality.setZero(m_eq);
  out.inequality.setZero(m_in);
  if (gradients) {
    out.cost_gradient.setZero(n_x_);
    out.equality_jacobian.setZero(m_eq, n_x_);
    out.inequality_jacobian.setZero(m_in, n_x_);
  }
  EvalState e(x, gradients, out, 4 * nu_ + 6, dyn_->signalCount());
  const int n_s = static_cast<int>(samples_.size());
  // The dynamics of every sample (the cost of an evaluation) on up to `threads` threads, each
  // with its own scratch and writing only its samples' buffers; then the rows in sample order
  // on this thread, so the result has the same bits for any thread count.
  const int threads = std::max(1, std::min(n_s, resolvedThreads()));
  while (static_cast<int>(workers_.size()) < threads) workers_.emplace_back(*dyn_, 4 * nu_ + 6);
  if (static_cast<int>(sample_eval_.size()) < n_s) sample_eval_.resize(n_s);
  std::vector<std::exception_ptr> errors(n_s);
#pragma omp parallel for schedule(static) num_threads(threads) if (threads > 1)
  for (int i = 0; i < n_s; ++i) {
    try {
      sampleSignals(samples_[i], x, gradients, workers_[threads > 1 ? omp_get_thread_num() : 0],
                    sample_eval_[i]);
    } catch (...) {
      errors[i] = std::current_exception();
    }
  }
  for (const std::exception_ptr& err : errors)
    if (err) std::rethrow_exception(err);
  for (int i = 0; i < n_s; ++i) {
    const Sample& smp = samples_[i];
    SampleEval& se = sample_eval_[i];
    e.brow = se.brow;
    signals_.swap(se.signals);
    jloc_.swap(se.jloc);
    addSampleCost(smp, e);
    addPathInequalities(smp, i, e);
    if (smp.final) addTerminalRows(e);
    signals_.swap(se.signals);
    jloc_.swap(se.jloc);
  }
  if (relaxed_) {
    const Eigen::Vector2d ev = x.segment<2>(eps_index_);
    out.cost += config_.w_eps * ev.squaredNorm();
    if (gradients) out.cost_gradient.segment<2>(eps_index_) += 2.0 * config_.w_eps * ev;
  }
  if (e.row != m_in) throw ReachError("TransitionNlp: internal error, inequality count mismatch");
}

int TransitionNlp::resolvedThreads() const {
  return config_.threads > 0 ? config_.threads : omp_get_max_threads();
}

TransitionNlp::Worker::Worker(const StanceReducedDynamics& d, int local_columns)
    : scratch(std::make_unique<StanceReducedDynamics::Scratch>(d)),
      kinematics(d.model()),
      input(d.inputCount()),
      jin(d.signalCount(), d.inputCount()) {
  (void)local_columns;
}

void TransitionNlp::sampleSignals(const Sample& smp, const Eigen::VectorXd& x, bool gradients,
                                  Worker& w, SampleEval& se) const {
  const StanceReducedDynamics& d = *dyn_;
  se.brow = basis_.evaluate(smp.t);
  se.signals.resize(d.signalCount());
  splineInput(x, se.brow, w.input);
  w.input.tail<6>() = smp.final ? lambdaNew(x) : Vector6d::Zero();
  if (gradients) {
    if (config_.chain_derivatives == ChainDerivatives::kAnalytic) {
      d.evaluate(*w.scratch, w.input, se.signals, w.jin);
    } else {
      d.evaluate(*w.scratch, w.input, se.signals, w.jin, config_.fd_step,
                 config_.central_differences);
    }
    const CubicBSplineBasis::Row& brow = se.brow;
    se.jloc.resize(d.signalCount(), 4 * nu_ + 6);
    for (int j = 0; j < 4; ++j) {
      se.jloc.middleCols(j * nu_, nu_) = brow.value[j] * w.jin.leftCols(nu_);
      se.jloc.middleCols(j * nu_, nu_) += brow.d1[j] * w.jin.middleCols(nu_, nu_);
      se.jloc.middleCols(j * nu_, nu_) += brow.d2[j] * w.jin.middleCols(2 * nu_, nu_);
    }
    se.jloc.rightCols<6>() = weight_ * w.jin.rightCols<6>();  // variables are lambda_2 / (m g)
  } else {
    d.evaluate(*w.scratch, w.input, se.signals);
  }
  if (leg_margin_ > -HUGE_VAL) {  // the legs' distance at q and d/dq (leg_clearance.h)
    const RobotModel& m = *model_;
    se.leg_gradient.resize(nq_);
    if (gradients) {  // the Jacobian pass left the scratch at perturbed states
      m.update(w.kinematics, se.signals.segment(d.qOffset(), nq_), Eigen::VectorXd::Zero(nq_));
      const LegClearance::Closest c = legs_.closest(m, w.kinematics);
      se.leg_distance = c.distance;
      legs_.gradient(m, w.kinematics, c, se.leg_gradient);
    } else {  // the dynamics' own forward kinematics at this sample's q
      se.leg_distance = legs_.closest(m, w.scratch->ws).distance;
    }
  }
}

void TransitionNlp::addSampleCost(const Sample& smp, EvalState& e) {
  const StanceReducedDynamics& d = *dyn_;
  NlpValues& out = e.out;
  const double W = weight_;
  const Eigen::VectorXd& qf = request_.qf;
  const Eigen::VectorXd& qdf = request_.qdf;
  const auto u = signals_.segment(d.uOffset(), nu_);
  const auto lam = signals_.segment<6>(d.lambdaOffset());
  const auto q = signals_.segment(d.qOffset(), nq_);
  const auto qd = signals_.segment(d.qdOffset(), nq_);
  u_scaled_ = u.cwiseProduct(u_max_inv_);
  const Eigen::VectorXd& us = u_scaled_;
  const double c_u = config_.w_torque * us.squaredNorm();
  const double c_l = config_.w_wrench * lam.squaredNorm() / (W * W);
  const double c_q = config_.w_position * (q - qf).squaredNorm();
  const double c_v = config_.w_velocity * (qd - qdf).squaredNorm();
  out.cost += smp.weight * (c_u + c_l + c_q + c_v);
  if (e.gradients) {
    e.coeff.setZero();
    e.coeff.segment(d.uOffset(), nu_) =
        (2.0 * config_.w_torque) * us.cwiseProduct(u_max_inv_).transpose();
    e.coeff.segment<6>(d.lambdaOffset()) = (2.0 * config_.w_wrench / (W * W)) * lam.transpose();
    e.coeff.segment(d.qOffset(), nq_) = (2.0 * config_.w_position) * (q - qf).transpose();
    e.coeff.segment(d.qdOffset(), nq_) = (2.0 * config_.w_velocity) * (qd - qdf).transpose();
    e.grow.noalias() = smp.weight * e.coeff * jloc_;
    scatter(e, out.cost_gradient.transpose(), e.grow, smp.final);
  }
  if (smp.final) {
    const Vector6d xl = e.x.segment<6>(lambda_index_);
    out.cost += smp.weight * config_.w_wrench * xl.squaredNorm();
    if (e.gradients) {
      out.cost_gradient.segment<6>(lambda_index_) += smp.weight * 2.0 * config_.w_wrench * xl;
    }
  }
}

void TransitionNlp::addPathInequalities(const Sample& smp, int i, EvalState& e) {
  const StanceReducedDynamics& d = *dyn_;
  NlpValues& out = e.out;
  const double W = weight_;
  const bool final = smp.final;
  const auto lam = signals_.segment<6>(d.lambdaOffset());
  const Eigen::VectorXd& us = u_scaled_;  // set by addSampleCost
  int& row = e.row;
  // Stance cone (8): -(C lambda_s) / (m g) + margin <= 0.
  out.inequality.segment<ContactWrenchCone::kRows>(row) =
      -(C_stance_ * lam) / W + Eigen::Matrix<double, 16, 1>::Constant(config_.cone_margin);
  if (e.gradients) {
    e.cone_rows.noalias() = (-1.0 / W) * C_stance_ * jloc_.middleRows<6>(d.lambdaOffset());
    for (int r = 0; r < ContactWrenchCone::kRows; ++r) {
      scatter(e, out.inequality_jacobian.row(row + r), e.cone_rows.row(r), final);
    }
  }
  row += ContactWrenchCone::kRows;
  // Torque bounds: +-u / u_max - (1 - margin) <= 0.
  for (int a = 0; a < nu_; ++a) {
    for (int sgn = -1; sgn <= 1; sgn += 2) {
      out.inequality[row] = sgn * us[a] - (1.0 - config_.torque_margin);
      if (e.gradients) {
        e.grow = (sgn * u_max_inv_[a]) * jloc_.row(d.uOffset() + a);
        scatter(e, out.inequality_jacobian.row(row), e.grow, final);
      }
      ++row;
    }
  }
  // Ground clearance: floor(t) - z_swing <= 0 (not at t_0, fixed, nor t_f, an equality).
  if (ground_clearance_ && i > 0 && smp.t < basis_.duration()) {
    out.inequality[row] = groundFloor(smp.t) - signals_[d.swingPositionOffset() + 2];
    if (e.gradients) {
      e.grow = -jloc_.row(d.swingPositionOffset() + 2);
      scatter(e, out.inequality_jacobian.row(row), e.grow, final);
    }
    ++row;
  }
  // Leg clearance: margin - d(q) <= 0 (not at t_0, fixed; at t_f once, in single support).
  if (hasLegRow(smp, i)) {
    const SampleEval& se = sample_eval_[i];
    out.inequality[row] = leg_row_bound_ - se.leg_distance;
    if (e.gradients) {
      e.grow.noalias() = -se.leg_gradient * jloc_.middleRows(d.qOffset(), nq_);
      scatter(e, out.inequality_jacobian.row(row), e.grow, final);
    }
    ++row;
  }
  // Reachable-set hulls: A y - b <= 0, y the swing sole's (x, y).
  for (int s : smp.slices) {
    const Eigen::MatrixX2d& A = slice_A_[s];
    const Eigen::VectorXd& b = slice_b_[s];
    const Eigen::Vector2d y = signals_.segment<2>(d.swingPositionOffset());
    for (Eigen::Index r = 0; r < A.rows(); ++r) {
      out.inequality[row] = A.row(r).dot(y) - b[r];
      if (e.gradients) {
        e.grow = A(r, 0) * jloc_.row(d.swingPositionOffset()) +
                 A(r, 1) * jloc_.row(d.swingPositionOffset() + 1);
        scatter(e, out.inequality_jacobian.row(row), e.grow, final);
      }
      ++row;
    }
  }
}

void TransitionNlp::addTerminalRows(EvalState& e) {
  const StanceReducedDynamics& d = *dyn_;
  NlpValues& out = e.out;
  const Eigen::VectorXd& x = e.x;
  const bool gradients = e.gradients;
  // New contact's cone at t_f: -(C lambda_2) / (m g) <= 0, linear in the variables.
  const Vector6d xl = x.segment<6>(lambda_index_);
  out.inequality.segment<ContactWrenchCone::kRows>(e.row) = -(C_new_ * xl);
  if (gradients) {
    out.inequality_jacobian.block<ContactWrenchCone::kRows, 6>(e.row, lambda_index_) = -C_new_;
  }
  e.row += ContactWrenchCone::kRows;

  // ---- equalities: new-mode contact at t_f ------------------------------------------------
  int erow = 0;
  // Rows scaled to metres by the knot spacing h (phidot h, phiddot h^2): a control point
  // moves q by O(1), qd by O(1/h) and qdd by O(1/h^2), so unscaled acceleration rows would be
  // ~100x more sensitive than the others and SLSQP would stall short of feasibility on them.
  const double h = basis_.knotSpacing();
  auto addEquality = [&](int signal_offset, double scale) {
    out.equality.segment<6>(erow) = scale * signals_.segment<6>(signal_offset);
    if (gradients) {
      for (int r = 0; r < 6; ++r) {
        e.grow = scale * jloc_.row(signal_offset + r);
        scatter(e, out.equality_jacobian.row(erow + r), e.grow, true);
      }
    }
    erow += 6;
  };
  if (relaxed_) {
    addEquality(d.phi2Offset(), 1.0);
    out.equality.head<2>() -= x.segment<2>(eps_index_);
    if (gradients) {
      out.equality_jacobian(0, eps_index_) -= 1.0;
      out.equality_jacobian(1, eps_index_ + 1) -= 1.0;
    }
    addEquality(d.phidot2Offset(), h);
  }
  addEquality(d.phiddot2Offset(), h * h);
  if (pelvis_posture_) {  // base z, pitch, roll at t_f
    const int rows[3] = {2, 4, 5};
    for (int r : rows) {
      out.equality[erow] = signals_[d.qOffset() + r] - (r == 2 ? pelvis_height_target_ : 0.0);
      if (gradients) {
        scatter(e, out.equality_jacobian.row(erow), jloc_.row(d.qOffset() + r), true);
      }
      ++erow;
    }
  }
}

/// Samples the solution at dt (and exactly at t_f) into `res`.
void TransitionNlp::sampleSolution(const Eigen::VectorXd& x, double dt, TransitionResult& res) {
  const Side stance = request_.stance;
  const double T = basis_.duration();
  int n = static_cast<int>(std::floor(T / dt + 1e-9)) + 1;
  const bool on_grid = std::abs((n - 1) * dt - T) <= 1e-9;
  if (!on_grid) ++n;
  res.dt = dt;
  res.time.resize(n);
  res.q.resize(nq_, n);
  res.qd.resize(nq_, n);
  res.qdd.resize(nq_, n);
  res.u.resize(nu_, n);
  res.lambda.setZero(12, n);
  const int is = stance == Side::kLeft ? 0 : 6, in = 6 - is;
  TransitionSampleState st;
  for (int k = 0; k < n; ++k) {
    const double t = k + 1 == n ? T : k * dt;
    state(x, t, st);
    res.time[k] = t;
    res.q.col(k) = st.q;
    res.qd.col(k) = st.qd;
    res.qdd.col(k) = st.qdd;
    res.u.col(k) = st.u;
    res.lambda.col(k).segment<6>(is) = st.lambda_stance;
    res.lambda.col(k).segment<6>(in) = st.lambda_new;
    if (k + 1 == n) res.landing_position = st.swing_position;
  }
  res.relaxed = relaxed_;
  res.eps = eps(x);
}

}  // namespace reach_trajopt
