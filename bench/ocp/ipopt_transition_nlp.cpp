#include "ipopt_transition_nlp.h"

#include <IpIpoptApplication.hpp>
#include <IpSolveStatistics.hpp>
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstring>
#include <exception>

namespace reach_trajopt {

namespace {

// IPOPT treats |bound| >= 1e19 (nlp_lower/upper_bound_inf) as no bound.
constexpr double kNoBound = 2.0e19;

const char* statusName(Ipopt::ApplicationReturnStatus s) {
  switch (s) {
    case Ipopt::Solve_Succeeded:
      return "Solve_Succeeded";
    case Ipopt::Solved_To_Acceptable_Level:
      return "Solved_To_Acceptable_Level";
    case Ipopt::Infeasible_Problem_Detected:
      return "Infeasible_Problem_Detected";
    case Ipopt::Search_Direction_Becomes_Too_Small:
      return "Search_Direction_Becomes_Too_Small";
    case Ipopt::Diverging_Iterates:
      return "Diverging_Iterates";
    case Ipopt::User_Requested_Stop:
      return "User_Requested_Stop";
    case Ipopt::Feasible_Point_Found:
      return "Feasible_Point_Found";
    case Ipopt::Maximum_Iterations_Exceeded:
      return "Maximum_Iterations_Exceeded";
    case Ipopt::Restoration_Failed:
      return "Restoration_Failed";
    case Ipopt::Error_In_Step_Computation:
      return "Error_In_Step_Computation";
    case Ipopt::Maximum_CpuTime_Exceeded:
      return "Maximum_CpuTime_Exceeded";
    case Ipopt::Not_Enough_Degrees_Of_Freedom:
      return "Not_Enough_Degrees_Of_Freedom";
    case Ipopt::Invalid_Problem_Definition:
      return "Invalid_Problem_Definition";
    case Ipopt::Invalid_Option:
      return "Invalid_Option";
    case Ipopt::Invalid_Number_Detected:
      return "Invalid_Number_Detected";
    case Ipopt::Unrecoverable_Exception:
      return "Unrecoverable_Exception";
    case Ipopt::NonIpopt_Exception_Thrown:
      return "NonIpopt_Exception_Thrown";
    case Ipopt::Insufficient_Memory:
      return "Insufficient_Memory";
    case Ipopt::Internal_Error:
      return "Internal_Error";
  }
  return "UNKNOWN";
}

}  // namespace

IpoptTransitionNlp::IpoptTransitionNlp(TransitionNlp& nlp, const Eigen::VectorXd& x0)
    : nlp_(nlp), x0_(x0), solution_(x0) {}

bool IpoptTransitionNlp::get_nlp_info(Ipopt::Index& n, Ipopt::Index& m, Ipopt::Index& nnz_jac_g,
                                      Ipopt::Index& nnz_h_lag, IndexStyleEnum& index_style) {
  n = nlp_.variableCount();
  m = nlp_.equalityCount() + nlp_.inequalityCount();
  nnz_jac_g = n * m;  // dense: TransitionNlp's Jacobians are dense row-major
  nnz_h_lag = 0;      // limited-memory Hessian approximation
  index_style = C_STYLE;
  return true;
}

bool IpoptTransitionNlp::get_bounds_info(Ipopt::Index n, Ipopt::Number* x_l, Ipopt::Number* x_u,
                                         Ipopt::Index m, Ipopt::Number* g_l, Ipopt::Number* g_u) {
  for (Ipopt::Index i = 0; i < n; ++i) {
    x_l[i] = std::max(nlp_.lowerBounds()[i], -kNoBound);
    x_u[i] = std::min(nlp_.upperBounds()[i], kNoBound);
  }
  const int m_eq = nlp_.equalityCount();
  for (Ipopt::Index j = 0; j < m; ++j) {
    g_l[j] = j < m_eq ? 0.0 : -kNoBound;
    g_u[j] = 0.0;
  }
  return true;
}

bool IpoptTransitionNlp::get_starting_point(Ipopt::Index n, bool init_x, Ipopt::Number* x,
                                            bool init_z, Ipopt::Number*, Ipopt::Number*,
                                            Ipopt::Index, bool init_lambda, Ipopt::Number*) {
  if (!init_x || init_z || init_lambda) return false;  // primal start only
  Eigen::Map<Eigen::VectorXd>(x, n) = x0_;
  return true;
}

bool IpoptTransitionNlp::prepare(const Ipopt::Number* x, bool gradients) {
  const int n = nlp_.variableCount();
  const bool same = valid_ && std::memcmp(x_.data(), x, n * sizeof(double)) == 0;
  if (same && (has_gradients_ || !gradients)) return true;
  x_ = Eigen::Map<const Eigen::VectorXd>(x, n);
  valid_ = false;
  try {
    nlp_.evaluate(x_, gradients, values_);
  } catch (const std::exception& e) {
    error_ = e.what();
    return false;  // IPOPT backtracks (or stops with Invalid_Number_Detected)
  }
  if (!std::isfinite(values_.cost) || !values_.equality.allFinite() ||
      !values_.inequality.allFinite()) {
    return false;
  }
  valid_ = true;
  has_gradients_ = gradients;
  if (gradients) ++gradient_evaluations_;
  return true;
}

bool IpoptTransitionNlp::eval_f(Ipopt::Index, const Ipopt::Number* x, bool,
                                Ipopt::Number& obj_value) {
  if (!prepare(x, false)) return false;
  obj_value = values_.cost;
  return true;
}

bool IpoptTransitionNlp::eval_grad_f(Ipopt::Index n, const Ipopt::Number* x, bool,
                                     Ipopt::Number* grad_f) {
  if (!prepare(x, true)) return false;
  Eigen::Map<Eigen::VectorXd>(grad_f, n) = values_.cost_gradient;
  return true;
}

bool IpoptTransitionNlp::eval_g(Ipopt::Index, const Ipopt::Number* x, bool, Ipopt::Index m,
                                Ipopt::Number* g) {
  if (!prepare(x, false)) return false;
  const int m_eq = nlp_.equalityCount();
  Eigen::Map<Eigen::VectorXd> out(g, m);
  out.head(m_eq) = values_.equality;
  out.tail(m - m_eq) = values_.inequality;
  return true;
}

bool IpoptTransitionNlp::eval_jac_g(Ipopt::Index n, const Ipopt::Number* x, bool, Ipopt::Index m,
                                    Ipopt::Index, Ipopt::Index* iRow, Ipopt::Index* jCol,
                                    Ipopt::Number* values) {
  if (values == nullptr) {  // structure: every entry, row-major
    for (Ipopt::Index r = 0; r < m; ++r) {
      for (Ipopt::Index c = 0; c < n; ++c) {
        iRow[r * n + c] = r;
        jCol[r * n + c] = c;
      }
    }
    return true;
  }
  if (!prepare(x, true)) return false;
  const int m_eq = nlp_.equalityCount();
  Eigen::Map<RowMajorMatrixXd> out(values, m, n);
  out.topRows(m_eq) = values_.equality_jacobian;
  out.bottomRows(m - m_eq) = values_.inequality_jacobian;
  return true;
}

void IpoptTransitionNlp::finalize_solution(Ipopt::SolverReturn, Ipopt::Index n,
                                           const Ipopt::Number* x, const Ipopt::Number*,
                                           const Ipopt::Number*, Ipopt::Index, const Ipopt::Number*,
                                           const Ipopt::Number*, Ipopt::Number,
                                           const Ipopt::IpoptData*,
                                           Ipopt::IpoptCalculatedQuantities*) {
  solution_ = Eigen::Map<const Eigen::VectorXd>(x, n);
}

IpoptBenchResult solveWithIpopt(TransitionNlp& nlp, const Eigen::VectorXd& x0,
                                const IpoptBenchSettings& settings) {
  Ipopt::SmartPtr<IpoptTransitionNlp> tnlp = new IpoptTransitionNlp(nlp, x0);
  Ipopt::SmartPtr<Ipopt::IpoptApplication> app = IpoptApplicationFactory();
  Ipopt::OptionsList& o = *app->Options();
  o.SetStringValue("sb", "yes");  // no banner
  o.SetIntegerValue("print_level", 0);
  o.SetStringValue("hessian_approximation", "limited-memory");
  o.SetNumericValue("tol", settings.tol);
  o.SetNumericValue("constr_viol_tol", settings.constr_viol_tol);
  o.SetNumericValue("acceptable_tol", 1.0e10);  // KKT error not part of the acceptable test
  o.SetNumericValue("acceptable_obj_change_tol", settings.acceptable_obj_change_tol);
  o.SetNumericValue("acceptable_constr_viol_tol", settings.acceptable_constr_viol_tol);
  o.SetNumericValue("acceptable_compl_inf_tol", settings.acceptable_compl_inf_tol);
  o.SetIntegerValue("acceptable_iter", settings.acceptable_iter);
  o.SetIntegerValue("max_iter", settings.max_iter);
  o.SetNumericValue("max_cpu_time", settings.max_cpu_time);

  IpoptBenchResult r;
  Ipopt::ApplicationReturnStatus status = app->Initialize();
  if (status == Ipopt::Solve_Succeeded) {
    const auto start = std::chrono::steady_clock::now();
    status = app->OptimizeTNLP(tnlp);
    r.wall_time = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  }
  r.status = statusName(status);
  r.error = tnlp->error();
  r.succeeded = status == Ipopt::Solve_Succeeded || status == Ipopt::Solved_To_Acceptable_Level;
  if (Ipopt::IsValid(app->Statistics())) r.iterations = app->Statistics()->IterationCount();
  r.gradient_evaluations = tnlp->gradientEvaluations();
  r.x = tnlp->solution();

  NlpValues v;
  nlp.evaluate(r.x, false, v);
  r.cost = v.cost;
  double viol = 0.0;
  if (v.equality.size() > 0) viol = v.equality.cwiseAbs().maxCoeff();
  if (v.inequality.size() > 0) viol = std::max(viol, v.inequality.maxCoeff());
  viol = std::max(viol, (nlp.lowerBounds() - r.x).maxCoeff());
  viol = std::max(viol, (r.x - nlp.upperBounds()).maxCoeff());
  r.nlp_violation = std::max(viol, 0.0);
  return r;
}

}  // namespace reach_trajopt
