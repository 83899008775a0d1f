/// \file set_propagation.cpp
/// One direction of the reachability check (see the header).

#include "reach_trajopt/reach/set_propagation.h"

#include <omp.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <exception>
#include <memory>
#include <mutex>
#include <type_traits>

#include "reach_trajopt/common/error.h"
#include "reach_trajopt/reach/backward_step.h"
#include "reach_trajopt/reach/boundary_selection.h"
#include "reach_trajopt/reach/counter_rng.h"
#include "reach_trajopt/reach/forward_step.h"

namespace reach_trajopt {

namespace {

constexpr int kChunk = 64;  // children per work item (fixed: results do not depend on threads)
// Below this many draws a step runs in its direction's own task: tasks cost more than they
// save. 64, not 256: the quick pass's forward steps (32 kept x 4 children = 128 draws) ran
// serially at 256; at 64 its forward stage at the walk's horizon went from 0.11-0.13 s to
// 0.08 s on 2 threads (bench/README.md, issue 16).
constexpr long kParallelMin = 64;

/// What the directions run together share: the progress callback (never called
/// concurrently) and a stop flag, raised when one direction throws (cancelled).
struct SharedRun {
  explicit SharedRun(const ReachProgressCallback& cb) : progress(cb) {}
  const ReachProgressCallback& progress;
  std::mutex progress_mutex;
  std::atomic<bool> stop{false};
};
enum Direction : std::uint64_t { kForward = 1, kBackward = 2 };

using Clock = std::chrono::steady_clock;
double since(Clock::time_point t0) {
  return std::chrono::duration<double>(Clock::now() - t0).count();
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
  // Inside a team (propagateSets): the items are tasks; this direction's task waits for them
  // at the end of the taskloop, running tasks of either direction meanwhile.
#pragma omp taskloop default(shared) grainsize(1) if (threads > 1 && total >= kParallelMin)
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
        good =
            s.step.child(s.u, s.q, qd.col(col), y.col(col), yr.col(col), u.col(col), lam.col(col));
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
  rule.threads = ctx.config.threads > 0 ? ctx.config.threads : omp_get_max_threads();
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

/// The whole direction, for one step type.
template <class Step>
PropagationStats propagateWith(const ReachContext& ctx, bool forward, int root_index,
                               const Eigen::VectorXd& q, const Eigen::VectorXd& qd, int steps,
                               int threads, std::vector<SampleSlice>& slices, SharedRun& run) {
  const auto t0 = Clock::now();
  const ReachConfig& config = ctx.config;
  const double dt = config.dt;
  const int sign = forward ? 1 : -1;
  const Direction dir = forward ? kForward : kBackward;
  const int children = forward ? config.children_per_parent : config.backward_children_per_parent;
  PropagationStats stats;
  std::vector<std::unique_ptr<Scratch<Step>>> scratch;
  for (int i = 0; i < threads; ++i) scratch.push_back(std::make_unique<Scratch<Step>>(ctx));
  slices.clear();
  slices.reserve(steps + 1);
  slices.push_back(rootSlice(ctx, root_index * dt, q, qd));
  for (int j = 0; j < steps && !run.stop; ++j) {
    SampleSlice next;
    next.time = (root_index + sign * (j + 1)) * dt;
    propagate(ctx, dir, j, j == 0 ? config.initial_samples : children, slices[j], next, scratch,
              stats.rejected);
    const auto tb = Clock::now();
    selectAndStore(ctx, forward, slices[j], next);
    stats.boundary_time += since(tb);
    stats.samples += next.size();
    slices.push_back(std::move(next));
    if (run.progress) {
      ReachProgress p{forward, j + 1, steps, stats.samples, 0};
      for (const auto& sc : scratch) p.qps += sc->step.qpCount();
      bool cancelled = false;
      {
        std::lock_guard<std::mutex> lock(run.progress_mutex);
        if (!run.stop) cancelled = !run.progress(p);  // none after a cancel
        if (cancelled) run.stop = true;
      }
      if (cancelled)
        throw ReachCancelled(std::string("reachability check cancelled after ") +
                             std::to_string(j + 1) + " of " + std::to_string(steps) + " " +
                             (forward ? "forward" : "backward") + " slices");
    }
  }
  for (const auto& s : scratch) {
    stats.qps += s->step.qpCount();
    if constexpr (std::is_same<Step, BackwardStep>::value)
      stats.prefiltered += s->step.prefilterRejects();
  }
  stats.propagation_time = since(t0) - stats.boundary_time;
  return stats;
}

/// One direction inside a team's task. An exception may not leave an OpenMP task: it is
/// stored in `error` (and stops the other direction), for the caller to rethrow.
PropagationStats runDirection(const ReachContext& ctx, const PropagationRoot& r, int threads,
                              std::vector<SampleSlice>& slices, SharedRun& run,
                              std::exception_ptr& error) {
  try {
    if (r.direction == PropagationDirection::kForward)
      return propagateWith<ForwardStep>(ctx, true, r.root_index, r.q, r.qd, r.steps, threads,
                                        slices, run);
    return propagateWith<BackwardStep>(ctx, false, r.root_index, r.q, r.qd, r.steps, threads,
                                       slices, run);
  } catch (...) {
    error = std::current_exception();
    run.stop = true;
  }
  return {};
}

}  // namespace

void propagateSets(const ReachContext& ctx, const PropagationRoot& a, const PropagationRoot& b,
                   int threads, std::vector<SampleSlice>& slices_a,
                   std::vector<SampleSlice>& slices_b, PropagationStats& stats_a,
                   PropagationStats& stats_b, const ReachProgressCallback& progress) {
  SharedRun run(progress);
  std::exception_ptr error_a, error_b;
#pragma omp parallel num_threads(threads)
#pragma omp single
  {
#pragma omp task default(shared)
    stats_a = runDirection(ctx, a, threads, slices_a, run, error_a);
#pragma omp task default(shared)
    stats_b = runDirection(ctx, b, threads, slices_b, run, error_b);
#pragma omp taskwait
  }
  if (error_a) std::rethrow_exception(error_a);
  if (error_b) std::rethrow_exception(error_b);
}

PropagationStats propagateSet(const ReachContext& ctx, PropagationDirection direction,
                              int root_index, const Eigen::VectorXd& q, const Eigen::VectorXd& qd,
                              int steps, int threads, std::vector<SampleSlice>& slices,
                              const ReachProgressCallback& progress) {
  const PropagationRoot root{direction, root_index, q, qd, steps};
  SharedRun run(progress);
  PropagationStats stats;
  std::exception_ptr error;
#pragma omp parallel num_threads(threads)
#pragma omp single
  stats = runDirection(ctx, root, threads, slices, run, error);
  if (error) std::rethrow_exception(error);
  return stats;
}

Eigen::VectorXd sampleConfigurationOf(const std::vector<SampleSlice>& slices,
                                      PropagationDirection direction, double dt, bool semi_implicit,
                                      int slice, int index) {
  const bool forward = direction == PropagationDirection::kForward;
  const SampleSlice& s = slices.at(slice);
  if (index < 0 || index >= s.size()) throw ReachError("sampleConfiguration: index out of range");
  if (s.kept_column[index] >= 0) return s.q_kept.col(s.kept_column[index]);
  const SampleSlice& prev = slices.at(slice - 1);
  const int p = s.parent[index];
  Eigen::VectorXd q(s.qd.rows());
  if (forward)
    forwardConfiguration(prev.q_kept.col(prev.kept_column[p]), prev.qd.col(p), s.qd.col(index), dt,
                         semi_implicit, q);
  else
    backwardConfiguration(prev.q_kept.col(prev.kept_column[p]), prev.qd.col(p), dt, q);
  return q;
}

}  // namespace reach_trajopt
