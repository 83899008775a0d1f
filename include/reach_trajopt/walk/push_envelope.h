#pragma once
/// \file push_envelope.h
/// The push-recovery envelope of a walking policy: walks of `steps` footsteps from a push in
/// `directions` directions (the first along +x, the forward direction, counter-clockwise; +y is
/// the left) x `magnitudes` [m/s] x `seeds`, one walk per cell, and which survived (no fall).
/// Two protocols: `standing`, the push an initial CoM velocity with the feet still
/// (WalkConfig::initial_com_velocity); `midswing`, a change of the base's velocity at half
/// swing of the 4th step while walking (WalkConfig::midswing_push), in place or forward. The
/// standing robot (no step, 3 s) under the same pushes is the reference a stepping policy
/// must not do worse than. The envelope radius of a direction is the largest magnitude m such
/// that every magnitude <= m of the grid survived with every seed.

#include <Eigen/Core>
#include <functional>
#include <string>
#include <vector>

#include "reach_trajopt/planner/capture_limits.h"
#include "reach_trajopt/walk/walk_setup.h"

namespace reach_trajopt {

/// The grid of pushes.
struct PushGrid {
  int directions = 8;                                ///< evenly spaced, the first along +x
  std::vector<double> magnitudes = {0.2, 0.4, 0.6};  ///< [m/s], increasing, > 0
  std::vector<unsigned> seeds = {1, 2};              ///< WalkConfig::seed of each walk
  int steps = 20;                                    ///< footsteps per walk
  enum class Protocol { kStanding, kMidswing };
  Protocol protocol = Protocol::kStanding;  ///< how the push is given (see the file comment)
  double forward_speed = 0.0;               ///< WalkConfig::forward_speed of every walk [m/s]
  /// The standing reference: every walk stands (no step) for 3 s instead of walking; the
  /// policy then only names it.
  bool standing = false;
  const char* protocolName() const;  ///< "standing", "midswing"
  /// \throws RequestError naming the bad field.
  void validate() const;
  double angle(int direction) const;                         ///< [rad] from +x
  Eigen::Vector2d push(int direction, int magnitude) const;  ///< [m/s]
};

/// One walk of the sweep.
struct PushWalk {
  int direction = 0, magnitude = 0, seed = 0;      ///< grid indices
  Eigen::Vector2d push = Eigen::Vector2d::Zero();  ///< [m/s]
  bool fell = false;
  int steps = 0;           ///< touchdowns
  std::string end_reason;  ///< WalkResult::end_reason
  double wall_s = 0.0;
  bool repeated = false;  ///< a policy without random draws: the first seed's walk, reused
};

/// The envelope of one policy.
struct PushEnvelope {
  WalkingPolicy policy;
  PushGrid grid;
  std::vector<PushWalk> walks;  ///< direction-major, then magnitude, then seed
  /// The LIPM capture limits of each direction (planner/capture_limits.h), from the walk's
  /// configs: what any stepping strategy could recover, beside what this policy did.
  std::vector<CaptureLimits> capture;
  /// When the walks' plans took effect (WalkConfig::planLatencyName(); "pause": the reference).
  std::string plan_latency = "pause";
  int pushes() const { return static_cast<int>(walks.size()); }
  int survived() const;
  /// The envelope radius of a direction [m/s] (0 when its smallest push fell).
  double radius(int direction) const;
  /// Largest radius over the lateral directions (+y, -y) and along +x [m/s]; -1 when the grid
  /// has no such direction (directions not a multiple of 4).
  double maxLateral() const;
  double maxForward() const;
  /// `BENCH walk.envelope preset=<p or standing> protocol=<standing|midswing> pushes=N survived=K
  /// max_lateral_mps=.. max_forward_mps=.. radii_mps=r0/r1/... capture0_mps=.. capture1_mps=..
  /// captureN_mps=.. fraction_of_capture1=r0/c0/... walks_wall_s=..` plus the policy's definition
  /// (the capture limits per direction, as the radii).
  std::string benchLine() const;
};

/// Runs the grid for one policy on `jobs` threads (each walk on one, its check single-threaded:
/// seeded sampling is thread-count independent). A policy without the reachability check draws
/// nothing, so each push runs once and its walk counts for every seed (marked `repeated`).
/// `on_walk` (optional) is called after each walk, from the worker thread, serialized.
PushEnvelope sweepPushes(const WalkSetup& setup, const std::string& urdf_path,
                         const WalkingPolicy& policy, const PushGrid& grid, int jobs,
                         const std::function<void(const PushWalk&)>& on_walk = {});

/// An SVG figure: one polar panel per envelope (rings = magnitudes, spokes = directions), each
/// push a dot (green: survived every seed, amber: some, red: none) and the envelope's polygon.
std::string envelopeSvg(const std::vector<PushEnvelope>& envelopes);

}  // namespace reach_trajopt
