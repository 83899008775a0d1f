/// \file reachability_analyzer.cpp
/// The bidirectional reachability check (see the header).

#include "reach_trajopt/reach/reachability_analyzer.h"

#include <omp.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <memory>
#include <sstream>
#include <type_traits>

#include "reach_trajopt/common/error.h"
#include "reach_trajopt/reach/backward_step.h"
#include "reach_trajopt/reach/boundary_selection.h"
#include "reach_trajopt/reach/counter_rng.h"
#include "reach_trajopt/reach/forward_step.h"
#include "reach_trajopt/reach/output_hull.h"
#include "reach_trajopt/reach/reach_context.h"

namespace reach_trajopt {

namespace {

constexpr int kChunk = 64;  // children per work item (fixed: results do not depend on threads)
// Below this many draws a step runs serially: a parallel region costs more than it saves.
constexpr long kParallelMin = 256;
enum Direction : std::uint64_t { kForward = 1, kBackward = 2 };

using Clock = std::chrono::steady_clock;
double since(Clock::time_point t0) {
  return std::chrono::duration<double>(Clock::now() - t0).count();
}

std::string fmt(double v, int precision = 3) {
  std::ostringstream os;
  os.precision(precision);
  os << v;
  return os.str();
}

/// Fills `out` with draw number `c` of `n_children` from the box [-bound, bound]. The first
/// vertices(n_children) draws are vertices of the box in antithetic pairs (draw 2k + 1 is the
/// negative of draw 2k), so every parent gets opposite bang-bang children; the rest are
/// uniform. Each draw depends only on its key (seed, direction, step, parent, child).
int vertexDraws(double vertex_fraction, int n_children) {
  if (vertex_fraction <= 0.0 || n_children < 2) return 0;
  const int pairs = static_cast<int>(std::ceil(0.5 * vertex_fraction * n_children));
  return std::min(2 * pairs, n_children - n_children % 2);
}

void drawBox(std::uint64_t seed, Direction dir, int step, int parent, int c, int n_vertex,
             const Eigen::VectorXd& bound, Eigen::Ref<Eigen::VectorXd> out) {
  if (c < n_vertex) {
    CounterRng rng(seed, dir, static_cast<std::uint64_t>(step), static_cast<std::uint64_t>(parent),
                   static_cast<std::uint64_t>(c / 2));
    const double sign = (c % 2) ? -1.0 : 1.0;
    for (int i = 0; i < bound.size(); ++i)
      out[i] = sign * ((rng.next() >> 63) ? bound[i] : -bound[i]);
    return;
  }
  CounterRng rng(seed, dir | 0x100, static_cast<std::uint64_t>(step),
                 static_cast<std::uint64_t>(parent), static_cast<std::uint64_t>(c));
  for (int i = 0; i < bound.size(); ++i) out[i] = rng.uniform(-bound[i], bound[i]);
}

/// Throws ReachError when (q, qd) violates the limits or the held contacts.
void validateState(const ReachContext& ctx, const char* which,
                   const Eigen::VectorXd& q, const Eigen::VectorXd& qd,
                   const std::vector<ContactConstraint>& contacts) {
  const RobotModel& model = *ctx.model;
  try {
    model.checkState(q, qd);
  } catch (const ReachError& e) {
    throw ReachError(std::string("reachability: ") + which + ": " + e.what());
  }
  const double tol = std::max(ctx.config.limit_tolerance, 1e-9);
  for (int i : ctx.finite_position)
    if (q[i] < ctx.q_min[i] - tol || q[i] > ctx.q_max[i] + tol)
      throw ReachError(std::string("reachability: ") + which + " violates the position limits of " +
                       model.joints()[i].name + " (q = " + fmt(q[i], 6) + ", limits [" +
                       fmt(ctx.q_min[i], 6) + ", " + fmt(ctx.q_max[i], 6) + "])");
  for (int i : ctx.finite_velocity)
    if (std::abs(qd[i]) > ctx.qd_max[i] + tol)
      throw ReachError(std::string("reachability: ") + which + " violates the velocity limit of " +
                       model.joints()[i].name + " (|qd| = " + fmt(std::abs(qd[i]), 6) + " > " +
                       fmt(ctx.qd_max[i], 6) + ")");
  Workspace ws(model);
  model.update(ws, q, qd);
  ContactConstraintTerms t(model.nq());
  for (const ContactConstraint& c : contacts) {
    c.evaluate(model, ws, t);
    const std::string frame = model.frameNames()[c.frame()];
    if (t.phi.cwiseAbs().maxCoeff() > ctx.config.contact_tolerance)
      throw ReachError(std::string("reachability: ") + which + " violates the contact of " + frame +
                       " (|phi| = " + fmt(t.phi.cwiseAbs().maxCoeff()) + " > contact_tolerance " +
                       fmt(ctx.config.contact_tolerance) + ")");
    if (t.phidot.cwiseAbs().maxCoeff() > ctx.config.contact_velocity_tolerance)
      throw ReachError(std::string("reachability: ") + which + " moves the held sole " + frame +
                       " (|J qd| = " + fmt(t.phidot.cwiseAbs().maxCoeff()) +
                       " > contact_velocity_tolerance " +
                       fmt(ctx.config.contact_velocity_tolerance) + ")");
  }
}

/// Per-thread scratch of one direction.
template <class Step>
struct Scratch {
  explicit Scratch(const ReachContext& ctx)
      : step(ctx), q(ctx.n), qd(ctx.n), draw(ctx.model->nq()), u(ctx.nu) {}
  Step step;
  Eigen::VectorXd q, qd, draw, u;
};

/// One propagation step: children of every boundary sample of `prev` into `next`.
template <class Step>
void propagate(const ReachContext& ctx, Direction dir, int step_index, int n_children,
               const SampleSlice& prev, SampleSlice& next,
               std::vector<std::unique_ptr<Scratch<Step>>>& scratch, long& rejected) {
  const int n = ctx.n, nu = ctx.nu, m = ctx.m(), ny = ctx.ny();
  const int parents = static_cast<int>(prev.kept.size());
  const long total = static_cast<long>(parents) * n_children;
  std::vector<char> ok(total, 0);
  Eigen::MatrixXd qd(n, total), y(ny, total), yr(ny, total), u(nu, total), lam(m, total);
  const int chunks = (n_children + kChunk - 1) / kChunk;
  const int items = parents * chunks;
  const int threads = static_cast<int>(scratch.size());
  const std::uint64_t seed = ctx.config.seed;
  const int n_vertex = vertexDraws(ctx.config.vertex_fraction, n_children);
#pragma omp parallel for schedule(dynamic, 1) num_threads(threads) if (total >= kParallelMin)
  for (int item = 0; item < items; ++item) {
    Scratch<Step>& s = *scratch[omp_get_thread_num()];
    const int k = item / chunks;
    const int c0 = (item % chunks) * kChunk;
    const int c1 = std::min(c0 + kChunk, n_children);
    const int parent = prev.kept[k];
    if (!s.step.setParent(prev.q_kept.col(k), prev.qd.col(parent))) continue;
    for (int c = c0; c < c1; ++c) {
      const long col = static_cast<long>(k) * n_children + c;
      bool good;
      if constexpr (std::is_same<Step, ForwardStep>::value) {
        drawBox(seed, dir, step_index, parent, c, n_vertex, ctx.u_max, s.u);
        good = s.step.child(s.u, s.q, qd.col(col), y.col(col), yr.col(col), u.col(col),
                            lam.col(col));
      } else {
        drawBox(seed, dir, step_index, parent, c, n_vertex, s.step.drawBound(), s.draw);
        good = s.step.child(s.draw, s.q, qd.col(col), y.col(col), yr.col(col), u.col(col),
                            lam.col(col));
      }
      ok[col] = good ? 1 : 0;
    }
  }
  long kept = 0;
  for (long i = 0; i < total; ++i) kept += ok[i];
  rejected += total - kept;
  next.parent.resize(kept);
  next.qd.resize(n, kept);
  next.output.resize(ny, kept);
  next.output_rate.resize(ny, kept);
  next.u.resize(nu, kept);
  next.lambda.resize(m, kept);
  long j = 0;
  for (long i = 0; i < total; ++i) {
    if (!ok[i]) continue;
    next.parent[j] = prev.kept[i / n_children];
    next.qd.col(j) = qd.col(i);
    next.output.col(j) = y.col(i);
    next.output_rate.col(j) = yr.col(i);
    next.u.col(j) = u.col(i);
    next.lambda.col(j) = lam.col(i);
    ++j;
  }
}

/// Selects the boundary (21) of a slice and stores the configurations of its samples.
void selectAndStore(const ReachContext& ctx, bool forward, const SampleSlice& prev,
                    SampleSlice& s) {
  BoundaryRule rule;
  rule.lookahead = ctx.config.boundary_lookahead;
  if (!forward)  // backward slices look back in time
    for (double& tau : rule.lookahead) tau = -tau;
  rule.angular_bins = ctx.config.angular_bins;
  rule.max_boundary = ctx.config.max_boundary;
  s.boundary = selectBoundary(s.output, s.output_rate, rule);
  // Interior picks: evenly spread over the samples not on the boundary.
  std::vector<char> on(s.size(), 0);
  for (int i : s.boundary) on[i] = 1;
  std::vector<int> rest;
  for (int i = 0; i < s.size(); ++i)
    if (!on[i]) rest.push_back(i);
  s.kept = s.boundary;
  const int want = std::min<int>(ctx.config.interior_samples, static_cast<int>(rest.size()));
  for (int k = 0; k < want; ++k)
    s.kept.push_back(rest[(static_cast<long>(k) * static_cast<long>(rest.size())) / want]);
  std::sort(s.kept.begin(), s.kept.end());
  s.q_kept.resize(ctx.n, s.kept.size());
  s.kept_column.assign(s.size(), -1);
  const double dt = ctx.config.dt;
  for (std::size_t k = 0; k < s.kept.size(); ++k) {
    const int i = s.kept[k];
    const int p = s.parent[i];
    const int pc = prev.kept_column[p];
    if (forward)
      forwardConfiguration(prev.q_kept.col(pc), prev.qd.col(p), s.qd.col(i), dt,
                           ctx.config.semiImplicit(), s.q_kept.col(k));
    else
      backwardConfiguration(prev.q_kept.col(pc), prev.qd.col(p), dt, s.q_kept.col(k));
    s.kept_column[i] = static_cast<int>(k);
  }
}

/// Slice 0: the root state alone.
SampleSlice rootSlice(const ReachContext& ctx, double time, const Eigen::VectorXd& q,
                      const Eigen::VectorXd& qd) {
  SampleSlice s;
  s.time = time;
  s.parent = {-1};
  s.qd = qd;
  s.u = Eigen::MatrixXd::Zero(ctx.nu, 1);
  s.lambda = Eigen::MatrixXd::Zero(ctx.m(), 1);
  s.output.resize(ctx.ny(), 1);
  s.output_rate.resize(ctx.ny(), 1);
  Workspace ws(*ctx.model);
  ctx.model->update(ws, q, qd);
  ctx.output(ws, s.output.col(0), s.output_rate.col(0));
  s.boundary = {0};
  s.kept = {0};
  s.q_kept = q;
  s.kept_column = {0};
  return s;
}

/// q of any sample, from its parent's stored configuration.
Eigen::VectorXd configurationOf(const std::vector<SampleSlice>& slices, bool forward, double dt,
                                bool semi, int slice, int index) {
  const SampleSlice& s = slices.at(slice);
  if (index < 0 || index >= s.size()) throw ReachError("sampleConfiguration: index out of range");
  if (s.kept_column[index] >= 0) return s.q_kept.col(s.kept_column[index]);
  const SampleSlice& prev = slices.at(slice - 1);
  const int p = s.parent[index];
  Eigen::VectorXd q(s.qd.rows());
  if (forward)
    forwardConfiguration(prev.q_kept.col(prev.kept_column[p]), prev.qd.col(p),
                         s.qd.col(index), dt, semi, q);
  else
    backwardConfiguration(prev.q_kept.col(prev.kept_column[p]), prev.qd.col(p), dt, q);
  return q;
}

/// Largest violations of the path's states and steps (see PathViolation).
void measurePath(const ReachContext& ctx, WitnessPath& w) {
  const RobotModel& model = *ctx.model;
  Workspace ws(model);
  const int n = ctx.n, nu = ctx.nu;
  const int L = static_cast<int>(w.q.cols());
  Eigen::MatrixXd M(n, n), J(6, n);
  Eigen::VectorXd b(n), r(n);
  ContactConstraintTerms t(n);
  ContactWrenchCone::Matrix C;
  PathViolation& v = w.violation;
  const double dt = ctx.config.dt;
  for (int k = 0; k < L; ++k) {
    const auto q = w.q.col(k);
    const auto qd = w.qd.col(k);
    for (int i : ctx.finite_position)
      v.position_limit = std::max({v.position_limit, q[i] - ctx.q_max[i], ctx.q_min[i] - q[i]});
    for (int i : ctx.finite_velocity)
      v.velocity_limit = std::max(v.velocity_limit, std::abs(qd[i]) - ctx.qd_max[i]);
    model.update(ws, q, qd);
    for (const ContactConstraint& c : ctx.contacts) {
      c.evaluate(model, ws, t);
      v.contact = std::max(v.contact, t.phi.cwiseAbs().maxCoeff());
      v.contact_velocity = std::max(v.contact_velocity, t.phidot.cwiseAbs().maxCoeff());
    }
    if (k + 1 >= L || k == w.junction) continue;
    // Step k -> k+1: eq. (1) at state k.
    model.massMatrix(ws, M);
    model.bias(ws, b);
    const Eigen::VectorXd qdd = (w.qd.col(k + 1) - qd) / dt;
    r = M * qdd + b;
    r.tail(nu) -= w.u.col(k);
    for (int c = 0; c < ctx.nc; ++c) {
      const FrameId f = ctx.contacts[c].frame();
      model.frameJacobian(ws, f, J);
      const Vector6d lam = w.lambda.col(k).segment<6>(6 * c);
      r -= J.transpose() * lam;
      ctx.cone.worldMatrix(model.framePose(ws, f).linear(), C);
      v.cone = std::max(v.cone, -(C * lam).minCoeff());
    }
    v.dynamics = std::max(v.dynamics, r.cwiseAbs().maxCoeff());
    for (int i = 0; i < nu; ++i)
      v.torque = std::max(v.torque, std::abs(w.u(i, k)) - ctx.u_max[i]);
    Eigen::VectorXd qn(n);
    forwardConfiguration(q, qd, w.qd.col(k + 1), dt, w.semi_implicit_step[k] != 0, qn);
    v.integration = std::max(v.integration, (w.q.col(k + 1) - qn).cwiseAbs().maxCoeff());
  }
}

}  // namespace

double PathViolation::max() const {
  return std::max({dynamics, cone, torque, position_limit, velocity_limit, contact,
                   contact_velocity, integration});
}

ReachabilityAnalyzer::ReachabilityAnalyzer(std::shared_ptr<const RobotModel> model,
                                           const ContactConfig& contact,
                                           const ReachConfig& config)
    : model_(std::move(model)), contact_(contact), config_(config) {
  if (!model_) throw ReachError("ReachabilityAnalyzer: null model");
  contact_.validate();
  config_.validate();
}

ReachResult ReachabilityAnalyzer::check(const ReachProblem& problem) const {
  return check(problem, config_);
}

Eigen::VectorXd ReachabilityAnalyzer::sampleConfiguration(const ReachResult& result, bool forward,
                                                          int slice, int index) const {
  return configurationOf(forward ? result.forward : result.backward, forward, result.dt,
                         result.semi_implicit, slice, index);
}

ReachResult ReachabilityAnalyzer::check(const ReachProblem& pb, const ReachConfig& config) const {
  const auto t_start = Clock::now();
  config.validate();
  config.requireResourcesWithinLimits(model_->nq());  // before any sample is drawn
  const ReachContext ctx(model_, contact_, config, pb.mode, pb.footholds, pb.target);
  const RobotModel& model = *model_;
  // ---- input checks ---------------------------------------------------------------------
  validateState(ctx, "x_0", pb.q0, pb.qd0, ctx.contacts);
  std::vector<ContactConstraint> final_contacts = ctx.contacts;
  if (pb.target) {
    if (!pb.mode.isSingleSupport())
      throw ReachError("reachability: a target foothold needs a single-support mode, got " +
                       pb.mode.name());
    final_contacts.emplace_back(model, pb.mode.swing() == Side::kLeft ? contact_.left_sole_frame
                                                                      : contact_.right_sole_frame,
                                *pb.target);
  }
  validateState(ctx, "x_f", pb.qf, pb.qdf, final_contacts);

  const double dt = config.dt;
  const int i_t = static_cast<int>(std::lround(config.horizon / dt));
  const int i_1 = static_cast<int>(std::lround(config.window_end / dt));
  const int i_2 = static_cast<int>(std::lround(config.window_start / dt));
  const int n_fwd = i_1;        // forward steps
  const int n_bwd = i_t - i_2;  // backward steps

  ReachResult res;
  res.dt = dt;
  res.semi_implicit = config.semiImplicit();
  for (const JointInfo& j : model.joints()) res.joint_names.push_back(j.name);
  const int threads = config.threads > 0 ? config.threads : omp_get_max_threads();
  res.counts.threads = threads;

  // ---- forward set (15)-(16) --------------------------------------------------------------
  {
    const auto t0 = Clock::now();
    std::vector<std::unique_ptr<Scratch<ForwardStep>>> scratch;
    for (int i = 0; i < threads; ++i)
      scratch.push_back(std::make_unique<Scratch<ForwardStep>>(ctx));
    res.forward.reserve(n_fwd + 1);
    res.forward.push_back(rootSlice(ctx, 0.0, pb.q0, pb.qd0));
    double boundary_time = 0.0;
    for (int j = 0; j < n_fwd; ++j) {
      SampleSlice next;
      next.time = (j + 1) * dt;
      propagate(ctx, kForward, j, j == 0 ? config.initial_samples : config.children_per_parent,
                res.forward[j], next, scratch, res.counts.forward_rejected);
      const auto tb = Clock::now();
      selectAndStore(ctx, true, res.forward[j], next);
      boundary_time += since(tb);
      res.counts.forward_samples += next.size();
      res.forward.push_back(std::move(next));
    }
    for (const auto& s : scratch) res.counts.forward_qps += s->step.qpCount();
    res.timings.boundary += boundary_time;
    res.timings.forward = since(t0) - boundary_time;
  }
  // ---- backward set (17)-(20) -------------------------------------------------------------
  {
    const auto t0 = Clock::now();
    std::vector<std::unique_ptr<Scratch<BackwardStep>>> scratch;
    for (int i = 0; i < threads; ++i)
      scratch.push_back(std::make_unique<Scratch<BackwardStep>>(ctx));
    res.backward.reserve(n_bwd + 1);
    res.backward.push_back(rootSlice(ctx, i_t * dt, pb.qf, pb.qdf));
    double boundary_time = 0.0;
    for (int j = 0; j < n_bwd; ++j) {
      SampleSlice next;
      next.time = (i_t - j - 1) * dt;
      propagate(ctx, kBackward, j,
                j == 0 ? config.initial_samples : config.backward_children_per_parent,
                res.backward[j], next, scratch, res.counts.backward_rejected);
      const auto tb = Clock::now();
      selectAndStore(ctx, false, res.backward[j], next);
      boundary_time += since(tb);
      res.counts.backward_samples += next.size();
      res.backward.push_back(std::move(next));
    }
    for (const auto& s : scratch) res.counts.backward_qps += s->step.qpCount();
    res.timings.boundary += boundary_time;
    res.timings.backward = since(t0) - boundary_time;
  }
  // ---- the test (14) on the overlap window ----------------------------------------------
  {
    const auto t0 = Clock::now();
    for (int i = i_2; i <= i_1; ++i) {
      SliceComparison c;
      c.time = i * dt;
      c.forward_slice = i;
      c.backward_slice = i_t - i;
      c.distance = hausdorffDistance(res.forward[i].output, res.backward[i_t - i].output);
      const double K = c.distance.resolution();
      c.overlap_tolerance = std::min(K, config.overlap_gap_max);
      const SampleSlice& F = res.forward[i];
      const SampleSlice& B = res.backward[i_t - i];
      if (F.size() > 0 && B.size() > 0) {
        // Inside a hull up to the sampling resolution (a set touching a face, e.g. x_f's sole
        // on the ground plane that bounds the forward set, counts as inside).
        c.backward_inside_forward = OutputHull(F.output).countInside(B.output, c.overlap_tolerance);
        c.forward_inside_backward = OutputHull(B.output).countInside(F.output, c.overlap_tolerance);
      }
      c.overlap = c.distance.closest <= c.overlap_tolerance || c.backward_inside_forward > 0 ||
                  c.forward_inside_backward > 0;
      c.within_delta = c.distance.hausdorff <= std::min(config.delta, K);
      res.window.push_back(c);
    }
    res.timings.hausdorff = since(t0);
  }
  // ---- verdict and witness ----------------------------------------------------------------
  const auto tw = Clock::now();
  int best = -1;
  bool best_ok = false;
  for (int k = 0; k < static_cast<int>(res.window.size()); ++k) {
    const SliceComparison& c = res.window[k];
    const bool ok = c.overlap || c.within_delta;
    if (c.distance.closest_a < 0) continue;
    if (best < 0 || (ok && !best_ok) ||
        (ok == best_ok && c.distance.closest < res.window[best].distance.closest)) {
      best = k;
      best_ok = ok;
    }
  }
  res.best = best;
  res.reachable = best_ok;
  if (best < 0) {
    res.reason = "unreachable: a forward or backward slice of the window is empty (every draw "
                 "was rejected)";
  } else {
    const SliceComparison& c = res.window[best];
    std::ostringstream os;
    if (best_ok && c.overlap)
      os << "reachable: the forward and backward output sets overlap at t = " << fmt(c.time)
         << " s (" << c.backward_inside_forward << " backward samples inside the forward hull, "
         << c.forward_inside_backward << " forward samples inside the backward hull, closest "
         << "pair " << fmt(c.distance.closest) << " m)";
    else if (best_ok)
      os << "reachable: d_H = " << fmt(c.distance.hausdorff) << " m <= min(delta, K) at t = "
         << fmt(c.time) << " s (Prop. 2)";
    else
      os << "unreachable: the forward and backward output sets stay apart over the window [" 
         << fmt(config.window_start) << ", " << fmt(config.window_end)
         << "] s; closest approach " << fmt(c.distance.closest) << " m at t = " << fmt(c.time)
         << " s (tolerance " << fmt(c.overlap_tolerance) << " m)";
    res.reason = os.str();
    // Witness: x_0 -> a (forward chain), b -> x_f (backward chain).
    WitnessPath& w = res.witness;
    std::vector<std::pair<int, int>> fchain, bchain;
    for (int s = c.forward_slice, i = c.distance.closest_a; s >= 0;
         i = res.forward[s].parent[i], --s)
      fchain.push_back({s, i});
    std::reverse(fchain.begin(), fchain.end());
    for (int s = c.backward_slice, i = c.distance.closest_b; s >= 0;
         i = res.backward[s].parent[i], --s)
      bchain.push_back({s, i});
    const int L = static_cast<int>(fchain.size() + bchain.size());
    const int n = ctx.n;
    w.q.resize(n, L);
    w.qd.resize(n, L);
    w.output.resize(ctx.ny(), L);
    w.u = Eigen::MatrixXd::Zero(ctx.nu, L - 1);
    w.lambda = Eigen::MatrixXd::Zero(ctx.m(), L - 1);
    w.semi_implicit_step.assign(L - 1, 1);
    w.junction = static_cast<int>(fchain.size()) - 1;
    int k = 0;
    for (const auto& [s, i] : fchain) {
      w.time.push_back(res.forward[s].time);
      w.q.col(k) = configurationOf(res.forward, true, dt, res.semi_implicit, s, i);
      w.qd.col(k) = res.forward[s].qd.col(i);
      w.output.col(k) = res.forward[s].output.col(i);
      if (k > 0) {
        w.u.col(k - 1) = res.forward[s].u.col(i);
        w.lambda.col(k - 1) = res.forward[s].lambda.col(i);
        w.semi_implicit_step[k - 1] = res.semi_implicit ? 1 : 0;
      }
      ++k;
    }
    for (const auto& [s, i] : bchain) {
      w.time.push_back(res.backward[s].time);
      w.q.col(k) = configurationOf(res.backward, false, dt, true, s, i);
      w.qd.col(k) = res.backward[s].qd.col(i);
      w.output.col(k) = res.backward[s].output.col(i);
      if (k < L - 1) {
        w.u.col(k) = res.backward[s].u.col(i);
        w.lambda.col(k) = res.backward[s].lambda.col(i);
      }
      ++k;
    }
    const int a = w.junction;
    w.output_gap = (w.output.col(a) - w.output.col(a + 1)).norm();
    w.position_gap = (w.q.col(a) - w.q.col(a + 1)).cwiseAbs().maxCoeff();
    w.velocity_gap = (w.qd.col(a) - w.qd.col(a + 1)).cwiseAbs().maxCoeff();
    measurePath(ctx, w);
    w.valid = true;
  }
  res.timings.witness = since(tw);
  res.timings.total = since(t_start);
  return res;
}

}  // namespace reach_trajopt
