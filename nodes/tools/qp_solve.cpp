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
/// Read by readQpProblem (qp_problem_json.h): unknown keys and inconsistent sizes are errors naming
/// the key path (e.g. "problem.json[3].Aeq: row 1 has 2 entries, expected 3").
/// Exit status: 0 when every problem was read (whatever its solve status), 2 when the input is not
/// valid JSON or a problem is malformed (message on stderr).

#include <Eigen/Core>
#include <cmath>
#include <fstream>
#include <iostream>
#include <limits>
#include <nlohmann/json.hpp>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "reach_trajopt/common/cli_options.h"
#include "reach_trajopt/common/error.h"
#include "reach_trajopt/common/json_reader.h"
#include "reach_trajopt/qp/dual_active_set_qp.h"
#include "reach_trajopt/qp/qp_problem_json.h"

namespace {

using nlohmann::json;
using reach_trajopt::JsonReader;
using reach_trajopt::qp::DualActiveSetQp;
using reach_trajopt::qp::QpSolverConfig;

/// At most this many problems in one batch (docs/limits.md).
constexpr std::size_t kMaxBatch = 100000;

json vectorJson(const Eigen::Ref<const Eigen::VectorXd>& v) {
  json out = json::array();
  for (Eigen::Index i = 0; i < v.size(); ++i) out.push_back(v(i));
  return out;
}

json invalidResult(const std::string& message) {
  return json{{"status", "invalid_input"},
              {"x", json::array()},
              {"objective", 0.0},
              {"multipliers", json::array()},
              {"active_set", json::array()},
              {"iterations", 0},
              {"message", message}};
}

json solveOne(const JsonReader& reader) {
  const reach_trajopt::qp::QpProblem p = reach_trajopt::qp::readQpProblem(reader);
  const auto& G = p.G;
  const auto& g = p.g;
  const auto& Aeq = p.Aeq;
  const auto& beq = p.beq;
  const auto& Ain = p.Ain;
  const auto& bin = p.bin;
  const auto& config = p.config;
  std::vector<int> warm = p.warm_start;
  const bool has_warm = p.has_warm_start;
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

/// The tool's options (--help prints them): none but --help.
const reach_trajopt::CliTool kTool(
    "qp_solve", "[problem.json]",
    "Solves QPs with the bundled dual active-set solver: one problem object, or a JSON list\n"
    "of them (a list of results is printed). Reads standard input when no file is given.",
    {});

}  // namespace

int main(int argc, char** argv) {
  reach_trajopt::CliArgs args;
  try {
    args = kTool.parse(argc, argv);
  } catch (const std::exception& e) {  // an unknown option: not a malformed problem
    std::cerr << "qp_solve: " << e.what() << "\n";
    return 2;
  }
  if (args.help()) {
    std::cout << kTool.usage();
    return 0;
  }
  if (args.positional().size() > 1) {
    std::cerr << kTool.usageLine() << "\n";
    return 2;
  }
  try {
    const std::string source = args.positional().empty() ? "-" : args.positional()[0];
    const json input = JsonReader::parseFile(source);
    const JsonReader top(input, source == "-" ? "<stdin>" : source);
    if (input.is_array()) {
      const std::size_t n = top.requireArray(0, kMaxBatch);
      json out = json::array();
      for (size_t i = 0; i < n; ++i) out.push_back(solveOne(top.at(i)));
      std::cout << out.dump() << "\n";
    } else {
      std::cout << solveOne(top).dump(2) << "\n";
    }
  } catch (const reach_trajopt::ReachError& e) {
    std::cerr << "qp_solve: malformed problem: " << e.what() << "\n";
    return 2;
  } catch (const std::exception& e) {  // e.g. std::bad_alloc: still a message, not an abort
    std::cerr << "qp_solve: " << e.what() << "\n";
    return 2;
  }
  return 0;
}
