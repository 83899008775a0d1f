#pragma once
/// \file qp_problem_json.h
/// One QP of the qp_solve tool read strictly from JSON (format in nodes/tools/qp_solve.cpp):
///   minimize 1/2 x^T G x + g^T x  s.t.  Aeq x = beq,  Ain x >= bin
/// Known keys only; G is n x n with n = size(g), Aeq m_eq x n with beq of m_eq, Ain m_in x n
/// with bin of m_in, warm_start indices in [0, m_eq + m_in). Numbers may be "nan", "inf",
/// "-inf" or null (the solver reports non-finite data as invalid_input; infinite bounds are
/// legal), everything else is an error naming the key path.

#include <Eigen/Core>
#include <vector>

#include "reach_trajopt/common/json_reader.h"
#include "reach_trajopt/qp/dual_active_set_qp.h"

namespace reach_trajopt {
namespace qp {

/// Upper bound on n and on each of m_eq, m_in of one problem (docs/limits.md): the solver's
/// dense factors cost O(n^2) memory and O(n^3) time.
constexpr int kMaxQpSize = 2000;

struct QpProblem {
  Eigen::MatrixXd G, Aeq, Ain;
  Eigen::VectorXd g, beq, bin;
  bool has_warm_start = false;
  std::vector<int> warm_start;
  QpSolverConfig config;
};

/// \throws ReachError naming the source and key path of the first problem.
QpProblem readQpProblem(const JsonReader& r);

}  // namespace qp
}  // namespace reach_trajopt
