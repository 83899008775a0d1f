#pragma once
/// \file witness_certificate.h
/// The certificate behind a "reachable" verdict (docs/method.md Sec. 4.5): a path x_0 -> x_f
/// whose every 1 ms step passes the full-model re-check (measurePath: eq. (1) with the
/// recorded torques and wrenches, torques within limits, the held contacts (5), the cones (8),
/// joint position and velocity limits, the swing sole above the ground).
///
///  1. Junction candidates: on every slice t of the overlap window [t_2, t_1], the forward /
///     backward pairs (a, b) ranked by the effort of a bridge over the remaining time
///     T = t_f - t:  |6 (q_a - q_b) / T^2|^2 + |4 (qd_a - qd_b) / T|^2 (the peak acceleration
///     of the cubic Hermite that closes the gap), over every sample of both slices (not only
///     the swing sole's output, which matches long before the state does);
///  2. for the best `certificate_candidates` pairs in that order: x_0 -> a traced through the
///     forward set, then the bridge a -> x(t_f) of junction_bridge.h along the backward chain
///     b -> x_f, and if that one is not certified, along the cubic from a to x_f
///     (hermiteChain);
///  3. certified when the path's largest violation is within certificate_tolerance (contact
///     within contact_tolerance / certificate_contact_velocity_tolerance) and x(t_f) within
///     terminal_position_tolerance / terminal_velocity_tolerance of x_f. The first certified
///     path is the witness; without one, the attempt that ended closest to x_f, uncertified.
///
/// Deterministic: the candidates and their order depend only on the sets.

#include <vector>

#include "reach_trajopt/reach/reach_context.h"
#include "reach_trajopt/reach/sample_slice.h"
#include "reach_trajopt/reach/window_comparison.h"
#include "reach_trajopt/reach/witness_path.h"

namespace reach_trajopt {

/// One forward / backward pair to bridge.
struct JunctionCandidate {
  int window_index = 0;  ///< into the window comparison
  int forward_sample = 0, backward_sample = 0;
  double effort = 0.0;  ///< the bridge effort of the file comment [(rad/s^2)^2]
};

/// The best `count` pairs over the window, lowest effort first (ties: earlier slice, lower
/// indices).
std::vector<JunctionCandidate> junctionCandidates(const ReachContext& ctx,
                                                  const std::vector<SampleSlice>& forward,
                                                  const std::vector<SampleSlice>& backward,
                                                  const std::vector<SliceComparison>& window,
                                                  int count);

/// Steps 1-3: the certified witness, or the closest uncertified attempt (valid = false when
/// no slice of the window has samples in both sets).
/// \param semi_implicit  the forward integrator of the forward set
WitnessPath certifyWitness(const ReachContext& ctx, const std::vector<SampleSlice>& forward,
                           const std::vector<SampleSlice>& backward,
                           const std::vector<SliceComparison>& window, bool semi_implicit);

/// True when a measured bridged path passes the certificate's tolerances (step 3).
bool withinCertificate(const ReachConfig& config, const WitnessPath& w);

/// How far a path ends from x_f in units of the certificate's terminal tolerances:
/// max(|q(t_f) - q_f|_inf / terminal_position_tolerance, |qd(t_f) - qd_f|_inf /
/// terminal_velocity_tolerance) (<= 1: x(t_f) within them; infinite for a bridge that stopped
/// early; NaN without an attempt, w.valid false).
double terminalGapInTolerances(const ReachConfig& config, const WitnessPath& w);

}  // namespace reach_trajopt
