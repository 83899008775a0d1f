#pragma once
/// \file contact_problems.h
/// Benchmark problem families for the bundled QP, all feasible by construction:
///  - contact QP of eq. (15) (docs/method.md Sec. 4): x = [qdd (18); du (12); lambda (6 per
///  contact)],
///    min |qdd|^2_Wq + |du|^2_Wu + |lambda|^2_Wl s.t. M qdd - S^T du - J^T lambda = S^T u - b,
///    J_i qdd = -Jdot_i qd, u_min <= u + du <= u_max, C lambda_i >= 0 (16-row surface contact
///    wrench cone of Caron et al. 2015). Children of one parent share M, J, b and G and differ
///    by the random torque u ~ U(u_min, u_max).
///  - backward feasibility QP (19): min |lambda|^2 s.t. J_b^T lambda = M_b qdd + b_b (6 rows),
///    cone rows, torque bounds on u = M_a qdd + b_a - J_a^T lambda. Children differ by qdd.
///  - random dense QPs of the same size class as eiquadprog's reference figures on this machine
///  type (bench/qp/README.md).
/// Problem form as in dual_active_set_qp.h: A_eq x = b_eq, A_in x >= b_in.

#include <Eigen/Dense>
#include <random>

namespace bench {

struct QpData {
  Eigen::MatrixXd G;
  Eigen::VectorXd g;
  Eigen::MatrixXd Aeq;
  Eigen::VectorXd beq;
  Eigen::MatrixXd Ain;
  Eigen::VectorXd bin;
};

constexpr int kNv = 18;  // floating base + 12 leg joints, Talos-legs-like
constexpr int kNu = 12;

inline Eigen::MatrixXd randn(std::mt19937& rng, int rows, int cols) {
  std::normal_distribution<double> normal;
  Eigen::MatrixXd A(rows, cols);
  for (int i = 0; i < rows * cols; ++i) A.data()[i] = normal(rng);
  return A;
}

/// 16-row wrench cone C w >= 0, w = [f; tau] at the sole centre (sole half-sizes X, Y, friction
/// mu).
inline Eigen::Matrix<double, 16, 6> wrenchCone(double mu = 0.7, double X = 0.1, double Y = 0.05) {
  Eigen::Matrix<double, 16, 6> C;
  C.setZero();
  // friction pyramid
  C.row(0) << -1, 0, mu, 0, 0, 0;
  C.row(1) << 1, 0, mu, 0, 0, 0;
  C.row(2) << 0, -1, mu, 0, 0, 0;
  C.row(3) << 0, 1, mu, 0, 0, 0;
  // centre of pressure inside the sole
  C.row(4) << 0, 0, Y, 1, 0, 0;
  C.row(5) << 0, 0, Y, -1, 0, 0;
  C.row(6) << 0, 0, X, 0, 1, 0;
  C.row(7) << 0, 0, X, 0, -1, 0;
  // yaw torque bounds
  int r = 8;
  for (double s1 : {-1.0, 1.0})
    for (double s2 : {-1.0, 1.0}) {
      C.row(r++) << -s1 * Y, -s2 * X, mu * (X + Y), s1 * mu, s2 * mu, 1;
      C.row(r++) << -s1 * Y, -s2 * X, mu * (X + Y), -s1 * mu, -s2 * mu, -1;
    }
  return C;
}

/// A parent state of the contact QP (15): M, J, b and the weights.
struct ContactParent {
  int nc;
  Eigen::MatrixXd M, J;  // 18 x 18, 6nc x 18
  Eigen::VectorXd b;     // 18
  Eigen::VectorXd jdqd;  // -Jdot qd, 6nc
  Eigen::VectorXd u_min, u_max;
  Eigen::MatrixXd G;  // constant weights
};

inline ContactParent contactParent(std::mt19937& rng, int nc) {
  ContactParent p;
  p.nc = nc;
  const Eigen::MatrixXd B = randn(rng, kNv, kNv);
  p.M = B * B.transpose() / kNv + Eigen::MatrixXd::Identity(kNv, kNv);
  p.M.topLeftCorner(3, 3) += 30.0 * Eigen::Matrix3d::Identity();  // total mass on the base
  p.J = randn(rng, 6 * nc, kNv);
  p.u_max = Eigen::VectorXd::Constant(kNu, 100.0);
  p.u_min = -p.u_max;
  // A consistent state: lambda0 inside the cone (weight shared by the feet), qdd0 random.
  const int n = kNv + kNu + 6 * nc;
  Eigen::VectorXd lambda0 = 0.3 * randn(rng, 6 * nc, 1);
  for (int c = 0; c < nc; ++c) lambda0(6 * c + 2) = 350.0 / nc;  // fz
  const Eigen::VectorXd qdd0 = randn(rng, kNv, 1);
  const Eigen::VectorXd u0 = (30.0 * randn(rng, kNu, 1)).cwiseMax(-90.0).cwiseMin(90.0);
  // S^T u0 - b = M qdd0 - J^T lambda0 (du0 = 0).
  p.b = -(p.M * qdd0 - p.J.transpose() * lambda0);
  p.b.tail(kNu) += u0;
  p.jdqd = p.J * qdd0;
  p.G = Eigen::MatrixXd::Zero(n, n);
  p.G.diagonal().head(kNv).setConstant(1.0);           // Wq
  p.G.diagonal().segment(kNv, kNu).setConstant(10.0);  // Wu
  p.G.diagonal().tail(6 * nc).setConstant(1e-3);       // Wl
  return p;
}

/// One child of the parent: the QP for the random torque u.
inline QpData contactChild(const ContactParent& p, const Eigen::VectorXd& u) {
  const int nl = 6 * p.nc, n = kNv + kNu + nl;
  const Eigen::Matrix<double, 16, 6> C = wrenchCone();
  QpData q;
  q.G = p.G;
  q.g = Eigen::VectorXd::Zero(n);
  q.Aeq = Eigen::MatrixXd::Zero(kNv + nl, n);
  q.Aeq.topLeftCorner(kNv, kNv) = p.M;
  q.Aeq.block(6, kNv, kNu, kNu) = -Eigen::MatrixXd::Identity(kNu, kNu);
  q.Aeq.topRightCorner(kNv, nl) = -p.J.transpose();
  q.Aeq.bottomLeftCorner(nl, kNv) = p.J;
  q.beq.resize(kNv + nl);
  q.beq.head(kNv) = -p.b;
  q.beq.segment(6, kNu) += u;
  q.beq.tail(nl) = p.jdqd;
  const int m_in = 2 * kNu + 16 * p.nc;
  q.Ain = Eigen::MatrixXd::Zero(m_in, n);
  q.bin.resize(m_in);
  q.Ain.block(0, kNv, kNu, kNu).setIdentity();  // du >= u_min - u
  q.bin.head(kNu) = p.u_min - u;
  q.Ain.block(kNu, kNv, kNu, kNu) = -Eigen::MatrixXd::Identity(kNu, kNu);  // -du >= u - u_max
  q.bin.segment(kNu, kNu) = u - p.u_max;
  for (int c = 0; c < p.nc; ++c) {
    q.Ain.block(2 * kNu + 16 * c, kNv + kNu + 6 * c, 16, 6) = C;
    q.bin.segment(2 * kNu + 16 * c, 16).setZero();
  }
  return q;
}

/// A parent of the backward feasibility QP (19): the base rows and actuated rows of M, b, J.
struct BackwardParent {
  int nc;
  Eigen::MatrixXd M, J;
  Eigen::VectorXd b, qdd0, u_min, u_max;
};

inline BackwardParent backwardParent(std::mt19937& rng, int nc) {
  BackwardParent p;
  p.nc = nc;
  const Eigen::MatrixXd B = randn(rng, kNv, kNv);
  p.M = B * B.transpose() / kNv + Eigen::MatrixXd::Identity(kNv, kNv);
  p.M.topLeftCorner(3, 3) += 30.0 * Eigen::Matrix3d::Identity();
  p.J = randn(rng, 6 * nc, kNv);
  p.qdd0 = randn(rng, kNv, 1);
  Eigen::VectorXd lambda0 = 0.3 * randn(rng, 6 * nc, 1);
  for (int c = 0; c < nc; ++c) lambda0(6 * c + 2) = 350.0 / nc;
  // b such that the base rows hold with lambda0 at qdd0.
  p.b = randn(rng, kNv, 1);
  p.b.head(6) = p.J.leftCols(6).transpose() * lambda0 - p.M.topRows(6) * p.qdd0;
  const Eigen::VectorXd u0 =
      p.M.bottomRows(kNu) * p.qdd0 + p.b.tail(kNu) - p.J.rightCols(kNu).transpose() * lambda0;
  p.u_min = u0.array() - 60.0;
  p.u_max = u0.array() + 60.0;
  return p;
}

/// The child QP for the sampled acceleration qdd (feasible for qdd near qdd0).
inline QpData backwardChild(const BackwardParent& p, const Eigen::VectorXd& qdd) {
  const int nl = 6 * p.nc;
  const Eigen::Matrix<double, 16, 6> C = wrenchCone();
  QpData q;
  q.G = Eigen::MatrixXd::Identity(nl, nl);
  q.g = Eigen::VectorXd::Zero(nl);
  q.Aeq = p.J.leftCols(6).transpose();  // J_b^T lambda = M_b qdd + b_b
  q.beq = p.M.topRows(6) * qdd + p.b.head(6);
  const Eigen::MatrixXd Ja_t = p.J.rightCols(kNu).transpose();  // 12 x nl
  const Eigen::VectorXd tau0 = p.M.bottomRows(kNu) * qdd + p.b.tail(kNu);
  const int m_in = 16 * p.nc + 2 * kNu;
  q.Ain = Eigen::MatrixXd::Zero(m_in, nl);
  q.bin = Eigen::VectorXd::Zero(m_in);
  for (int c = 0; c < p.nc; ++c) q.Ain.block(16 * c, 6 * c, 16, 6) = C;
  // u_min <= tau0 - Ja^T lambda <= u_max
  q.Ain.block(16 * p.nc, 0, kNu, nl) = -Ja_t;
  q.bin.segment(16 * p.nc, kNu) = p.u_min - tau0;
  q.Ain.block(16 * p.nc + kNu, 0, kNu, nl) = Ja_t;
  q.bin.segment(16 * p.nc + kNu, kNu) = tau0 - p.u_max;
  return q;
}

/// Random dense QP: n variables, m_eq equalities, m_in inequalities, feasible at a random point.
inline QpData randomQp(std::mt19937& rng, int n, int m_eq, int m_in) {
  QpData q;
  const Eigen::MatrixXd B = randn(rng, n, n);
  q.G = B * B.transpose() / n + 0.5 * Eigen::MatrixXd::Identity(n, n);
  q.g = randn(rng, n, 1);
  const Eigen::VectorXd x_f = randn(rng, n, 1);
  q.Aeq = randn(rng, m_eq, n);
  q.beq = q.Aeq * x_f;
  q.Ain = randn(rng, m_in, n);
  q.bin = q.Ain * x_f - randn(rng, m_in, 1).cwiseAbs();
  return q;
}

}  // namespace bench
