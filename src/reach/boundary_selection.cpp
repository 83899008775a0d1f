/// \file boundary_selection.cpp
/// Boundary samples (21): convex hulls and angular bins per output plane.

#include "reach_trajopt/reach/boundary_selection.h"

#include <omp.h>

#include <algorithm>
#include <cmath>
#include <numeric>

#include "reach_trajopt/common/error.h"

namespace reach_trajopt {

namespace {

/// Below this many samples the planes are done serially (a parallel region costs more). 96, not
/// 256: the quick budget's slices (128 forward children) then share their nine hulls too; its
/// bench case on 2 threads took about 4 % less in paired runs, with a steadier 1 -> 2 thread
/// speed-up (1.85-1.90 against 1.59-1.87 over three runs each; bench/README.md, issue 16).
constexpr int kParallelBoundaryMin = 96;

double cross(const Eigen::Vector2d& o, const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
  return (a - o).x() * (b - o).y() - (a - o).y() * (b - o).x();
}

/// Farthest point from the centroid in each of `bins` sectors (ties: lowest index).
std::vector<int> angularBins(const Eigen::Matrix2Xd& p, int bins) {
  std::vector<int> best(bins, -1);
  std::vector<double> dist(bins, -1.0);
  const Eigen::Vector2d c = p.rowwise().mean();
  for (int i = 0; i < p.cols(); ++i) {
    const Eigen::Vector2d d = p.col(i) - c;
    const double r = d.norm();
    if (r == 0.0) continue;
    int k = static_cast<int>(std::floor((std::atan2(d.y(), d.x()) + M_PI) / (2.0 * M_PI) * bins));
    k = std::min(std::max(k, 0), bins - 1);
    if (r > dist[k]) {
      dist[k] = r;
      best[k] = i;
    }
  }
  std::vector<int> out;
  for (int i : best)
    if (i >= 0) out.push_back(i);
  return out;
}

}  // namespace

std::vector<int> convexHull2d(const Eigen::Ref<const Eigen::Matrix2Xd>& points) {
  const int n = static_cast<int>(points.cols());
  std::vector<int> idx(n);
  std::iota(idx.begin(), idx.end(), 0);
  std::sort(idx.begin(), idx.end(), [&](int a, int b) {
    if (points(0, a) != points(0, b)) return points(0, a) < points(0, b);
    if (points(1, a) != points(1, b)) return points(1, a) < points(1, b);
    return a < b;
  });
  // Drop coincident points (keep the lowest index, which sorts first).
  idx.erase(std::unique(idx.begin(), idx.end(),
                        [&](int a, int b) { return points.col(a) == points.col(b); }),
            idx.end());
  if (idx.size() < 3) return idx;
  std::vector<int> hull(2 * idx.size());
  int k = 0;
  for (int i : idx) {  // lower hull
    while (k >= 2 && cross(points.col(hull[k - 2]), points.col(hull[k - 1]), points.col(i)) <= 0)
      --k;
    hull[k++] = i;
  }
  for (int j = static_cast<int>(idx.size()) - 2, t = k + 1; j >= 0; --j) {  // upper hull
    const int i = idx[j];
    while (k >= t && cross(points.col(hull[k - 2]), points.col(hull[k - 1]), points.col(i)) <= 0)
      --k;
    hull[k++] = i;
  }
  hull.resize(k - 1);
  return hull;
}

namespace {

/// One output: for each tau, the extremes of y + tau y_rate and `angular_bins` samples spread
/// evenly over its sorted order.
std::vector<std::vector<int>> candidateLists1d(const Eigen::Ref<const Eigen::MatrixXd>& y,
                                               const Eigen::Ref<const Eigen::MatrixXd>& y_rate,
                                               const BoundaryRule& rule) {
  const int n = static_cast<int>(y.cols());
  std::vector<std::vector<int>> lists;
  Eigen::MatrixXd yh(1, n);
  for (double tau : rule.lookahead) {
    yh = y + tau * y_rate;
    std::vector<int> order(n);
    std::iota(order.begin(), order.end(), 0);
    std::stable_sort(order.begin(), order.end(), [&](int a, int b) { return yh(0, a) < yh(0, b); });
    std::vector<int> picks = {order.front(), order.back()};
    const int extra = std::max(rule.angular_bins, 0);
    for (int k = 1; k <= extra; ++k) picks.push_back(order[(k * (n - 1)) / (extra + 1)]);
    lists.push_back(picks);
  }
  return lists;
}

/// Two or three outputs: one task per (tau, plane), its hull and its angular bins. The tasks
/// are independent and their lists land at fixed places, so the merge sees the serial order.
std::vector<std::vector<int>> candidateListsPlanes(const Eigen::Ref<const Eigen::MatrixXd>& y,
                                                   const Eigen::Ref<const Eigen::MatrixXd>& y_rate,
                                                   const BoundaryRule& rule) {
  const int ny = static_cast<int>(y.rows());
  const int n = static_cast<int>(y.cols());
  const int planes[3][2] = {{0, 1}, {0, 2}, {1, 2}};
  const int n_planes = ny == 2 ? 1 : 3;
  const int tasks = static_cast<int>(rule.lookahead.size()) * n_planes;
  std::vector<std::vector<int>> hulls(tasks), bins(tasks);
  const auto plane_task = [&](int t) {
    const double tau = rule.lookahead[t / n_planes];
    const int pl = t % n_planes;
    Eigen::Matrix2Xd p(2, n);
    p.row(0) = y.row(planes[pl][0]) + tau * y_rate.row(planes[pl][0]);
    p.row(1) = y.row(planes[pl][1]) + tau * y_rate.row(planes[pl][1]);
    hulls[t] = convexHull2d(p);
    if (rule.angular_bins > 0) bins[t] = angularBins(p, rule.angular_bins);
  };
  const bool parallel = tasks > 1 && rule.threads > 1 && n >= kParallelBoundaryMin;
  if (!parallel) {
    for (int t = 0; t < tasks; ++t) plane_task(t);
  } else if (omp_in_parallel()) {
    // Called from a task of the check's parallel region (set_propagation.cpp), where a
    // nested parallel region would get one thread: tasks let the team's other threads
    // take planes. The implicit taskgroup waits for this loop's tasks only.
#pragma omp taskloop grainsize(1) default(shared)
    for (int t = 0; t < tasks; ++t) plane_task(t);
  } else {
#pragma omp parallel for schedule(dynamic, 1) num_threads(rule.threads)
    for (int t = 0; t < tasks; ++t) plane_task(t);
  }
  std::vector<std::vector<int>> lists;
  for (int t = 0; t < tasks; ++t) {
    lists.push_back(std::move(hulls[t]));
    if (rule.angular_bins > 0) lists.push_back(std::move(bins[t]));
  }
  return lists;
}

/// Round-robin merge of the candidate lists up to `cap` distinct samples of `n`, sorted.
std::vector<int> mergeRoundRobin(const std::vector<std::vector<int>>& lists, int n, int cap) {
  std::vector<char> taken(n, 0);
  std::vector<int> out;
  for (std::size_t pos = 0; static_cast<int>(out.size()) < cap; ++pos) {
    bool any = false;
    for (const auto& l : lists) {
      if (pos >= l.size()) continue;
      any = true;
      const int i = l[pos];
      if (!taken[i] && static_cast<int>(out.size()) < cap) {
        taken[i] = 1;
        out.push_back(i);
      }
    }
    if (!any) break;
  }
  std::sort(out.begin(), out.end());
  return out;
}

}  // namespace

std::vector<int> selectBoundary(const Eigen::Ref<const Eigen::MatrixXd>& y,
                                const Eigen::Ref<const Eigen::MatrixXd>& y_rate,
                                const BoundaryRule& rule) {
  const int ny = static_cast<int>(y.rows());
  const int n = static_cast<int>(y.cols());
  if (ny < 1 || ny > 3) throw ReachError("selectBoundary: outputs must have 1-3 rows");
  requireSize("selectBoundary: y_rate rows", y_rate.rows(), ny);
  requireSize("selectBoundary: y_rate cols", y_rate.cols(), n);
  if (rule.max_boundary < 1) throw ReachError("selectBoundary: max_boundary must be >= 1");
  if (n == 0) return {};
  if (n <= rule.max_boundary) {
    std::vector<int> all(n);
    std::iota(all.begin(), all.end(), 0);
    return all;
  }
  const std::vector<std::vector<int>> lists =
      ny == 1 ? candidateLists1d(y, y_rate, rule) : candidateListsPlanes(y, y_rate, rule);
  return mergeRoundRobin(lists, n, rule.max_boundary);
}

}  // namespace reach_trajopt
