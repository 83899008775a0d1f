#pragma once
/// \file ipopt_transition_nlp.h
/// IPOPT (the paper's NLP solver) on our TransitionNlp, for the OCP benchmark only: the product
/// never links IPOPT, and its headers stay private to the bench_ocp target.
///
/// The adapter hands IPOPT exactly the NLP that NLopt's SLSQP sees in TransitionOcp: the same
/// variables and bounds, g = [equalities (= 0); inequalities (<= 0)] with their dense Jacobian
/// (every entry declared, row-major), the same start point. There is no exact Hessian: IPOPT
/// runs with hessian_approximation = limited-memory (L-BFGS), the counterpart of SLSQP's BFGS.
/// As in TransitionOcp's NLopt bridge, one TransitionNlp::evaluate() serves all callbacks at a
/// point, so `gradientEvaluations()` counts the same thing as TransitionResult::iterations.

#include <Eigen/Core>
#include <IpTNLP.hpp>
#include <string>

#include "reach_trajopt/ocp/transition_nlp.h"

namespace reach_trajopt {

/// IPOPT settings of the benchmark (see solveWithIpopt()). Two ways to stop, as SLSQP has:
///  - IPOPT's own convergence test (scaled KKT error <= tol, |g| violation <= constr_viol_tol);
///  - the counterpart of SLSQP's ftol_rel test (NLopt stops SLSQP at a feasible iterate whose
///    relative cost change is below ftol_rel, without looking at the multipliers): IPOPT's
///    "acceptable" test with only the relative cost change, the constraint violation and the
///    complementarity active (acceptable_tol, i.e. the KKT error, switched off), met once.
struct IpoptBenchSettings {
  double tol = 1.0e-6;              ///< IPOPT's scaled overall NLP error
  double constr_viol_tol = 1.0e-6;  ///< max |g| violation [m / dimensionless NLP rows]
  /// Relative cost change of the acceptable test: TransitionOcpConfig::ftol_rel (strict) or
  /// relaxed_ftol_rel (relaxed).
  double acceptable_obj_change_tol = 1.0e-6;
  double acceptable_constr_viol_tol = 1.0e-6;  ///< as constr_viol_tol
  double acceptable_compl_inf_tol = 1.0e-6;    ///< max |s z|: the barrier parameter is small
  int acceptable_iter = 1;                     ///< SLSQP stops on one iterate passing its test
  int max_iter = 400;                          ///< = TransitionOcpConfig::max_evaluations
  double max_cpu_time = 10.0;  ///< [s] = TransitionOcpConfig::time_limit (3.11: CPU time)
};

/// Outcome of one IPOPT solve of a TransitionNlp.
struct IpoptBenchResult {
  std::string status;            ///< IPOPT's ApplicationReturnStatus, e.g. "Solve_Succeeded"
  bool succeeded = false;        ///< Solve_Succeeded or Solved_To_Acceptable_Level
  std::string error;             ///< last exception of TransitionNlp::evaluate (IPOPT backtracked)
  double wall_time = 0.0;        ///< OptimizeTNLP wall time [s]
  int iterations = 0;            ///< IPOPT iterations
  int gradient_evaluations = 0;  ///< evaluate(x, gradients = true) at distinct points
  Eigen::VectorXd x;             ///< final point (n)
  double cost = 0.0;             ///< TransitionNlp cost at x
  /// max(|equality|, max(inequality, 0), bound excess) at x, in the NLP's row units.
  double nlp_violation = 0.0;
};

/// IPOPT's TNLP over a TransitionNlp (see file comment). The TransitionNlp must outlive it.
class IpoptTransitionNlp : public Ipopt::TNLP {
 public:
  IpoptTransitionNlp(TransitionNlp& nlp, const Eigen::VectorXd& x0);

  bool get_nlp_info(Ipopt::Index& n, Ipopt::Index& m, Ipopt::Index& nnz_jac_g,
                    Ipopt::Index& nnz_h_lag, IndexStyleEnum& index_style) override;
  bool get_bounds_info(Ipopt::Index n, Ipopt::Number* x_l, Ipopt::Number* x_u, Ipopt::Index m,
                       Ipopt::Number* g_l, Ipopt::Number* g_u) override;
  bool get_starting_point(Ipopt::Index n, bool init_x, Ipopt::Number* x, bool init_z,
                          Ipopt::Number* z_L, Ipopt::Number* z_U, Ipopt::Index m, bool init_lambda,
                          Ipopt::Number* lambda) override;
  bool eval_f(Ipopt::Index n, const Ipopt::Number* x, bool new_x,
              Ipopt::Number& obj_value) override;
  bool eval_grad_f(Ipopt::Index n, const Ipopt::Number* x, bool new_x,
                   Ipopt::Number* grad_f) override;
  bool eval_g(Ipopt::Index n, const Ipopt::Number* x, bool new_x, Ipopt::Index m,
              Ipopt::Number* g) override;
  bool eval_jac_g(Ipopt::Index n, const Ipopt::Number* x, bool new_x, Ipopt::Index m,
                  Ipopt::Index nele_jac, Ipopt::Index* iRow, Ipopt::Index* jCol,
                  Ipopt::Number* values) override;
  void finalize_solution(Ipopt::SolverReturn status, Ipopt::Index n, const Ipopt::Number* x,
                         const Ipopt::Number* z_L, const Ipopt::Number* z_U, Ipopt::Index m,
                         const Ipopt::Number* g, const Ipopt::Number* lambda,
                         Ipopt::Number obj_value, const Ipopt::IpoptData* ip_data,
                         Ipopt::IpoptCalculatedQuantities* ip_cq) override;

  const Eigen::VectorXd& solution() const { return solution_; }
  int gradientEvaluations() const { return gradient_evaluations_; }
  /// Message of an exception thrown by TransitionNlp::evaluate (empty when none).
  const std::string& error() const { return error_; }

 private:
  /// Evaluates the NLP at x unless it already did (with gradients when asked).
  bool prepare(const Ipopt::Number* x, bool gradients);

  TransitionNlp& nlp_;
  Eigen::VectorXd x0_, x_, solution_;
  NlpValues values_;
  bool valid_ = false, has_gradients_ = false;
  int gradient_evaluations_ = 0;
  std::string error_;
};

/// Solves `nlp` from x0 with IPOPT (print_level 0, limited-memory Hessian, `settings`).
IpoptBenchResult solveWithIpopt(TransitionNlp& nlp, const Eigen::VectorXd& x0,
                                const IpoptBenchSettings& settings = {});

}  // namespace reach_trajopt
