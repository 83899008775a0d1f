/// \file reach_config.cpp
/// Validation and YAML reading of ReachConfig.

#include "reach_trajopt/reach/reach_config.h"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "reach_trajopt/common/cli_args.h"
#include "reach_trajopt/common/config_yaml.h"
#include "reach_trajopt/common/error.h"

namespace reach_trajopt {
namespace {

[[noreturn]] void bad(const std::string& field, const std::string& why) {
  throw ReachError("ReachConfig: " + field + " " + why);
}

void requirePositive(const char* field, double v) {
  if (!std::isfinite(v) || v <= 0.0) {
    std::ostringstream os;
    os << "must be positive and finite, got " << v;
    bad(field, os.str());
  }
}

void requireNonNegative(const char* field, double v) {
  if (!std::isfinite(v) || v < 0.0) {
    std::ostringstream os;
    os << "must be >= 0 and finite, got " << v;
    bad(field, os.str());
  }
}

void requireAtMost(const char* field, long long v, long long limit) {
  if (v > limit)
    bad(field,
        "must be <= " + std::to_string(limit) + " (docs/limits.md), got " + std::to_string(v));
}

/// True when t is an integer multiple of dt (to 1e-9 of a step).
bool onGrid(double t, double dt) { return std::abs(t / dt - std::round(t / dt)) < 1e-6; }

}  // namespace

void ReachConfig::validate() const {
  requirePositive("dt", dt);
  requirePositive("horizon", horizon);
  requireNonNegative("window_start", window_start);
  requireNonNegative("window_end", window_end);
  if (window_start > window_end + 1e-12 || window_end > horizon + 1e-12) {
    std::ostringstream os;
    os << "needs 0 <= window_start <= window_end <= horizon (the overlap window [t_2, t_1] "
          "must lie in [t_0, t_f]), got window_start "
       << window_start << ", window_end " << window_end << ", horizon " << horizon;
    bad("window", os.str() + ": empty window");
  }
  if (!onGrid(horizon, dt) || !onGrid(window_start, dt) || !onGrid(window_end, dt))
    bad("horizon/window_start/window_end", "must be multiples of dt");
  if (horizon < dt * (1.0 - 1e-9))
    bad("horizon", "must be at least one time step dt = " + std::to_string(dt) + " s, got " +
                       std::to_string(horizon));
  using L = ReachLimits;
  if (horizon / dt > L::kMaxSteps + 0.5)
    bad("horizon", "/ dt = " + std::to_string(horizon / dt) + " steps is over the limit of " +
                       std::to_string(L::kMaxSteps));
  if (initial_samples < 1) bad("initial_samples", "must be >= 1 (zero samples)");
  if (children_per_parent < 1) bad("children_per_parent", "must be >= 1 (zero samples)");
  if (max_boundary < 1) bad("max_boundary", "must be >= 1");
  if (angular_bins < 0) bad("angular_bins", "must be >= 0");
  if (interior_samples < 0) bad("interior_samples", "must be >= 0");
  if (backward_children_per_parent < 1)
    bad("backward_children_per_parent", "must be >= 1 (zero samples)");
  requireAtMost("initial_samples", initial_samples, L::kMaxInitialSamples);
  requireAtMost("children_per_parent", children_per_parent, L::kMaxChildrenPerParent);
  requireAtMost("backward_children_per_parent", backward_children_per_parent,
                L::kMaxChildrenPerParent);
  requireAtMost("max_boundary", max_boundary, L::kMaxBoundary);
  requireAtMost("interior_samples", interior_samples, L::kMaxBoundary);
  requireAtMost("angular_bins", angular_bins, L::kMaxAngularBins);
  if (boundary_lookahead.empty()) bad("boundary_lookahead", "must hold at least one value");
  requireAtMost("boundary_lookahead (entries)", static_cast<long long>(boundary_lookahead.size()),
                L::kMaxLookahead);
  for (double tau : boundary_lookahead) requireNonNegative("boundary_lookahead", tau);
  if (!(vertex_fraction >= 0.0 && vertex_fraction <= 1.0))
    bad("vertex_fraction", "must be in [0, 1]");
  if (threads < 0) bad("threads", "must be >= 0");
  // Each thread owns a workspace; more threads than the machine has cannot run faster.
  if (threads > hardwareThreads())
    bad("threads", "must be <= the " + std::to_string(hardwareThreads()) +
                       " hardware threads of this machine (0: OpenMP's default), got " +
                       std::to_string(threads));
  if (forward_integrator != "semi_implicit" && forward_integrator != "explicit")
    bad("forward_integrator",
        "must be 'semi_implicit' or 'explicit', got '" + forward_integrator + "'");
  requirePositive("w_qdd", w_qdd);
  requirePositive("w_du", w_du);
  requirePositive("w_lambda", w_lambda);
  if (!(contact_stabilization >= 0.0 && contact_stabilization <= 1.0))
    bad("contact_stabilization", "must be in [0, 1]");
  requirePositive("backward_joint_accel", backward_joint_accel);
  requirePositive("backward_base_accel", backward_base_accel);
  requireNonNegative("delta", delta);
  requireNonNegative("overlap_gap_max", overlap_gap_max);
  if (certificate_candidates < 1) bad("certificate_candidates", "must be >= 1");
  requireAtMost("certificate_candidates", certificate_candidates, L::kMaxCertificateCandidates);
  requirePositive("certificate_tolerance", certificate_tolerance);
  requirePositive("certificate_contact_velocity_tolerance", certificate_contact_velocity_tolerance);
  requirePositive("terminal_position_tolerance", terminal_position_tolerance);
  requirePositive("terminal_velocity_tolerance", terminal_velocity_tolerance);
  requireNonNegative("constraint_margin", constraint_margin);
  if (output_axes.empty() || output_axes.size() > 3) bad("output_axes", "must hold 1-3 axes");
  for (std::size_t i = 0; i < output_axes.size(); ++i) {
    const char c = output_axes[i];
    if (c != 'x' && c != 'y' && c != 'z') bad("output_axes", "may only hold x, y, z");
    if (output_axes.find(c) != i) bad("output_axes", "repeats an axis");
  }
  if (std::isnan(swing_ground_margin) || swing_ground_margin == HUGE_VAL)
    bad("swing_ground_margin", "must be a number (-inf disables)");
  requirePositive("contact_tolerance", contact_tolerance);
  requirePositive("contact_velocity_tolerance", contact_velocity_tolerance);
  requireNonNegative("limit_tolerance", limit_tolerance);
}

double ReachConfig::estimatedQps() const {
  const double steps = std::ceil(window_end / dt) + std::ceil((horizon - window_start) / dt);
  const double parents = static_cast<double>(max_boundary) + interior_samples;
  const double per_slice = parents * std::max(children_per_parent, backward_children_per_parent);
  return 2.0 * initial_samples + steps * per_slice;
}

double ReachConfig::estimatedMemoryBytes(int nq) const {
  // output + rate (3 each), qd, u, lambda (12), kept q: doubles; parent index; QP scratch.
  const double per_sample = 8.0 * (6 + 3.0 * nq + 12) + 16;
  return per_sample * estimatedQps();
}

void ReachConfig::requireResourcesWithinLimits(int nq) const {
  const double qps = estimatedQps();
  if (qps > ReachLimits::kMaxQps) {
    std::ostringstream os;
    os << "ReachConfig: the check would solve about " << qps << " QPs (initial_samples "
       << initial_samples << ", max_boundary " << max_boundary << ", interior_samples "
       << interior_samples << ", horizon " << horizon << " s at dt " << dt
       << " s), over the limit of " << ReachLimits::kMaxQps << " (minutes of wall time)";
    throw ReachError(os.str());
  }
  const double bytes = estimatedMemoryBytes(nq);
  if (bytes > ReachLimits::kMaxMemoryBytes) {
    std::ostringstream os;
    os << "ReachConfig: the check would need about " << std::lround(bytes / (1024 * 1024))
       << " MiB (initial_samples " << initial_samples << ", max_boundary " << max_boundary
       << ", children_per_parent " << children_per_parent << ", horizon " << horizon << " s at dt "
       << dt << " s), over the limit of "
       << std::lround(ReachLimits::kMaxMemoryBytes / (1024 * 1024)) << " MiB";
    throw ReachError(os.str());
  }
}

ReachConfig ReachConfig::fromYaml(const YamlSection& s, const ReachConfig& base) {
  s.requireOnlyKeys({"dt",
                     "horizon",
                     "window_start",
                     "window_end",
                     "initial_samples",
                     "children_per_parent",
                     "max_boundary",
                     "angular_bins",
                     "interior_samples",
                     "backward_children_per_parent",
                     "boundary_lookahead",
                     "vertex_fraction",
                     "seed",
                     "threads",
                     "forward_integrator",
                     "w_qdd",
                     "w_du",
                     "w_lambda",
                     "contact_stabilization",
                     "backward_joint_accel",
                     "backward_base_accel",
                     "delta",
                     "overlap_gap_max",
                     "certificate_candidates",
                     "certificate_tolerance",
                     "certificate_contact_velocity_tolerance",
                     "terminal_position_tolerance",
                     "terminal_velocity_tolerance",
                     "constraint_margin",
                     "output_frame",
                     "output_axes",
                     "swing_ground_margin",
                     "contact_tolerance",
                     "contact_velocity_tolerance",
                     "limit_tolerance"});
  ReachConfig c = base;
  s.read("dt", c.dt);
  s.read("horizon", c.horizon);
  s.read("window_start", c.window_start);
  s.read("window_end", c.window_end);
  s.read("initial_samples", c.initial_samples);
  s.read("children_per_parent", c.children_per_parent);
  s.read("max_boundary", c.max_boundary);
  s.read("angular_bins", c.angular_bins);
  s.read("interior_samples", c.interior_samples);
  s.read("backward_children_per_parent", c.backward_children_per_parent);
  s.read("boundary_lookahead", c.boundary_lookahead);
  s.read("vertex_fraction", c.vertex_fraction);
  int seed = static_cast<int>(c.seed);
  if (s.read("seed", seed)) {
    if (seed < 0) throw ReachError(s.where("seed") + ": must be >= 0");
    c.seed = static_cast<std::uint64_t>(seed);
  }
  s.read("threads", c.threads);
  s.read("forward_integrator", c.forward_integrator);
  s.read("w_qdd", c.w_qdd);
  s.read("w_du", c.w_du);
  s.read("w_lambda", c.w_lambda);
  s.read("contact_stabilization", c.contact_stabilization);
  s.read("backward_joint_accel", c.backward_joint_accel);
  s.read("backward_base_accel", c.backward_base_accel);
  s.read("delta", c.delta);
  s.read("overlap_gap_max", c.overlap_gap_max);
  s.read("certificate_candidates", c.certificate_candidates);
  s.read("certificate_tolerance", c.certificate_tolerance);
  s.read("certificate_contact_velocity_tolerance", c.certificate_contact_velocity_tolerance);
  s.read("terminal_position_tolerance", c.terminal_position_tolerance);
  s.read("terminal_velocity_tolerance", c.terminal_velocity_tolerance);
  s.read("constraint_margin", c.constraint_margin);
  s.read("output_frame", c.output_frame);
  s.read("output_axes", c.output_axes);
  s.read("swing_ground_margin", c.swing_ground_margin);
  s.read("contact_tolerance", c.contact_tolerance);
  s.read("contact_velocity_tolerance", c.contact_velocity_tolerance);
  s.read("limit_tolerance", c.limit_tolerance);
  return validatedIn(s, c);
}

ReachConfig ReachConfig::fromYaml(const YamlSection& s) { return fromYaml(s, ReachConfig()); }

}  // namespace reach_trajopt
