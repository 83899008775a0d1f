#include "reach_trajopt/sim/sim_body_tree.h"

#include <urdf_parser/urdf_parser.h>

#include <Eigen/Eigenvalues>
#include <cmath>

#include "reach_trajopt/common/error.h"
#include "reach_trajopt/common/text_file.h"
#include "reach_trajopt/model/collision_shape.h"
#include "reach_trajopt/model/joint_locking.h"
#include "reach_trajopt/model/urdf_validation.h"

namespace reach_trajopt {

namespace {

Eigen::Isometry3d toIsometry(const urdf::Pose& p) {
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T.translation() = Eigen::Vector3d(p.position.x, p.position.y, p.position.z);
  T.linear() = Eigen::Quaterniond(p.rotation.w, p.rotation.x, p.rotation.y, p.rotation.z)
                   .normalized()
                   .toRotationMatrix();
  return T;
}

// Mass properties accumulated in the body's URDF frame: sum of m, m c, and inertias about the
// body frame's origin.
struct MassAccumulator {
  double mass = 0.0;
  Eigen::Vector3d first_moment = Eigen::Vector3d::Zero();
  Eigen::Matrix3d inertia_origin = Eigen::Matrix3d::Zero();

  void add(double m, const Eigen::Vector3d& c, const Eigen::Matrix3d& I_com) {
    mass += m;
    first_moment += m * c;
    inertia_origin +=
        I_com + m * (c.squaredNorm() * Eigen::Matrix3d::Identity() - c * c.transpose());
  }
};

class Builder {
 public:
  Builder(const urdf::ModelInterface& model, const std::string& source) : model_(model) {
    tree_.source = source;
  }

  SimBodyTree build() {
    urdf::LinkConstSharedPtr root = model_.getRoot();
    if (!root) throw ModelError(tree_.source + ": URDF has no root link");
    tree_.floating_base = root->name != "world";
    SimBody body;
    body.name = root->name;
    tree_.bodies.push_back(body);
    masses_.emplace_back();
    visit(*root, 0, Eigen::Isometry3d::Identity());
    for (size_t i = 0; i < tree_.bodies.size(); ++i) finish(tree_.bodies[i], masses_[i]);
    return std::move(tree_);
  }

 private:
  // Adds `link` (at pose T in the URDF frame of body b) and recurses into its children.
  void visit(const urdf::Link& link, int b, const Eigen::Isometry3d& T) {
    SimBody& body = tree_.bodies[b];
    if (body.links.empty() || body.links.back() != link.name) body.links.push_back(link.name);
    tree_.frames[link.name] = {b, T};
    if (link.inertial && link.inertial->mass > 0.0) {
      const urdf::Inertial& in = *link.inertial;
      const Eigen::Isometry3d Tc = T * toIsometry(in.origin);
      Eigen::Matrix3d I;
      I << in.ixx, in.ixy, in.ixz, in.ixy, in.iyy, in.iyz, in.ixz, in.iyz, in.izz;
      masses_[b].add(in.mass, Tc.translation(), Tc.linear() * I * Tc.linear().transpose());
    }
    for (const auto& col : link.collision_array) addShape(link.name, b, T, *col);

    for (const urdf::JointSharedPtr& joint : link.child_joints) {
      urdf::LinkConstSharedPtr child = model_.getLink(joint->child_link_name);
      if (!child) throw ModelError(tree_.source + ": joint '" + joint->name + "' has no child");
      const Eigen::Isometry3d T_joint = toIsometry(joint->parent_to_joint_origin_transform);
      switch (joint->type) {
        case urdf::Joint::FIXED:
          visit(*child, b, T * T_joint);
          break;
        case urdf::Joint::REVOLUTE:
        case urdf::Joint::CONTINUOUS:
        case urdf::Joint::PRISMATIC: {
          SimBody next;
          next.name = child->name;
          next.parent = b;
          next.joint = joint->name;
          next.joint_type = joint->type == urdf::Joint::PRISMATIC ? SimBody::JointType::kPrismatic
                                                                  : SimBody::JointType::kRevolute;
          next.parent_to_body = T * T_joint;
          next.axis = Eigen::Vector3d(joint->axis.x, joint->axis.y, joint->axis.z);
          if (next.axis.norm() < 1e-12) {
            throw ModelError(tree_.source + ": joint '" + joint->name + "' has a zero axis");
          }
          next.axis.normalize();
          if (joint->type != urdf::Joint::CONTINUOUS) {
            if (!joint->limits) {
              throw ModelError(tree_.source + ": joint '" + joint->name + "' has no <limit>");
            }
            next.q_min = joint->limits->lower;
            next.q_max = joint->limits->upper;
          }
          // URDF effort 0 means "not given": leave the joint unsaturated.
          if (joint->limits && joint->limits->effort > 0.0) next.effort_max = joint->limits->effort;
          tree_.bodies.push_back(next);
          masses_.emplace_back();
          visit(*child, static_cast<int>(tree_.bodies.size()) - 1, Eigen::Isometry3d::Identity());
          break;
        }
        default:
          throw ModelError(tree_.source + ": joint '" + joint->name +
                           "' is floating or planar; the simulator supports fixed, revolute, "
                           "continuous and prismatic joints");
      }
    }
  }

  void addShape(const std::string& link, int b, const Eigen::Isometry3d& T,
                const urdf::Collision& col) {
    std::optional<SimShape> shape = readCollisionShape(col, link, tree_.source);
    if (!shape) return;  // meshes do not collide in the simulator (documented in bullet_world.h)
    shape->pose = T * shape->pose;  // link frame -> the body's URDF frame
    tree_.bodies[b].shapes.push_back(*shape);
  }

  void finish(SimBody& body, const MassAccumulator& acc) {
    body.mass = acc.mass;
    if (acc.mass <= 0.0) return;
    body.com = acc.first_moment / acc.mass;
    const Eigen::Vector3d& c = body.com;
    body.inertia = acc.inertia_origin -
                   acc.mass * (c.squaredNorm() * Eigen::Matrix3d::Identity() - c * c.transpose());
    body.inertia = 0.5 * (body.inertia + body.inertia.transpose()).eval();
    body.principal = Eigen::Isometry3d::Identity();
    body.principal.translation() = c;
    const Eigen::Matrix3d off =
        body.inertia - Eigen::Matrix3d(body.inertia.diagonal().asDiagonal());
    if (off.cwiseAbs().maxCoeff() <= 1e-14 * body.inertia.trace()) {
      // Already principal: keep the URDF axes (no round-off from an eigen-decomposition).
      body.principal_inertia = body.inertia.diagonal();
    } else {
      Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eig(body.inertia);
      Eigen::Matrix3d V = eig.eigenvectors();
      if (V.determinant() < 0.0) V.col(2) = -V.col(2);
      body.principal.linear() = V;
      body.principal_inertia = eig.eigenvalues();
    }
    if ((body.principal_inertia.array() < 0.0).any()) {
      throw ModelError(tree_.source + ": body '" + body.name +
                       "' has an inertia that is not positive semi-definite");
    }
  }

  const urdf::ModelInterface& model_;
  SimBodyTree tree_;
  std::vector<MassAccumulator> masses_;
};

}  // namespace

SimBodyTree SimBodyTree::fromUrdfFile(const std::string& path, const LockedJoints& locked) {
  return fromUrdfString(readTextFile<ModelError>(path, "URDF file '" + path + "'", kMaxUrdfBytes),
                        path, locked);
}

SimBodyTree SimBodyTree::fromUrdfString(const std::string& xml, const std::string& source,
                                        const LockedJoints& locked) {
  urdf::ModelInterfaceSharedPtr model = urdf::parseURDF(xml);
  if (!model) throw ModelError(source + ": malformed URDF (urdfdom could not parse it)");
  lockJoints(*model, locked, source);
  return Builder(*model, source).build();
}

const std::pair<int, Eigen::Isometry3d>& SimBodyTree::frame(const std::string& link) const {
  auto it = frames.find(link);
  if (it == frames.end()) throw ModelError("unknown frame '" + link + "' in " + source);
  return it->second;
}

double SimBodyTree::totalMass() const {
  double m = 0.0;
  for (const SimBody& b : bodies) m += b.mass;
  return m;
}

}  // namespace reach_trajopt
