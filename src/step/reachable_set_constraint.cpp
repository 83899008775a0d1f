/// \file reachable_set_constraint.cpp
/// Swing sole hulls of the forward set as OCP slices (see the header).

#include "reach_trajopt/step/reachable_set_constraint.h"

#include <algorithm>
#include <cmath>

#include "reach_trajopt/reach/output_hull.h"

namespace reach_trajopt {

double junctionTime(const WitnessPath& w) {
  return w.valid && w.bridge_start >= 0 ? w.time[w.bridge_start] : HUGE_VAL;
}

namespace {

/// junctionTime() with a margin for rounding: the slice at the junction is kept.
double lastSliceTime(const WitnessPath& w) { return junctionTime(w) + 1e-12; }

}  // namespace

std::vector<ReachableSlice> slicesUpToJunction(std::vector<ReachableSlice> slices,
                                               const WitnessPath& witness) {
  const double until = lastSliceTime(witness);
  slices.erase(std::remove_if(slices.begin(), slices.end(),
                              [until](const ReachableSlice& s) { return s.time > until; }),
               slices.end());
  return slices;
}

std::vector<ReachableSlice> grownSlices(std::vector<ReachableSlice> slices, double extra) {
  for (ReachableSlice& s : slices) s.b += extra * s.A.rowwise().norm();
  return slices;
}

std::vector<ReachableSlice> reachableSetConstraint(const ReachResult& result,
                                                   const std::string& output_axes, double margin) {
  std::vector<ReachableSlice> out;
  const auto ix = output_axes.find('x'), iy = output_axes.find('y');
  if (ix == std::string::npos || iy == std::string::npos) return out;
  const double until = lastSliceTime(result.witness);
  for (const SampleSlice& s : result.forward) {
    if (s.time <= 0.0 || s.time > until || s.size() < 3) continue;
    Eigen::MatrixXd xy(2, s.size());
    xy.row(0) = s.output.row(static_cast<Eigen::Index>(ix));
    xy.row(1) = s.output.row(static_cast<Eigen::Index>(iy));
    const OutputHull hull(xy);
    if (hull.degenerate()) continue;
    ReachableSlice slice;
    slice.time = s.time;
    slice.A = hull.normals().transpose();
    slice.b = hull.offsets().array() + margin;
    out.push_back(std::move(slice));
  }
  return out;
}

}  // namespace reach_trajopt
