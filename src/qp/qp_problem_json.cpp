/// \file qp_problem_json.cpp
/// Strict reading of qp_solve problems (qp_problem_json.h).

#include "reach_trajopt/qp/qp_problem_json.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>

namespace reach_trajopt {
namespace qp {
namespace {

/// A constraint block: matrix `A` (m x n, or absent/empty: no rows) and its vector `b`.
void readRows(const JsonReader& r, const char* A_key, const char* b_key, Eigen::Index n,
              Eigen::MatrixXd& A, Eigen::VectorXd& b) {
  Eigen::Index m = 0;
  if (r.has(A_key)) {
    const JsonReader a = r.at(A_key);
    m = static_cast<Eigen::Index>(a.requireArray(0, kMaxQpSize));
    A = a.matrix(m, n, NonFinite::kAllow);
  } else {
    A.resize(0, n);
  }
  if (r.has(b_key))
    b = r.at(b_key).vector(m, NonFinite::kAllow);
  else if (m > 0)
    r.at(b_key);  // throws "missing key"
  else
    b.resize(0);
}

}  // namespace

QpProblem readQpProblem(const JsonReader& r) {
  r.requireObject("a problem object {\"G\": [[...]], \"g\": [...], ...}");
  r.requireOnlyKeys({"G", "g", "Aeq", "beq", "Ain", "bin", "warm_start", "options"});
  QpProblem p;
  const JsonReader g = r.at("g");
  const auto n = static_cast<Eigen::Index>(g.requireArray(0, kMaxQpSize));
  p.g = g.vector(n, NonFinite::kAllow);
  p.G = r.at("G").matrix(n, n, NonFinite::kAllow);
  // The solver factors G's lower triangle: an asymmetric G would be another problem (or be
  // reported as not positive definite).
  for (Eigen::Index i = 0; i < n; ++i)
    for (Eigen::Index j = 0; j < i; ++j) {
      const double a = p.G(i, j), b = p.G(j, i);
      if (std::isfinite(a) && std::isfinite(b) &&
          std::abs(a - b) > 1e-9 * std::max(std::abs(a), std::abs(b))) {
        std::ostringstream os;
        os << "G is not symmetric: G[" << i << "][" << j << "] = " << a << " but G[" << j << "]["
           << i << "] = " << b;
        r.at("G").at(static_cast<std::size_t>(i)).at(static_cast<std::size_t>(j)).fail(os.str());
      }
    }
  readRows(r, "Aeq", "beq", n, p.Aeq, p.beq);
  readRows(r, "Ain", "bin", n, p.Ain, p.bin);
  if (r.has("warm_start")) {
    p.has_warm_start = true;
    const JsonReader w = r.at("warm_start");
    const long long rows = p.Aeq.rows() + p.Ain.rows();
    const std::size_t k = w.requireArray(0, static_cast<std::size_t>(rows));
    for (std::size_t i = 0; i < k; ++i)
      p.warm_start.push_back(static_cast<int>(w.at(i).integer(0, rows - 1)));
  }
  if (r.has("options")) {
    const JsonReader o = r.at("options");
    o.requireOnlyKeys({"max_iterations", "feasibility_tol", "dependence_tol", "regularization"});
    if (o.has("max_iterations"))
      p.config.max_iterations = static_cast<int>(o.at("max_iterations").integer(0, 1000000));
    o.optionalNumber("feasibility_tol", p.config.feasibility_tol);
    o.optionalNumber("dependence_tol", p.config.dependence_tol);
    o.optionalNumber("regularization", p.config.regularization);
  }
  return p;
}

}  // namespace qp
}  // namespace reach_trajopt
