/// Benchmark: the bundled QP (DualActiveSetQp) against eiquadprog's EiquadprogFast (C++, PyPI
/// wheel), interleaved problem by problem in one run (absolute times swing between runs on this
/// machine; the ratio is what to read). Families: the contact QP (15), the backward feasibility
/// QP (19), random dense QPs (see contact_problems.h). Per family three lines:
///   .cold    ours factorizes G and starts from no active set | eiquadprog factorizes G
///   .factor  ours reuses a HessianFactor, no warm start      | eiquadprog given J = L^{-T}
///   .warm    ours reuses the factor and warm-starts from the previous child's active set
///                                                            | eiquadprog given J (it has no
///                                                              warm start: its best mode)
/// eiquadprog 1.3.2's given-J mode starts from +J J^T g0 instead of -J J^T g0 (checked on an
/// unconstrained problem), so it is given -g there; the cross-check confirms its answers.
/// Each time is the median over problems of the fastest of `kRepeats` solves; ratio = ours/ref
/// (below 1: ours faster). Solutions are cross-checked (|x - x_ref| <= 1e-6 relative).

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <eiquadprog/eiquadprog-fast.hpp>
#include <random>
#include <string>
#include <vector>

#include "contact_problems.h"
#include "reach_trajopt/qp/dual_active_set_qp.h"

namespace {

using bench::QpData;
using Clock = std::chrono::steady_clock;
using reach_trajopt::qp::DualActiveSetQp;
using reach_trajopt::qp::HessianFactor;
using reach_trajopt::qp::QpStatus;

constexpr int kRepeats = 3;

template <typename F>
double bestOfUs(F&& f) {
  return bestOfUs([] {}, f);
}

/// Fastest of kRepeats runs of f, each after an untimed setup().
template <typename S, typename F>
double bestOfUs(S&& setup, F&& f) {
  double best = 1e300;
  for (int r = 0; r < kRepeats; ++r) {
    setup();
    const auto t0 = Clock::now();
    f();
    const double us = std::chrono::duration<double, std::micro>(Clock::now() - t0).count();
    best = std::min(best, us);
  }
  return best;
}

double median(std::vector<double> v) {
  if (v.empty()) return 0.0;
  std::nth_element(v.begin(), v.begin() + v.size() / 2, v.end());
  return v[v.size() / 2];
}

struct Series {
  std::vector<double> ours, ref;
  std::vector<double> ours_iter;
  int mismatches = 0, failures = 0;
};

struct Family {
  std::string name;
  Series cold, factor, warm;
  int n = 0, m_eq = 0, m_in = 0;
};

/// One group of problems sharing G (a parent and its children), solved in sequence.
void runGroup(const std::vector<QpData>& children, Family& fam) {
  const QpData& first = children.front();
  const int n = static_cast<int>(first.G.rows());
  const int m_eq = static_cast<int>(first.Aeq.rows());
  const int m_in = static_cast<int>(first.Ain.rows());
  fam.n = n;
  fam.m_eq = m_eq;
  fam.m_in = m_in;
  DualActiveSetQp ours(n, m_eq, m_in);
  HessianFactor factor(n);
  factor.compute(first.G);
  eiquadprog::solvers::EiquadprogFast eiq, eiq_j;
  eiq.reset(n, m_eq, m_in);
  eiq_j.reset(n, m_eq, m_in);
  eiq_j.is_inverse_provided_ = true;
  Eigen::VectorXd x_ref(n);
  std::vector<int> warm;
  warm.reserve(n);
  for (const QpData& q : children) {
    const Eigen::VectorXd ce0 = -q.beq, ci0 = -q.bin, minus_g = -q.g;
    int status_ref = 0;
    // cold
    fam.cold.ref.push_back(bestOfUs(
        [&] { status_ref = eiq.solve_quadprog(q.G, q.g, q.Aeq, ce0, q.Ain, ci0, x_ref); }));
    fam.cold.ours.push_back(bestOfUs([&] { ours.solve(q.G, q.g, q.Aeq, q.beq, q.Ain, q.bin); }));
    auto check = [&](Series& s) {
      const auto& r = ours.result();
      s.ours_iter.push_back(r.iterations);
      if (r.status != QpStatus::kOptimal || status_ref != 0) {
        ++s.failures;
        return;
      }
      const double scale = std::max(1.0, x_ref.lpNorm<Eigen::Infinity>());
      if ((r.x - x_ref).lpNorm<Eigen::Infinity>() > 1e-6 * scale) ++s.mismatches;
    };
    check(fam.cold);
    // factor given
    // eiquadprog works in m_J, so the inverse factor is copied back before each solve.
    fam.factor.ref.push_back(bestOfUs(
        [&] { eiq_j.m_J = factor.J0(); },
        [&] { status_ref = eiq_j.solve_quadprog(q.G, minus_g, q.Aeq, ce0, q.Ain, ci0, x_ref); }));
    fam.factor.ours.push_back(
        bestOfUs([&] { ours.solve(factor, q.g, q.Aeq, q.beq, q.Ain, q.bin); }));
    check(fam.factor);
    // warm start from the previous child
    fam.warm.ref.push_back(fam.factor.ref.back());
    fam.warm.ours.push_back(
        bestOfUs([&] { ours.solve(factor, q.g, q.Aeq, q.beq, q.Ain, q.bin, &warm); }));
    check(fam.warm);
    warm = ours.result().active_set;
  }
}

void print(const Family& fam) {
  const std::pair<const char*, const Series*> rows[] = {
      {"cold", &fam.cold}, {"factor", &fam.factor}, {"warm", &fam.warm}};
  for (const auto& [mode, s] : rows) {
    const double ours = median(s->ours), ref = median(s->ref), ref_cold = median(fam.cold.ref);
    std::printf(
        "BENCH qp.%s.%s ours_us=%.2f ref=eiquadprog%s ref_us=%.2f ratio=%.3f "
        "ratio_vs_eiquadprog_cold=%.3f n=%d m_eq=%d m_in=%d problems=%zu median_iterations=%.0f "
        "mismatches=%d failures=%d\n",
        fam.name.c_str(), mode, ours, std::string(mode) == "cold" ? "" : "_given_J", ref,
        ours / ref, ours / ref_cold, fam.n, fam.m_eq, fam.m_in, s->ours.size(),
        median(s->ours_iter), s->mismatches, s->failures);
  }
  std::fflush(stdout);
}

}  // namespace

int main(int argc, char** argv) {
  const double scale = argc > 1 ? std::atof(argv[1]) : 1.0;  // problem count multiplier
  const int parents = std::max(1, static_cast<int>(20 * scale));
  const int children = 25;
  std::mt19937 rng(20201);

  for (int nc : {2, 1}) {
    Family fam;
    fam.name = nc == 2 ? "contact" : "contact_single";
    for (int p = 0; p < parents; ++p) {
      const bench::ContactParent parent = bench::contactParent(rng, nc);
      std::vector<QpData> group;
      std::uniform_real_distribution<double> uni(0.0, 1.0);
      for (int c = 0; c < children; ++c) {
        Eigen::VectorXd u(bench::kNu);
        for (int i = 0; i < bench::kNu; ++i)
          u(i) = parent.u_min(i) + uni(rng) * (parent.u_max(i) - parent.u_min(i));
        group.push_back(bench::contactChild(parent, u));
      }
      runGroup(group, fam);
    }
    print(fam);
  }
  {
    Family fam;
    fam.name = "backward";
    for (int p = 0; p < parents; ++p) {
      const bench::BackwardParent parent = bench::backwardParent(rng, 2);
      std::vector<QpData> group;
      for (int c = 0; c < children; ++c)
        group.push_back(
            bench::backwardChild(parent, parent.qdd0 + 0.05 * bench::randn(rng, bench::kNv, 1)));
      runGroup(group, fam);
    }
    print(fam);
  }
  for (auto [n, m_in] :
       {std::pair{30, 60}, std::pair{30, 40}, std::pair{45, 60}, std::pair{60, 80}}) {
    Family fam;
    fam.name = "random_" + std::to_string(n) + "_18_" + std::to_string(m_in);
    for (int p = 0; p < parents; ++p) {
      const QpData base = bench::randomQp(rng, n, 18, m_in);
      std::vector<QpData> group;
      for (int c = 0; c < children / 5; ++c) {  // children: same G and rows, moved rhs
        QpData q = base;
        const Eigen::VectorXd x_f = bench::randn(rng, n, 1);
        q.beq = q.Aeq * x_f;
        q.bin = q.Ain * x_f - bench::randn(rng, m_in, 1).cwiseAbs();
        group.push_back(q);
      }
      runGroup(group, fam);
    }
    print(fam);
  }
  return 0;
}
