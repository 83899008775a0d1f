/// \file robot_model_loader.cpp
/// URDF -> urdfdom -> KDL tree (kdl_parser) -> the flattened ModelTree of RobotModel.

#include <urdf_parser/urdf_parser.h>

#include <cmath>
#include <kdl/tree.hpp>
#include <kdl_parser/kdl_parser.hpp>
#include <limits>
#include <map>
#include <optional>

#include "reach_trajopt/common/text_file.h"
#include "reach_trajopt/model/collision_shape.h"
#include "reach_trajopt/model/model_tree.h"
#include "reach_trajopt/model/robot_model.h"
#include "reach_trajopt/model/spatial_algebra.h"
#include "reach_trajopt/model/urdf_validation.h"

namespace reach_trajopt {
namespace {

constexpr double kNoLimit = std::numeric_limits<double>::infinity();

Eigen::Isometry3d toEigen(const KDL::Frame& f) {
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  for (int r = 0; r < 3; ++r) {
    for (int c = 0; c < 3; ++c) T.linear()(r, c) = f.M(r, c);
    T.translation()(r) = f.p(r);
  }
  return T;
}

Eigen::Isometry3d toEigen(const urdf::Pose& p) {
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T.linear() = Eigen::Quaterniond(p.rotation.w, p.rotation.x, p.rotation.y, p.rotation.z)
                   .normalized()
                   .toRotationMatrix();
  T.translation() << p.position.x, p.position.y, p.position.z;
  return T;
}

/// Adds a rigid inertia (mass m, com c and inertia about the origin I0, all in a frame F)
/// placed at `F_in_body` to a body's inertia. A massless inertia with a rotational part (URDFs
/// have them, e.g. feet with mass 0) still adds its rotational inertia, as Pinocchio does.
void addInertia(Body& body, const Eigen::Isometry3d& F_in_body, double m, const Eigen::Vector3d& c,
                const Eigen::Matrix3d& I0) {
  const Eigen::Matrix3d R = F_in_body.linear();
  const Eigen::Vector3d c_body = F_in_body * c;
  const Eigen::Vector3d Rc = R * c;
  // Inertia about the frame origin rotated into the body, then shifted to the body origin.
  const Eigen::Matrix3d I_com = R * I0 * R.transpose() + m * skew(Rc) * skew(Rc);
  const Eigen::Matrix3d I_body = I_com - m * skew(c_body) * skew(c_body);
  const double total = body.mass + m;
  if (total > 0.0) body.com = (body.mass * body.com + m * c_body) / total;
  body.inertia_origin += I_body;
  body.mass = total;
}

/// Inertia of a URDF link in its own frame: mass, com and rotational inertia about the origin.
void linkInertia(const urdf::InertialSharedPtr& inertial, double& m, Eigen::Vector3d& c,
                 Eigen::Matrix3d& I0) {
  m = 0.0;
  c.setZero();
  I0.setZero();
  if (!inertial) return;
  const urdf::Inertial& in = *inertial;
  m = in.mass;
  const Eigen::Isometry3d T = toEigen(in.origin);
  Eigen::Matrix3d Ic;
  Ic << in.ixx, in.ixy, in.ixz, in.ixy, in.iyy, in.iyz, in.ixz, in.iyz, in.izz;
  c = T.translation();
  I0 = T.linear() * Ic * T.linear().transpose() - m * skew(c) * skew(c);
}

}  // namespace

/// Builds a RobotModel from a URDF and its KDL tree; friend of RobotModel so it can fill the
/// private members. One builder per model.
class ModelBuilder {
 public:
  static std::shared_ptr<const RobotModel> build(urdf::ModelInterface& urdf,
                                                 const ModelOptions& options,
                                                 const std::string& source);

 private:
  ModelBuilder(const urdf::ModelInterface& urdf, const std::string& source);
  int newBody(int parent, const Eigen::Isometry3d& placement, const Eigen::Vector3d& axis,
              bool prismatic);
  /// The six virtual joints x, y, z, yaw, pitch, roll; returns the last body (the root link's).
  int addFloatingBase(const urdf::InertialSharedPtr& root_inertial);
  /// Depth-first over the KDL tree below `element`, in kdl_parser's order (the URDF's child
  /// order); `body` carries the element's link at `in_body`.
  void visit(const KDL::SegmentMap::const_iterator& element, int body,
             const Eigen::Isometry3d& in_body);
  JointInfo jointInfo(const urdf::Joint& joint) const;
  /// The link's collision primitives (collision_shape.h) into the model.
  void addCollisionShapes(const urdf::Link& link);
  void finish();

  const urdf::ModelInterface& urdf_;
  const std::string& source_;
  std::shared_ptr<RobotModel> model_;
  ModelTree* tree_ = nullptr;
};

ModelBuilder::ModelBuilder(const urdf::ModelInterface& urdf, const std::string& source)
    : urdf_(urdf), source_(source), model_(new RobotModel()) {
  model_->tree_ = std::make_unique<ModelTree>();
  tree_ = model_->tree_.get();
}

std::shared_ptr<const RobotModel> ModelBuilder::build(urdf::ModelInterface& urdf,
                                                      const ModelOptions& options,
                                                      const std::string& source) {
  if (!options.gravity.allFinite()) throw ModelError("non-finite gravity for " + source);
  validateUrdf(urdf, source);  // axes, masses, inertias (urdf_validation.h)
  lockJoints(urdf, options.locked_joints, source);
  if (!urdf.root_link_) throw ModelError("URDF has no root link: " + source);
  // kdl_parser drops (and warns about) the root link's inertia; we keep it ourselves.
  const urdf::InertialSharedPtr root_inertial = urdf.root_link_->inertial;
  urdf.root_link_->inertial.reset();
  KDL::Tree kdl_tree;
  if (!kdl_parser::treeFromUrdfModel(urdf, kdl_tree))
    throw ModelError("kdl_parser could not build a KDL tree from " + source);

  ModelBuilder b(urdf, source);
  RobotModel& model = *b.model_;
  model.name_ = urdf.getName();
  model.source_ = source;
  model.gravity_ = options.gravity;
  model.locked_joints_ = options.locked_joints;
  const urdf::LinkConstSharedPtr root = urdf.getRoot();
  if (!root) throw ModelError("URDF has no root link: " + source);
  bool floating = root->name != "world";
  if (options.base == ModelOptions::Base::kFloating) floating = true;
  if (options.base == ModelOptions::Base::kFixed) floating = false;
  model.floating_base_ = floating;
  // A fixed-base root link never moves: its mass does not enter M or b.
  const int root_body = floating ? b.addFloatingBase(root_inertial) : -1;
  b.tree_->frames.push_back({root->name, root_body, Eigen::Isometry3d::Identity()});
  model.link_names_.push_back(root->name);
  model.link_parents_.push_back("");
  b.addCollisionShapes(*root);
  b.visit(kdl_tree.getRootSegment(), root_body, Eigen::Isometry3d::Identity());
  b.finish();
  return b.model_;
}

int ModelBuilder::newBody(int parent, const Eigen::Isometry3d& placement,
                          const Eigen::Vector3d& axis, bool prismatic) {
  Body b;
  b.parent = parent;
  b.placement = placement;
  b.axis = axis.normalized();
  b.prismatic = prismatic;
  b.com.setZero();
  b.inertia_origin.setZero();
  tree_->bodies.push_back(b);
  return static_cast<int>(tree_->bodies.size()) - 1;
}

int ModelBuilder::addFloatingBase(const urdf::InertialSharedPtr& root_inertial) {
  // x, y, z along the world axes, then yaw (z), pitch (y), roll (x).
  const char* names[6] = {"base_x", "base_y", "base_z", "base_yaw", "base_pitch", "base_roll"};
  const Eigen::Vector3d axes[6] = {Eigen::Vector3d::UnitX(), Eigen::Vector3d::UnitY(),
                                   Eigen::Vector3d::UnitZ(), Eigen::Vector3d::UnitZ(),
                                   Eigen::Vector3d::UnitY(), Eigen::Vector3d::UnitX()};
  int root_body = -1;
  for (int i = 0; i < 6; ++i) {
    root_body = newBody(root_body, Eigen::Isometry3d::Identity(), axes[i], i < 3);
    JointInfo j;
    j.name = names[i];
    j.is_virtual = true;
    j.is_prismatic = i < 3;
    j.q_min = -kNoLimit;
    j.q_max = kNoLimit;
    j.qd_max = kNoLimit;
    j.effort_max = 0.0;
    model_->joints_.push_back(j);
  }
  // kdl_parser ignores the root link's inertia: take it from the URDF.
  double m;
  Eigen::Vector3d c;
  Eigen::Matrix3d I0;
  linkInertia(root_inertial, m, c, I0);
  addInertia(tree_->bodies[root_body], Eigen::Isometry3d::Identity(), m, c, I0);
  return root_body;
}

JointInfo ModelBuilder::jointInfo(const urdf::Joint& uj) const {
  JointInfo j;
  j.name = uj.name;
  j.is_prismatic = uj.type == urdf::Joint::PRISMATIC;
  j.is_continuous = uj.type == urdf::Joint::CONTINUOUS;
  j.q_min = -kNoLimit;
  j.q_max = kNoLimit;
  j.qd_max = kNoLimit;
  j.effort_max = kNoLimit;
  if (uj.limits) {
    if (uj.type != urdf::Joint::CONTINUOUS) {
      j.q_min = uj.limits->lower;
      j.q_max = uj.limits->upper;
    }
    if (uj.limits->velocity > 0.0) j.qd_max = uj.limits->velocity;
    if (uj.limits->effort > 0.0) j.effort_max = uj.limits->effort;
  }
  if (j.q_min > j.q_max)
    throw ModelError("joint '" + j.name + "' has lower limit above upper limit in " + source_);
  return j;
}

void ModelBuilder::visit(const KDL::SegmentMap::const_iterator& element, int body,
                         const Eigen::Isometry3d& in_body) {
  for (const auto& child : GetTreeElementChildren(element->second)) {
    const KDL::Segment& seg = GetTreeElementSegment(child->second);
    const KDL::Joint& kj = seg.getJoint();
    const Eigen::Isometry3d T0 = in_body * toEigen(seg.pose(0.0));
    const std::string& link_name = seg.getName();
    const urdf::LinkConstSharedPtr link = urdf_.getLink(link_name);
    const urdf::JointConstSharedPtr uj = link ? link->parent_joint : nullptr;
    if (!uj) throw ModelError("link '" + link_name + "' has no parent joint in " + source_);
    int child_body = body;
    Eigen::Isometry3d child_in_body = T0;
    if (kj.getType() == KDL::Joint::None) {
      if (uj->type != urdf::Joint::FIXED)
        throw ModelError("unsupported joint type of '" + uj->name + "' in " + source_ +
                         " (only revolute, continuous, prismatic and fixed)");
    } else {
      // KDL gives the axis in the parent *segment's* frame (the URDF joint origin's rotation
      // applied), which is not the body frame when the parent link hangs on fixed joints:
      // undo the joint origin's rotation only, giving the axis in the child link's frame.
      const KDL::Vector a = kj.JointAxis();
      const Eigen::Vector3d axis_parent(a.x(), a.y(), a.z());
      const Eigen::Vector3d axis_child = toEigen(seg.pose(0.0)).linear().transpose() * axis_parent;
      const JointInfo j = jointInfo(*uj);
      child_body = newBody(body, T0, axis_child, j.is_prismatic);
      child_in_body = Eigen::Isometry3d::Identity();
      model_->joints_.push_back(j);
    }
    // The link's inertia straight from urdfdom (its <inertial> origin, rotation included),
    // expressed in the link frame, then placed where the link sits in its body.
    double m;
    Eigen::Vector3d c;
    Eigen::Matrix3d I0;
    linkInertia(link->inertial, m, c, I0);
    if (child_body >= 0) addInertia(tree_->bodies[child_body], child_in_body, m, c, I0);
    tree_->frames.push_back({link_name, child_body, child_in_body});
    model_->link_names_.push_back(link_name);
    model_->link_parents_.push_back(uj->parent_link_name);
    addCollisionShapes(*link);
    visit(child, child_body, child_in_body);
  }
}

void ModelBuilder::addCollisionShapes(const urdf::Link& link) {
  for (const urdf::CollisionSharedPtr& c : link.collision_array) {
    if (!c) continue;
    if (std::optional<CollisionShape> shape = readCollisionShape(*c, link.name, source_))
      model_->collision_shapes_.push_back(std::move(*shape));
  }
}

void ModelBuilder::finish() {
  ModelTree& tree = *tree_;
  if (tree.bodies.empty())
    throw ModelError("the robot in " + source_ + " has no degree of freedom");
  for (int i = 0; i < static_cast<int>(tree.bodies.size()); ++i) {
    for (int j = i; j >= 0; j = tree.bodies[j].parent) tree.bodies[i].support.push_back(j);
    model_->total_mass_ += tree.bodies[i].mass;
  }
  for (const Frame& f : tree.frames) model_->frame_names_.push_back(f.name);
}

std::shared_ptr<const RobotModel> RobotModel::fromUrdfString(const std::string& xml,
                                                             const ModelOptions& options,
                                                             const std::string& source) {
  if (xml.find("<robot") == std::string::npos)
    throw ModelError("malformed URDF in " + source + ": no <robot> element");
  validateUrdfXml(xml, source);  // before urdfdom: numbers, names, one tree (urdf_validation.h)
  const urdf::ModelInterfaceSharedPtr urdf = urdf::parseURDF(xml);
  if (!urdf) throw ModelError("malformed URDF in " + source + " (urdfdom could not parse it)");
  return ModelBuilder::build(*urdf, options, source);
}

std::shared_ptr<const RobotModel> RobotModel::fromUrdfFile(const std::string& path,
                                                           const ModelOptions& options) {
  return fromUrdfString(readTextFile<ModelError>(path, "URDF file '" + path + "'", kMaxUrdfBytes),
                        options, path);
}

}  // namespace reach_trajopt
