/// \file wrench_cone.cpp
/// Prints the contact wrench cone of eq. (7)-(8) as JSON, for tests and inspection:
///   wrench_cone [--mu 0.7] [--half-length 0.135] [--half-width 0.08] [--rpy r p y]
/// Output: {"mu", "half_length", "half_width", "R": 3x3, "sole": 16x6 C, "world": 16x6
/// C blkdiag(R^T, R^T)} with R = Rz(y) Ry(p) Rx(r) the sole's orientation in the world.
/// Exit status 2 with the message on stderr for bad arguments (e.g. mu <= 0).

#include <Eigen/Geometry>
#include <cmath>
#include <cstdlib>
#include <iostream>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "reach_trajopt/common/cli_args.h"
#include "reach_trajopt/common/cli_options.h"
#include "reach_trajopt/common/error.h"
#include "reach_trajopt/contact/contact_wrench_cone.h"

namespace {

double parseNumber(const std::string& flag, const char* text) {
  // NaN / inf pass: ContactWrenchCone and --rpy's check name them ("must be positive and finite").
  return reach_trajopt::parseDoubleOption(flag, text, -HUGE_VAL, HUGE_VAL, true);
}

template <typename M>
nlohmann::json toJson(const M& m) {
  nlohmann::json rows = nlohmann::json::array();
  for (Eigen::Index r = 0; r < m.rows(); ++r) {
    nlohmann::json row = nlohmann::json::array();
    for (Eigen::Index c = 0; c < m.cols(); ++c) row.push_back(m(r, c));
    rows.push_back(row);
  }
  return rows;
}

/// The tool's options (--help prints them).
const reach_trajopt::CliTool kTool(
    "wrench_cone", "",
    "Prints the contact wrench cone of eq. (7)-(8) as JSON: the sole's and the world's C.",
    {{"--mu", "M", "friction coefficient", "0.7"},
     {"--half-length", "X", "sole half-length [m]", "0.135"},
     {"--half-width", "Y", "sole half-width [m]", "0.08"},
     {"--rpy", "roll pitch yaw", "the sole's orientation in the world [rad]", "0 0 0", 3}});

/// --rpy's three angles (zeros when not given).
Eigen::Vector3d rpyOption(const reach_trajopt::CliArgs& args) {
  Eigen::Vector3d rpy = Eigen::Vector3d::Zero();
  const std::vector<std::string>& v = args.values("--rpy");
  for (std::size_t k = 0; k < v.size() && k < 3; ++k) rpy[k] = parseNumber("--rpy", v[k].c_str());
  reach_trajopt::requireFinite("--rpy", rpy);
  return rpy;
}

}  // namespace

int main(int argc, char** argv) {
  return kTool.run(argc, argv, [](const reach_trajopt::CliArgs& args) {
    if (!args.positional().empty())
      throw reach_trajopt::ReachError("unknown argument '" + args.positional()[0] + "'");
    const double mu = parseNumber("--mu", args.value("--mu").c_str());
    const double X = parseNumber("--half-length", args.value("--half-length").c_str());
    const double Y = parseNumber("--half-width", args.value("--half-width").c_str());
    const Eigen::Vector3d rpy = rpyOption(args);
    const reach_trajopt::ContactWrenchCone cone(mu, X, Y);
    const Eigen::Matrix3d R = (Eigen::AngleAxisd(rpy[2], Eigen::Vector3d::UnitZ()) *
                               Eigen::AngleAxisd(rpy[1], Eigen::Vector3d::UnitY()) *
                               Eigen::AngleAxisd(rpy[0], Eigen::Vector3d::UnitX()))
                                  .toRotationMatrix();
    nlohmann::json out;
    out["mu"] = mu;
    out["half_length"] = X;
    out["half_width"] = Y;
    out["R"] = toJson(R);
    out["sole"] = toJson(cone.soleMatrix());
    out["world"] = toJson(cone.worldMatrix(R));
    std::cout << out.dump() << "\n";
    return 0;
  });
}
