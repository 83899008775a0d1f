#pragma once
/// \file leg_clearance.h
/// The distance between the two legs, a state constraint h_state(x) >= margin of eq. (4) along
/// a swing (docs/method.md, "Swing-path constraints"). Each collision primitive of a leg's
/// links (collision_shape.h, the shapes the simulator collides) is bounded by capsules,
/// segments swept by a sphere, in its link's frame:
///  - sphere: its centre, its radius;
///  - cylinder (axis z): its axis, its radius (the capsule's caps overhang the flat ends by r);
///  - box, sizes L >= W >= H: n = round(W / H) (1 to 8) capsules side by side across W, each
///    along L end to end with the half diagonal of its W / n x H cross-section as radius (a
///    flat sole box gets a row of thin capsules, which overhang it by ~H / sqrt(2), not one
///    whose radius is half its width).
/// Each capsule contains its shape, so the capsules' distance is a lower bound of the shapes'
/// distance: a path whose capsules keep a margin keeps the legs' real shapes that far apart.
/// A leg is every link below the last link the two sole frames' paths to the root share (the
/// pelvis, for a biped), on the path to its sole. A robot whose legs have no primitive (meshes
/// only) has no pair, and the constraint holds trivially (empty()).

#include <Eigen/Core>
#include <limits>
#include <string>
#include <vector>

#include "reach_trajopt/common/side.h"
#include "reach_trajopt/model/robot_model.h"

namespace reach_trajopt {

/// A capsule fixed to a link: the segment a-b (link frame) swept by a sphere of `radius`.
struct LinkCapsule {
  std::string link;
  FrameId frame = -1;
  Eigen::Vector3d a = Eigen::Vector3d::Zero(), b = Eigen::Vector3d::Zero();  ///< [m]
  double radius = 0.0;                                                       ///< [m]
};

/// The capsules bounding a collision primitive (pose in its link frame), per the file comment;
/// their `frame` is left to the caller.
std::vector<LinkCapsule> boundingCapsules(const CollisionShape& shape);

/// Closest points of segments p0-p1 and q0-q1: p0 + s (p1 - p0) and q0 + t (q1 - q0), s, t in
/// [0, 1] (Ericson, Real-Time Collision Detection, 2005, Sec. 5.1.9). Returns the distance [m].
double closestPointsOfSegments(const Eigen::Vector3d& p0, const Eigen::Vector3d& p1,
                               const Eigen::Vector3d& q0, const Eigen::Vector3d& q1,
                               Eigen::Vector3d& on_p, Eigen::Vector3d& on_q);

/// @brief Signed distance between the left and right legs' capsules, and its gradient in q.
class LegClearance {
 public:
  /// The closest pair of one configuration (after RobotModel::update).
  struct Closest {
    double distance = std::numeric_limits<double>::infinity();  ///< [m], < 0: capsules overlap
    int left = -1, right = -1;  ///< capsule indices in capsules(kLeft / kRight)
    Eigen::Vector3d left_point = Eigen::Vector3d::Zero();   ///< on the left axis, world [m]
    Eigen::Vector3d right_point = Eigen::Vector3d::Zero();  ///< on the right axis, world [m]
  };

  LegClearance() = default;  ///< no capsules: every configuration is clear
  /// \throws ReachError naming the frame when a sole frame is unknown, or when both soles are
  ///     on one chain (no two legs).
  LegClearance(const RobotModel& model, const std::string& left_sole_frame,
               const std::string& right_sole_frame);

  bool empty() const { return left_.empty() || right_.empty(); }
  const std::vector<LinkCapsule>& capsules(Side side) const {
    return side == Side::kLeft ? left_ : right_;
  }

  /// The closest left/right capsule pair at the model's last update() in `ws`. No allocation
  /// after a thread's first call.
  Closest closest(const RobotModel& model, const Workspace& ws) const;
  /// Every left/right capsule pair closer than `max_distance` [m] at the model's last update(),
  /// with its closest points (each pair once; at most pairCount()). `pairs` keeps its capacity.
  void pairsWithin(const RobotModel& model, const Workspace& ws, double max_distance,
                   std::vector<Closest>& pairs) const;
  int pairCount() const { return static_cast<int>(left_.size() * right_.size()); }
  /// closest().distance >= margin [m] at the model's last update(), decided link pair by link
  /// pair (see the file comment) and stopped at the first capsule pair closer than `margin`.
  /// No allocation after a thread's first call.
  bool separatedBy(const RobotModel& model, const Workspace& ws, double margin) const;
  /// The legs' distance at configuration q (its own forward kinematics): closest().distance;
  /// +inf when empty().
  double distanceAt(const RobotModel& model, const Eigen::Ref<const Eigen::VectorXd>& q) const;
  /// d(distance)/dq of the pair `c` (1 x n_q): n^T (J_left(p_l) - J_right(p_r)), n the unit
  /// vector from the right point to the left one (the closest points move along the surfaces,
  /// which does not change the distance to first order). Zero when the axes intersect.
  void gradient(const RobotModel& model, const Workspace& ws, const Closest& c,
                Eigen::Ref<Eigen::RowVectorXd> grad) const;
  /// The drift of the pair's distance acceleration [m/s^2] at the model's last update() with
  /// velocity qd, the normal n held fixed: gradient() qdd + accelerationDrift() is
  /// n^T (a_l - a_r), the closest points' (fixed on their links) relative acceleration along
  /// n, a_p = J_p qdd + Jdot_p qd. It leaves out n's turning, |(I - n n^T) v_rel|^2 / |p_l - p_r|
  /// >= 0, which the points sliding along the axes cancel: for legs that translate past one
  /// another the distance, a convex function of the translation, accelerates at least this
  /// much (a barrier on it is conservative). Zero when the axes intersect.
  double accelerationDrift(const RobotModel& model, const Workspace& ws, const Closest& c) const;
  /// gradient() and accelerationDrift() of several pairs at once (row k of `gradients`,
  /// pairs.size() x n_q, and drifts[k] are pairs[k]'s), each capsule frame's Jacobian and
  /// velocity terms computed once: a controller tick's barrier rows. No allocation after a
  /// thread's first calls.
  void pairTerms(const RobotModel& model, const Workspace& ws, const std::vector<Closest>& pairs,
                 Eigen::Ref<Eigen::MatrixXd> gradients, Eigen::Ref<Eigen::VectorXd> drifts) const;

 private:
  /// Calls visit(const Closest&) for every left/right capsule pair.
  template <typename Visit>
  void forEachPair(const RobotModel& model, const Workspace& ws, Visit&& visit) const;

  /// A run of one link's consecutive capsules in left_ / right_ (a link's shapes come one
  /// after the other) and a capsule enclosing them all, in the link's frame.
  struct LinkGroup {
    FrameId frame = -1;
    int first = 0, count = 0;  ///< its capsules: [first, first + count)
    Eigen::Vector3d a = Eigen::Vector3d::Zero(), b = Eigen::Vector3d::Zero();  ///< [m]
    double radius = 0.0;                                                       ///< [m]
  };
  static std::vector<LinkGroup> groupByLink(const std::vector<LinkCapsule>& capsules);

  std::vector<LinkCapsule> left_, right_;
  std::vector<LinkGroup> left_links_, right_links_;
};

}  // namespace reach_trajopt
