/// \file witness_certificate.cpp
/// Junction candidates, bridged witness paths and their certificate (see the header).

#include "reach_trajopt/reach/witness_certificate.h"

#include <omp.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <exception>
#include <limits>
#include <memory>
#include <mutex>
#include <tuple>

#include "reach_trajopt/reach/forward_step.h"
#include "reach_trajopt/reach/junction_bridge.h"
#include "reach_trajopt/reach/set_propagation.h"

namespace reach_trajopt {

namespace {

/// Bridge-effort features [6 q / T^2; 4 qd / T] of every sample of a slice (2 n_q x size).
Eigen::MatrixXd effortFeatures(const std::vector<SampleSlice>& slices,
                               PropagationDirection direction, double dt, bool semi_implicit,
                               int slice, double T) {
  const SampleSlice& s = slices[slice];
  const int n = static_cast<int>(s.qd.rows());
  Eigen::MatrixXd f(2 * n, s.size());
  for (int i = 0; i < s.size(); ++i) {
    f.col(i).head(n) =
        (6.0 / (T * T)) * sampleConfigurationOf(slices, direction, dt, semi_implicit, slice, i);
    f.col(i).tail(n) = (4.0 / T) * s.qd.col(i);
  }
  return f;
}

/// The terminal part of withinCertificate: x(t_f) within the tolerances of x_f.
bool withinTerminalTolerance(const ReachConfig& config, const WitnessPath& w) {
  return w.terminal_position_gap <= config.terminal_position_tolerance &&
         w.terminal_velocity_gap <= config.terminal_velocity_tolerance;
}

bool before(const JunctionCandidate& a, const JunctionCandidate& b) {
  return std::tie(a.effort, a.window_index, a.forward_sample, a.backward_sample) <
         std::tie(b.effort, b.window_index, b.forward_sample, b.backward_sample);
}

/// The `count` lowest-effort pairs of one window slice.
std::vector<JunctionCandidate> sliceCandidates(const ReachContext& ctx,
                                               const std::vector<SampleSlice>& forward,
                                               const std::vector<SampleSlice>& backward,
                                               const SliceComparison& c, int window_index,
                                               int count) {
  const ReachConfig& cfg = ctx.config;
  const double T = cfg.horizon - c.time;
  std::vector<JunctionCandidate> out;
  // The bridge needs two steps for its deadbeat end.
  if (T < 2.0 * cfg.dt - 1e-12) return out;
  if (forward[c.forward_slice].size() == 0 || backward[c.backward_slice].size() == 0) return out;
  const Eigen::MatrixXd F = effortFeatures(forward, PropagationDirection::kForward, cfg.dt,
                                           cfg.semiImplicit(), c.forward_slice, T);
  const Eigen::MatrixXd B =
      effortFeatures(backward, PropagationDirection::kBackward, cfg.dt, true, c.backward_slice, T);
  // |f - g|^2 = |f|^2 + |g|^2 - 2 f.g for every pair.
  Eigen::MatrixXd D = -2.0 * F.transpose() * B;
  D.colwise() += F.colwise().squaredNorm().transpose();
  D.rowwise() += B.colwise().squaredNorm();
  // The `count` best pairs, kept in a max-heap on `before` (no list of all N M pairs).
  std::vector<JunctionCandidate> best;
  best.reserve(static_cast<size_t>(count) + 1);
  for (int l = 0; l < D.cols(); ++l)
    for (int i = 0; i < D.rows(); ++i) {
      const JunctionCandidate c{window_index, i, l, std::max(0.0, D(i, l))};
      if (static_cast<int>(best.size()) == count && !before(c, best.front())) continue;
      best.push_back(c);
      std::push_heap(best.begin(), best.end(), before);
      if (static_cast<int>(best.size()) > count) {
        std::pop_heap(best.begin(), best.end(), before);
        best.pop_back();
      }
    }
  std::sort(best.begin(), best.end(), before);
  return best;
}

/// The backward set's chain `bchain` (slice, sample) from b to x_f as the bridge's reference:
/// configurations and velocities (n x N+1) and torques (nu x N).
BackwardChain backwardChainOf(const std::vector<SampleSlice>& backward,
                              const std::vector<std::pair<int, int>>& bchain, int n, int nu,
                              double dt) {
  const int N = static_cast<int>(bchain.size()) - 1;  // bridge steps
  BackwardChain chain;
  chain.q.resize(n, N + 1);
  chain.qd.resize(n, N + 1);
  chain.u.resize(nu, N);
  for (int k = 0; k <= N; ++k) {
    const auto [s, i] = bchain[k];
    chain.q.col(k) =
        sampleConfigurationOf(backward, PropagationDirection::kBackward, dt, true, s, i);
    chain.qd.col(k) = backward[s].qd.col(i);
    // A backward sample's torque acts during its step toward its parent (one step later).
    if (k < N) chain.u.col(k) = backward[s].u.col(i);
  }
  return chain;
}

/// The witness's samples: the forward chain `fchain` (x_0 -> a, configurations `q_fwd`), then
/// the bridge's `seg` from a. Sizes w's arrays; gaps and flags are the caller's.
void fillWitnessSamples(const ReachContext& ctx, const std::vector<SampleSlice>& forward,
                        const std::vector<std::pair<int, int>>& fchain,
                        const Eigen::MatrixXd& q_fwd, const BridgeSegment& seg, bool semi_implicit,
                        WitnessPath& w) {
  const double dt = ctx.config.dt;
  const int F = static_cast<int>(fchain.size());
  const int L = F + seg.steps_done;
  w.q.resize(ctx.n, L);
  w.qd.resize(ctx.n, L);
  w.output.resize(ctx.ny(), L);
  w.u = Eigen::MatrixXd::Zero(ctx.nu, L - 1);
  w.lambda = Eigen::MatrixXd::Zero(ctx.m(), L - 1);
  w.semi_implicit_step.assign(L - 1, ctx.config.semiImplicit() ? 1 : 0);
  for (int k = 0; k < F; ++k) {
    const auto [s, i] = fchain[k];
    w.time.push_back(forward[s].time);
    w.q.col(k) = q_fwd.col(k);
    w.qd.col(k) = forward[s].qd.col(i);
    w.output.col(k) = forward[s].output.col(i);
    if (k > 0) {
      w.u.col(k - 1) = forward[s].u.col(i);
      w.lambda.col(k - 1) = forward[s].lambda.col(i);
      w.semi_implicit_step[k - 1] = semi_implicit ? 1 : 0;
    }
  }
  const double t_a = forward[fchain.back().first].time;
  for (int j = 1; j <= seg.steps_done; ++j) {
    const int k = F - 1 + j;
    w.time.push_back(t_a + j * dt);
    w.q.col(k) = seg.q.col(j);
    w.qd.col(k) = seg.qd.col(j);
    w.output.col(k) = seg.output.col(j);
    w.u.col(k - 1) = seg.u.col(j - 1);
    w.lambda.col(k - 1) = seg.lambda.col(j - 1);
  }
}

/// x_0 -> a through the forward set, then the bridge from a along the backward chain from b
/// (direct: along the cubic from a to x_f); `measured`: its steps were re-checked (only when
/// x(t_f) lands on x_f, see below).
WitnessPath bridgedPath(const ReachContext& ctx, ForwardStep& step,
                        const std::vector<SampleSlice>& forward,
                        const std::vector<SampleSlice>& backward, const SliceComparison& c,
                        const JunctionCandidate& cand, bool semi_implicit, bool direct,
                        bool& measured) {
  measured = false;
  const double dt = ctx.config.dt;
  const int n = ctx.n;
  std::vector<std::pair<int, int>> fchain =
      chainToRoot(forward, c.forward_slice, cand.forward_sample);
  std::reverse(fchain.begin(), fchain.end());
  const std::vector<std::pair<int, int>> bchain =
      chainToRoot(backward, c.backward_slice, cand.backward_sample);
  const int N = static_cast<int>(bchain.size()) - 1;  // bridge steps
  BackwardChain chain = backwardChainOf(backward, bchain, n, ctx.nu, dt);
  const int F = static_cast<int>(fchain.size());
  WitnessPath w;
  Eigen::MatrixXd q_fwd(n, F);
  for (int k = 0; k < F; ++k)
    q_fwd.col(k) = sampleConfigurationOf(forward, PropagationDirection::kForward, dt, semi_implicit,
                                         fchain[k].first, fchain[k].second);
  const auto [sa, ia] = fchain.back();
  // The pair's gap, before a direct bridge replaces the chain.
  w.position_gap = (q_fwd.col(F - 1) - chain.q.col(0)).cwiseAbs().maxCoeff();
  w.velocity_gap = (forward[sa].qd.col(ia) - chain.qd.col(0)).cwiseAbs().maxCoeff();
  if (direct)
    chain = hermiteChain(q_fwd.col(F - 1), forward[sa].qd.col(ia), chain.q.col(N), chain.qd.col(N),
                         N, dt, forward[sa].u.col(ia));
  const BridgeSegment seg =
      bridgeJunction(ctx, step, q_fwd.col(F - 1), forward[sa].qd.col(ia), chain);
  fillWitnessSamples(ctx, forward, fchain, q_fwd, seg, semi_implicit, w);
  const int L = F + seg.steps_done;
  w.junction = -1;
  w.bridge_start = F - 1;
  const SampleSlice& b = backward[c.backward_slice];
  w.output_gap = (forward[sa].output.col(ia) - b.output.col(cand.backward_sample)).norm();
  if (seg.completed()) {
    w.terminal_position_gap = (w.q.col(L - 1) - chain.q.col(N)).cwiseAbs().maxCoeff();
    w.terminal_velocity_gap = (w.qd.col(L - 1) - chain.qd.col(N)).cwiseAbs().maxCoeff();
    w.terminal_output_gap = (w.output.col(L - 1) - backward[0].output.col(0)).norm();
  } else {
    w.terminal_position_gap = w.terminal_velocity_gap = w.terminal_output_gap = HUGE_VAL;
  }
  w.valid = true;
  // The re-check of every step (measurePath) can only matter when x(t_f) lands on x_f: an
  // attempt that misses it is never certified, and only the closest one is measured, by
  // certifyWitness, once it is known.
  if (seg.completed() && withinTerminalTolerance(ctx.config, w)) {
    measurePath(ctx, w);
    measured = true;
  }
  w.certified = measured && withinCertificate(ctx.config, w);
  return w;
}

}  // namespace

double terminalGapInTolerances(const ReachConfig& config, const WitnessPath& w) {
  if (!w.valid) return std::numeric_limits<double>::quiet_NaN();
  return std::max(w.terminal_position_gap / config.terminal_position_tolerance,
                  w.terminal_velocity_gap / config.terminal_velocity_tolerance);
}

std::vector<JunctionCandidate> junctionCandidates(const ReachContext& ctx,
                                                  const std::vector<SampleSlice>& forward,
                                                  const std::vector<SampleSlice>& backward,
                                                  const std::vector<SliceComparison>& window,
                                                  int count) {
  const int slices = static_cast<int>(window.size());
  std::vector<std::vector<JunctionCandidate>> per_slice(slices);
  const int threads = ctx.config.threads > 0 ? ctx.config.threads : omp_get_max_threads();
#pragma omp parallel for schedule(dynamic) num_threads(threads)
  for (int k = 0; k < slices; ++k)
    per_slice[k] = sliceCandidates(ctx, forward, backward, window[k], k, count);
  std::vector<JunctionCandidate> all;
  for (const auto& v : per_slice) all.insert(all.end(), v.begin(), v.end());
  std::sort(all.begin(), all.end(), before);
  if (static_cast<int>(all.size()) > count) all.resize(count);
  return all;
}

bool withinCertificate(const ReachConfig& config, const WitnessPath& w) {
  const PathViolation& v = w.violation;
  return w.bridge_start >= 0 && v.maxWithoutContact() <= config.certificate_tolerance &&
         v.contact <= config.contact_tolerance &&
         v.contact_velocity <= config.certificate_contact_velocity_tolerance &&
         w.terminal_position_gap <= config.terminal_position_tolerance &&
         w.terminal_velocity_gap <= config.terminal_velocity_tolerance;
}

WitnessPath certifyWitness(const ReachContext& ctx, const std::vector<SampleSlice>& forward,
                           const std::vector<SampleSlice>& backward,
                           const std::vector<SliceComparison>& window, bool semi_implicit) {
  const std::vector<JunctionCandidate> candidates =
      junctionCandidates(ctx, forward, backward, window, ctx.budget.certificate_candidates);
  // The attempts in their serial order: each candidate along its backward chain, then direct.
  // Threads claim them one at a time in that order, and claim none after an attempt that
  // certified; every attempt before the first certified one has then run. They are judged in
  // that order, so the witness (the first certified attempt) and the closest attempt are
  // those of a serial run for any thread count; only attempts claimed after the witness's are
  // wasted work. (Claimed one by one, a long attempt no longer holds a batch of short ones.)
  const int attempts = 2 * static_cast<int>(candidates.size());
  const int threads = std::max(
      1, std::min(ctx.config.threads > 0 ? ctx.config.threads : omp_get_max_threads(), attempts));
  std::vector<std::unique_ptr<ForwardStep>> steps;
  for (int t = 0; t < threads; ++t)
    steps.push_back(std::make_unique<ForwardStep>(ctx, junctionBridgeCost()));
  std::vector<WitnessPath> paths(attempts);
  std::vector<char> measured(attempts, 0);
  std::atomic<int> next_attempt{0};
  std::atomic<int> first_certified{attempts};
  std::exception_ptr error;  // the first exception of an attempt, rethrown after the region
  std::mutex error_mutex;
#pragma omp parallel num_threads(threads) if (threads > 1)
  {
    ForwardStep& step = *steps[omp_get_thread_num()];
    for (int a = next_attempt++; a < first_certified.load(); a = next_attempt++) {
      try {
        const JunctionCandidate& cand = candidates[a / 2];
        bool m = false;
        paths[a] = bridgedPath(ctx, step, forward, backward, window[cand.window_index], cand,
                               semi_implicit, a % 2 == 1, m);
        measured[a] = m ? 1 : 0;
        if (paths[a].certified) {
          int f = first_certified.load();
          while (a < f && !first_certified.compare_exchange_weak(f, a)) {
          }
        }
      } catch (...) {
        std::lock_guard<std::mutex> lock(error_mutex);
        if (!error) error = std::current_exception();
        first_certified.store(-1);  // every thread stops claiming
      }
    }
  }
  if (error) std::rethrow_exception(error);
  WitnessPath best;
  bool best_measured = false;
  int tried = 0;
  for (int a = 0; a < attempts; ++a) {
    tried = a / 2 + 1;
    WitnessPath& w = paths[a];
    w.candidates_tried = tried;
    if (w.certified) return std::move(w);
    // Keep the attempt that ended closest to x_f (a completed bridge before a stopped one).
    if (!best.valid || w.terminal_position_gap < best.terminal_position_gap ||
        (std::isinf(best.terminal_position_gap) && w.time.size() > best.time.size())) {
      best = std::move(w);
      best_measured = measured[a] != 0;
    }
  }
  if (best.valid && !best_measured) measurePath(ctx, best);  // its violations are reported
  best.candidates_tried = tried;
  return best;
}

}  // namespace reach_trajopt
