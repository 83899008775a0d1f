/// \file set_propagation.cpp
/// One direction of the reachability check (see the header).

#include "reach_trajopt/reach/set_propagation.h"

#include <omp.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstdint>
#include <exception>
#include <memory>
#include <mutex>
#include <type_traits>

#include "reach_trajopt/common/error.h"
#include "reach_trajopt/common/stopwatch.h"
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
constexpr int kClaimsPerThread = 8;  // a step's items are claimed in about this many parts
                                     // per thread (dynamic balance)

class DirectionRun;

/// What the directions run together share: the progress callback, the first exception any
/// of them threw, the mutex guarding both (the callback is never called concurrently), a
/// stop flag raised by that exception (or a cancel), and the directions workers claim from.
struct SharedRun {
  explicit SharedRun(const ReachProgressCallback& cb) : progress(cb) {}
  const ReachProgressCallback& progress;
  std::exception_ptr error;
  std::mutex mutex;
  std::atomic<bool> stop{false};
  std::vector<DirectionRun*> directions;  ///< what the workers take items from
};
enum Direction : std::uint64_t { kForward = 1, kBackward = 2 };

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

/// Selects the boundary (21) of a slice and stores the configurations of its samples.
void selectAndStore(const ReachContext& ctx, bool forward, const SampleSlice& prev,
                    SampleSlice& s) {
  BoundaryRule rule;
  rule.lookahead = ctx.config.boundary_lookahead;
  if (!forward)  // backward slices look back in time
    for (double& tau : rule.lookahead) tau = -tau;
  rule.angular_bins = ctx.config.angular_bins;
  rule.max_boundary = ctx.budget.max_boundary;
  rule.threads = ctx.config.threads > 0 ? ctx.config.threads : omp_get_max_threads();
  s.boundary = selectBoundary(s.output, s.output_rate, rule);
  // Interior picks: evenly spread over the samples not on the boundary.
  std::vector<char> on(s.size(), 0);
  for (int i : s.boundary) on[i] = 1;
  std::vector<int> rest;
  for (int i = 0; i < s.size(); ++i)
    if (!on[i]) rest.push_back(i);
  s.kept = s.boundary;
  const int want = std::min<int>(ctx.budget.interior_samples, static_cast<int>(rest.size()));
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

/// The children of one step, stored at fixed columns (parent k, child c at k n_children + c).
struct StepChildren {
  StepChildren(const ReachContext& ctx, long total)
      : ok(total, 0),
        qd(ctx.n, total),
        y(ctx.ny(), total),
        yr(ctx.ny(), total),
        u(ctx.nu, total),
        lam(ctx.m(), total) {}
  std::vector<char> ok;
  Eigen::MatrixXd qd, y, yr, u, lam;
};

/// One direction of the check, run by OpenMP worker tasks that never wait. A step's children
/// are work items (kChunk children of one parent); the step publishes them (a cursor), and
/// workers claim a few at a time. The worker that runs the step's last items either publishes
/// another round of them (a thin slice, ReachConfig::redraw_rounds) or gathers them
/// (compaction, boundary selection, progress) and publishes the next step, with a worker task
/// per thread. No thread ever blocks inside a task, so at the region's closing barrier every
/// thread works on both directions as they come (a task waiting for its children in libgomp
/// could only run its own). Small steps, and one thread, run inline.
/// A direction being propagated, whatever its step type.
class DirectionRun {
 public:
  virtual ~DirectionRun() = default;
  /// Starts the direction (in a parallel region's single thread, or serially).
  virtual void start() = 0;
  /// Steps not yet gathered (the length of the direction's remaining chain).
  virtual int stepsLeft() const = 0;
  /// Some item of the published step is unclaimed.
  virtual bool claimable() const = 0;
  /// Claims a few unclaimed items and runs them (and the step's end when they were its last);
  /// false when none was left to claim.
  virtual bool claimAndRun() = 0;
};

/// A worker task: runs items until none is left, staying with the direction this thread last
/// worked on while it has items, else taking the direction with the most steps left (the
/// longer chain). Alternating directions on one core cost each item 10-18 % more CPU time than
/// with one thread; keeping to one cut a quick check of the walk by about 5 % on 2 threads
/// (bench/README.md, issue 16). `last` is only compared, never followed: a stale address from an
/// earlier check merely sets a preference.
void runWorker(SharedRun& run) {
  static thread_local const DirectionRun* last = nullptr;
  while (!run.stop) {
    DirectionRun* best = nullptr;
    for (DirectionRun* d : run.directions) {
      if (!d->claimable()) continue;
      if (d == last) {
        best = d;
        break;
      }
      if (best == nullptr || d->stepsLeft() > best->stepsLeft()) best = d;
    }
    if (best == nullptr) return;
    last = best;
    best->claimAndRun();  // may find the items claimed by another worker meanwhile: look again
  }
}

/// Propagates one DirectionSet (its slices and stats).
template <class Step>
class StepRun : public DirectionRun {
 public:
  StepRun(const ReachContext& ctx, DirectionSet& set, int threads, SharedRun& run)
      : ctx_(ctx),
        forward_(set.root.direction == PropagationDirection::kForward),
        dir_(forward_ ? kForward : kBackward),
        root_(set.root),
        threads_(threads),
        slices_(set.slices),
        stats_(set.stats),
        run_(run) {
    for (int i = 0; i < threads; ++i) scratch_.push_back(std::make_unique<Scratch<Step>>(ctx));
  }

  void start() override {
    guarded([&] {
      t0_ = SteadyClock::now();
      stats_ = PropagationStats();
      slices_.clear();
      slices_.reserve(root_.steps + 1);
      slices_.push_back(rootSlice(ctx_, root_.root_index * ctx_.config.dt, root_.q, root_.qd));
      steps_left_.store(root_.steps, std::memory_order_relaxed);
      advance();
    });
  }

 private:
  /// Runs steps inline until one is handed to tasks or the direction ends.
  void advance() {
    while (true) {
      const int j = static_cast<int>(slices_.size()) - 1;
      if (j == root_.steps || run_.stop) {
        for (const auto& s : scratch_) {
          stats_.qps += s->step.qpCount();
          if constexpr (std::is_same<Step, BackwardStep>::value)
            stats_.prefiltered += s->step.prefilterRejects();
        }
        stats_.propagation_time = secondsSince(t0_) - stats_.boundary_time;
        return;
      }
      const SamplingBudget& budget = ctx_.budget;
      n_children_ =
          j == 0 ? budget.initial_samples
                 : (forward_ ? budget.children_per_parent : budget.backward_children_per_parent);
      chunks_ = (n_children_ + kChunk - 1) / kChunk;
      rounds_.clear();
      survivors_ = 0;
      if (!runRounds()) return;  // handed to worker tasks
    }
  }

  /// Draws the current step's rounds from rounds_.size() on: each one inline when it is small
  /// (or one thread), until the step is gathered (true), or hands a round to worker tasks
  /// (false: the worker that runs its last item goes on).
  bool runRounds() {
    while (true) {
      const long total = static_cast<long>(slices_.back().kept.size()) * n_children_;
      rounds_.push_back(std::make_unique<StepChildren>(ctx_, total));
      const int items = static_cast<int>(slices_.back().kept.size()) * chunks_;
      if (threads_ > 1 && total >= kParallelMin) {
        pending_.store(items, std::memory_order_relaxed);
        grain_.store(std::max(1, items / (kClaimsPerThread * threads_)), std::memory_order_relaxed);
        cursor_.store(static_cast<std::uint64_t>(items) << 32, std::memory_order_release);
        SharedRun& run = run_;
        for (int t = 0; t < threads_; ++t) {
#pragma omp task default(none) shared(run)
          runWorker(run);
        }
        return false;
      }
      runItems(0, items);
      if (!anotherRound()) {
        finishStep();
        return true;
      }
    }
  }

  /// After a round: true when the slice is still thin and rounds are left (ReachConfig::
  /// redraw_rounds, redraw_below).
  bool anotherRound() {
    for (char ok : rounds_.back()->ok) survivors_ += ok;
    const ReachConfig& config = ctx_.config;
    const double wanted =
        config.redraw_below * (ctx_.budget.max_boundary + ctx_.budget.interior_samples);
    return static_cast<int>(rounds_.size()) <= config.redraw_rounds && survivors_ < wanted;
  }

  int stepsLeft() const override { return steps_left_.load(std::memory_order_relaxed); }

  bool claimable() const override {
    const std::uint64_t c = cursor_.load(std::memory_order_relaxed);
    return (c & 0xffffffffu) < (c >> 32);
  }

  bool claimAndRun() override {
    std::uint64_t c = cursor_.load(std::memory_order_acquire);
    std::uint64_t items = 0, next = 0, end = 0;
    do {
      items = c >> 32;
      next = c & 0xffffffffu;
      if (next >= items) return false;
      end = std::min<std::uint64_t>(items, next + grain_.load(std::memory_order_relaxed));
    } while (!cursor_.compare_exchange_weak(c, (items << 32) | end, std::memory_order_acq_rel,
                                            std::memory_order_acquire));
    const int i0 = static_cast<int>(next), i1 = static_cast<int>(end);
    guarded([&] {
      runItems(i0, i1);
      if (pending_.fetch_sub(i1 - i0, std::memory_order_acq_rel) != i1 - i0) return;
      if (!anotherRound())
        finishStep();
      else if (!runRounds())
        return;  // the next round is the workers'
      advance();
    });
    return true;
  }

  /// Work items [i0, i1) of the current step (any thread).
  void runItems(int i0, int i1) {
    const SampleSlice& prev = slices_.back();
    const int step_index = static_cast<int>(slices_.size()) - 1;
    const std::uint64_t seed = ctx_.config.seed;
    const int n_vertex = vertexDraws(ctx_.config.vertex_fraction, n_children_);
    // Round r draws children r n + c (new keys; uniform: the vertices are round 0's).
    const int key0 = static_cast<int>(rounds_.size() - 1) * n_children_;
    StepChildren& ch = *rounds_.back();
    Scratch<Step>& s = *scratch_[omp_get_thread_num()];
    for (int item = i0; item < i1; ++item) {
      const int k = item / chunks_;
      const int c0 = (item % chunks_) * kChunk;
      const int c1 = std::min(c0 + kChunk, n_children_);
      const int parent = prev.kept[k];
      if (!s.step.setParent(prev.q_kept.col(k), prev.qd.col(parent))) continue;
      for (int c = c0; c < c1; ++c) {
        const long col = static_cast<long>(k) * n_children_ + c;
        bool good;
        if constexpr (std::is_same<Step, ForwardStep>::value) {
          drawBox(seed, dir_, step_index, parent, key0 + c, n_vertex, ctx_.u_max, s.u);
          good = s.step.child(s.u, s.q, ch.qd.col(col), ch.y.col(col), ch.yr.col(col),
                              ch.u.col(col), ch.lam.col(col));
        } else {
          drawBox(seed, dir_, step_index, parent, key0 + c, n_vertex, s.step.drawBound(), s.draw);
          good = s.step.child(s.draw, s.q, ch.qd.col(col), ch.y.col(col), ch.yr.col(col),
                              ch.u.col(col), ch.lam.col(col));
        }
        ch.ok[col] = good ? 1 : 0;
      }
    }
  }

  /// Gathers the step's children (every round's, in round order) into the next slice, selects
  /// its boundary, reports.
  void finishStep() {
    const SampleSlice& prev = slices_.back();
    const int j = static_cast<int>(slices_.size()) - 1;
    SampleSlice next;
    next.time = (root_.root_index + (forward_ ? 1 : -1) * (j + 1)) * ctx_.config.dt;
    const long kept = survivors_;  // anotherRound() counted every round's survivors
    long total = 0;
    for (const auto& ch : rounds_) total += static_cast<long>(ch->ok.size());
    stats_.rejected += total - kept;
    next.parent.resize(kept);
    next.qd.resize(ctx_.n, kept);
    next.output.resize(ctx_.ny(), kept);
    next.output_rate.resize(ctx_.ny(), kept);
    next.u.resize(ctx_.nu, kept);
    next.lambda.resize(ctx_.m(), kept);
    long col = 0;
    for (const auto& round : rounds_) {
      const StepChildren& ch = *round;
      for (long i = 0; i < static_cast<long>(ch.ok.size()); ++i) {
        if (!ch.ok[i]) continue;
        next.parent[col] = prev.kept[i / n_children_];
        next.qd.col(col) = ch.qd.col(i);
        next.output.col(col) = ch.y.col(i);
        next.output_rate.col(col) = ch.yr.col(i);
        next.u.col(col) = ch.u.col(i);
        next.lambda.col(col) = ch.lam.col(i);
        ++col;
      }
    }
    rounds_.clear();
    const auto tb = SteadyClock::now();
    selectAndStore(ctx_, forward_, prev, next);
    stats_.boundary_time += secondsSince(tb);
    stats_.samples += next.size();
    slices_.push_back(std::move(next));
    steps_left_.store(root_.steps - (j + 1), std::memory_order_relaxed);
    report(j + 1);
  }

  /// The progress callback after slice `done` (never two at once; none after a cancel).
  void report(int done) {
    if (!run_.progress) return;
    ReachProgress p{forward_, done, root_.steps, stats_.samples, 0};
    for (const auto& sc : scratch_) p.qps += sc->step.qpCount();
    bool cancelled = false;
    {
      std::lock_guard<std::mutex> lock(run_.mutex);
      if (!run_.stop) cancelled = !run_.progress(p);
      if (cancelled) run_.stop = true;
    }
    if (cancelled)
      throw ReachCancelled(std::string("reachability check cancelled after ") +
                           std::to_string(done) + " of " + std::to_string(root_.steps) + " " +
                           (forward_ ? "forward" : "backward") + " slices");
  }

  /// No exception may leave an OpenMP task: the first is kept for the caller and stops both
  /// directions.
  template <class F>
  void guarded(F&& f) {
    try {
      f();
    } catch (...) {
      std::lock_guard<std::mutex> lock(run_.mutex);
      if (!run_.error) run_.error = std::current_exception();
      run_.stop = true;
    }
  }

  const ReachContext& ctx_;
  const bool forward_;
  const Direction dir_;
  const PropagationRoot& root_;
  const int threads_;
  std::vector<SampleSlice>& slices_;
  PropagationStats& stats_;
  SharedRun& run_;
  std::vector<std::unique_ptr<Scratch<Step>>> scratch_;
  SteadyClock::time_point t0_;
  int n_children_ = 0, chunks_ = 1;
  std::vector<std::unique_ptr<StepChildren>> rounds_;  ///< the current step's rounds of draws
  long survivors_ = 0;                                 ///< their children kept so far
  std::atomic<int> pending_{0};
  std::atomic<int> grain_{1};
  std::atomic<std::uint64_t> cursor_{0};
  std::atomic<int> steps_left_{0};
};

std::unique_ptr<DirectionRun> makeRun(const ReachContext& ctx, DirectionSet& set, int threads,
                                      SharedRun& run) {
  if (set.root.direction == PropagationDirection::kForward)
    return std::make_unique<StepRun<ForwardStep>>(ctx, set, threads, run);
  return std::make_unique<StepRun<BackwardStep>>(ctx, set, threads, run);
}

}  // namespace

void propagateSets(const ReachContext& ctx, const std::vector<DirectionSet*>& sets, int threads,
                   const ReachProgressCallback& progress) {
  // Every direction starts in the single thread; the region's closing barrier runs every
  // task to the end.
  SharedRun run(progress);
  std::vector<std::unique_ptr<DirectionRun>> runs;
  for (DirectionSet* set : sets) runs.push_back(makeRun(ctx, *set, threads, run));
  for (const auto& r : runs) run.directions.push_back(r.get());
#pragma omp parallel num_threads(threads)
#pragma omp single nowait
  for (const auto& r : runs) r->start();
  if (run.error) std::rethrow_exception(run.error);
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
