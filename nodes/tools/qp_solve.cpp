/// \file qp_solve.cpp
/// qp_solve: solves QPs with the bundled dual active-set solver (DualActiveSetQp), to reproduce a
/// failing contact, feasibility or controller QP outside ROS (no master needed).
///
///   qp_solve [problem.json]        (reads stdin when no file is given)
///
/// Input: one problem object, or a JSON list of them (batch mode: a list of results is printed).
///   minimize 1/2 x^T G x + g^T x  s.t.  Aeq x = beq,  Ain x >= bin
///   {"G": [[..], ..], "g": [..], "Aeq": [[..], ..], "beq": [..], "Ain": [[..], ..], "bin": [..],
///    "warm_start": [indices]  (optional, numbering of "active_set"),
///    "options": {"max_iterations": 1000, "feasibility_tol": 1e-10, "dependence_tol": 1e-10,
///                "regularization": 0.0}  (optional)}
/// Matrices are lists of rows; empty lists are allowed and missing Aeq/beq/Ain/bin mean no rows.
/// JSON has no NaN: the strings "nan", "inf", "-inf" and null are read as those values.
/// Output: {"status": "optimal"|"infeasible"|"iteration_limit"|"invalid_input", "x", "objective",
///   "multipliers" (equalities then inequalities, G x + g = Aeq^T l_eq + Ain^T l_in, l_in >= 0),
///   "active_set" (equality i -> i, inequality j -> m_eq + j), "iterations", "message"}.
/// Exit status: 0 when every problem was read (whatever its solve status), 2 when the input is not
/// valid JSON or a problem is malformed (message on stderr).

#include <cmath>
#include <fstream>
#include <iostream>
#include <limits>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include <Eigen/Core>
#include <nlohmann/json.hpp>

#include "reach_trajopt/common/error.h"
#include "reach_trajopt/qp/dual_active_set_qp.h"

namespace {

using nlohmann::json;
using reach_trajopt::qp::DualActiveSetQp;
using reach_trajopt::qp::QpSolverConfig;

struct BadProblem : std::runtime_error {
  using std::runtime_error::runtime_error;
};

double readNumber(const json& v, const std::string& where) {
  if (v.is_number()) return v.get<double>();
  if (v.is_null()) return std::numeric_limits<double>::quiet_NaN();
  if (v.is_string()) {
    const std::string s = v.get<std::string>();
    if (s == "nan" || s == "NaN") return std::numeric_limits<double>::quiet_NaN();
    if (s == "inf" || s == "+inf" || s == "Infinity")
      return std::numeric_limits<double>::infinity();
    if (s == "-inf" || s == "-Infinity") return -std::numeric_limits<double>::infinity();
  }
  throw BadProblem(where + ": expected a number, got " + v.dump());
}

Eigen::VectorXd readVector(const json& p, const char* key, bool required) {
  if (!p.contains(key)) {
    if (required) throw BadProblem(std::string("missing key '") + key + "'");
    return Eigen::VectorXd(0);
  }
  const json& v = p.at(key);
  if (!v.is_array()) throw BadProblem(std::string(key) + ": expected a list of numbers");
  Eigen::VectorXd out(v.size());
  for (size_t i = 0; i < v.size(); ++i)
    out(i) = readNumber(v[i], std::string(key) + "[" + std::to_string(i) + "]");
  return out;
}

Eigen::MatrixXd readMatrix(const json& p, const char* key, bool required) {
  if (!p.contains(key)) {
    if (required) throw BadProblem(std::string("missing key '") + key + "'");
    return Eigen::MatrixXd(0, 0);
  }
  const json& m = p.at(key);
  if (!m.is_array()) throw BadProblem(std::string(key) + ": expected a list of rows");
  if (m.empty()) return Eigen::MatrixXd(0, 0);
  if (!m[0].is_array()) throw BadProblem(std::string(key) + ": expected a list of rows");
  const size_t cols = m[0].size();
  Eigen::MatrixXd out(m.size(), cols);
  for (size_t i = 0; i < m.size(); ++i) {
    if (!m[i].is_array() || m[i].size() != cols)
      throw BadProblem(std::string(key) + ": row " + std::to_string(i) + " has " +
                       (m[i].is_array() ? std::to_string(m[i].size()) : "no") +
                       " entries, row 0 has " + std::to_string(cols));
    for (size_t j = 0; j < cols; ++j)
      out(i, j) = readNumber(m[i][j], std::string(key) + "[" + std::to_string(i) + "][" +
                                          std::to_string(j) + "]");
  }
  return out;
}

json vectorJson(const Eigen::Ref<const Eigen::VectorXd>& v) {
  json out = json::array();
  for (Eigen::Index i = 0; i < v.size(); ++i) out.push_back(v(i));
  return out;
}

json invalidResult(const std::string& message) {
  return json{{"status", "invalid_input"}, {"x", json::array()},        {"objective", 0.0},
              {"multipliers", json::array()}, {"active_set", json::array()},
              {"iterations", 0},             {"message", message}};
}

json solveOne(const json& p) {
  if (!p.is_object()) throw BadProblem("a problem must be a JSON object");
  const Eigen::MatrixXd G = readMatrix(p, "G", true);
  const Eigen::VectorXd g = readVector(p, "g", true);
  const Eigen::MatrixXd Aeq = readMatrix(p, "Aeq", false);
  const Eigen::VectorXd beq = readVector(p, "beq", false);
  const Eigen::MatrixXd Ain = readMatrix(p, "Ain", false);
  const Eigen::VectorXd bin = readVector(p, "bin", false);
  std::vector<int> warm;
  const bool has_warm = p.contains("warm_start");
  if (has_warm) {
    if (!p["warm_start"].is_array()) throw BadProblem("warm_start: expected a list of integers");
    for (const json& v : p["warm_start"]) {
      if (!v.is_number_integer()) throw BadProblem("warm_start: expected a list of integers");
      warm.push_back(v.get<int>());
    }
  }
  QpSolverConfig config;
  if (p.contains("options")) {
    const json& o = p["options"];
    if (!o.is_object()) throw BadProblem("options: expected an object");
    for (auto it = o.begin(); it != o.end(); ++it) {
      if (!it.value().is_number()) throw BadProblem("options." + it.key() + ": expected a number");
      if (it.key() == "max_iterations") config.max_iterations = it.value().get<int>();
      else if (it.key() == "feasibility_tol") config.feasibility_tol = it.value().get<double>();
      else if (it.key() == "dependence_tol") config.dependence_tol = it.value().get<double>();
      else if (it.key() == "regularization") config.regularization = it.value().get<double>();
      else throw BadProblem("options: unknown key '" + it.key() + "'");
    }
  }
  try {
    DualActiveSetQp solver(static_cast<int>(g.size()), static_cast<int>(Aeq.rows()),
                           static_cast<int>(Ain.rows()), config);
    const auto& r = solver.solve(G, g, Aeq, beq, Ain, bin, has_warm ? &warm : nullptr);
    return json{{"status", reach_trajopt::qp::toString(r.status)},
                {"x", vectorJson(r.x)},
                {"objective", r.objective},
                {"multipliers", vectorJson(r.all())},
                {"active_set", r.active_set},
                {"iterations", r.iterations},
                {"message", r.message}};
  } catch (const reach_trajopt::ReachError& e) {
    return invalidResult(e.what());
  }
}

}  // namespace

int main(int argc, char** argv) {
  const std::string arg1 = argc == 2 ? argv[1] : "";
  if (argc > 2 || arg1 == "-h" || arg1 == "--help") {
    std::cerr << "usage: qp_solve [problem.json]   (stdin when no file; a list = batch)\n";
    return 2;
  }
  json input;
  try {
    if (argc == 2) {
      std::ifstream file(argv[1]);
      if (!file) {
        std::cerr << "qp_solve: cannot open '" << argv[1] << "'\n";
        return 2;
      }
      input = json::parse(file);
    } else {
      input = json::parse(std::cin);
    }
  } catch (const json::parse_error& e) {
    std::cerr << "qp_solve: invalid JSON: " << e.what() << "\n";
    return 2;
  }
  try {
    if (input.is_array()) {
      json out = json::array();
      for (size_t i = 0; i < input.size(); ++i) {
        try {
          out.push_back(solveOne(input[i]));
        } catch (const BadProblem& e) {
          throw BadProblem("problem " + std::to_string(i) + ": " + e.what());
        }
      }
      std::cout << out.dump() << "\n";
    } else {
      std::cout << solveOne(input).dump(2) << "\n";
    }
  } catch (const BadProblem& e) {
    std::cerr << "qp_solve: malformed problem: " << e.what() << "\n";
    return 2;
  } catch (const json::exception& e) {
    std::cerr << "qp_solve: malformed problem: " << e.what() << "\n";
    return 2;
  }
  return 0;
}
