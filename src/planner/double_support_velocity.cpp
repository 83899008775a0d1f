#include "reach_trajopt/planner/double_support_velocity.h"

#include <Eigen/LU>
#include <Eigen/QR>
#include <string>
#include <vector>

#include "reach_trajopt/common/error.h"

namespace reach_trajopt {

Eigen::VectorXd doubleSupportVelocity(const RobotModel& model, const Eigen::VectorXd& q,
                                      FrameId left_sole, FrameId right_sole,
                                      const Eigen::Vector3d& com_velocity) {
  const int n = model.nq(), nu = model.nu();
  if (n - nu != 6) throw ModelError("doubleSupportVelocity: needs a floating-base model");
  requireSize("doubleSupportVelocity: q", q.size(), n);
  requireFinite("doubleSupportVelocity: q", q);
  requireFinite("doubleSupportVelocity: com_velocity", com_velocity);
  Workspace ws(model);
  model.update(ws, q, Eigen::VectorXd::Zero(n));
  Eigen::MatrixXd J(12, n);
  Matrix6Xd Js(6, n);
  model.frameJacobian(ws, left_sole, Js);
  J.topRows<6>() = Js;
  model.frameJacobian(ws, right_sole, Js);
  J.bottomRows<6>() = Js;
  // Joints: J_a qd_a = -J_b qd_b, the least-norm solution when there are more than 12
  // actuated joints. It exists unless the legs are singular (a straight knee).
  Eigen::CompleteOrthogonalDecomposition<Eigen::MatrixXd> legs(J.rightCols(nu));
  legs.setThreshold(1e-6);
  if (legs.rank() < 12)
    throw ReachError("doubleSupportVelocity: the legs are singular at q (a straight knee?)");
  // Z: qd as a function of the base's linear velocity (angular rates zero).
  Eigen::MatrixXd Z = Eigen::MatrixXd::Zero(n, 3);
  Z.topRows<3>().setIdentity();
  Z.bottomRows(nu) = -legs.solve(J.leftCols<3>());
  Eigen::Matrix3Xd Jc(3, n);
  model.centerOfMassJacobian(ws, Jc);
  const Eigen::Matrix3d JcZ = Jc * Z;
  const Eigen::Vector3d v_base = JcZ.fullPivLu().solve(com_velocity);
  Eigen::VectorXd qd = Z * v_base;
  if (!qd.allFinite()) throw ReachError("doubleSupportVelocity: no finite solution at q");
  return qd;
}

Eigen::VectorXd doubleSupportBaseVelocity(const RobotModel& model, const Eigen::VectorXd& q,
                                          FrameId left, FrameId right, const Eigen::Vector2d& v) {
  const int n = model.nq();
  requireSize("doubleSupportBaseVelocity: q", q.size(), n);
  requireFinite("doubleSupportBaseVelocity: base velocity", v);
  Eigen::VectorXd qd = Eigen::VectorXd::Zero(n);
  if (v.squaredNorm() == 0.0) return qd;
  Workspace ws(model);
  model.update(ws, q, qd);
  Matrix6Xd J(6, n);
  for (FrameId f : {left, right}) {
    model.frameJacobian(ws, f, J);
    // Leg columns: the joints whose column is non-zero for this sole (besides the base).
    std::vector<int> cols;
    for (int j = 6; j < n; ++j)
      if (J.col(j).norm() > 0.0) cols.push_back(j);
    Eigen::MatrixXd Jl(6, cols.size());
    for (size_t k = 0; k < cols.size(); ++k) Jl.col(k) = J.col(cols[k]);
    Eigen::VectorXd base = Eigen::VectorXd::Zero(6);
    base.head<2>() = v;
    const Eigen::VectorXd ql = Jl.completeOrthogonalDecomposition().solve(-J.leftCols(6) * base);
    for (size_t k = 0; k < cols.size(); ++k) qd[cols[k]] = ql[k];
  }
  qd.head<2>() = v;
  return qd;
}

}  // namespace reach_trajopt
