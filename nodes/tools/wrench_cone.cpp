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

#include "reach_trajopt/common/cli_args.h"
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

}  // namespace

int main(int argc, char** argv) {
  try {
    double mu = 0.7, X = 0.135, Y = 0.08;
    Eigen::Vector3d rpy = Eigen::Vector3d::Zero();
    for (int i = 1; i < argc; ++i) {
      const std::string a = argv[i];
      const auto need = [&](int n) {
        if (i + n >= argc) throw reach_trajopt::ReachError(a + ": missing value");
      };
      if (a == "--mu") {
        need(1);
        mu = parseNumber(a, argv[++i]);
      } else if (a == "--half-length") {
        need(1);
        X = parseNumber(a, argv[++i]);
      } else if (a == "--half-width") {
        need(1);
        Y = parseNumber(a, argv[++i]);
      } else if (a == "--rpy") {
        need(3);
        for (int k = 0; k < 3; ++k) rpy[k] = parseNumber(a, argv[++i]);
      } else if (a == "-h" || a == "--help") {
        std::cout << "usage: wrench_cone [--mu M] [--half-length X] [--half-width Y] "
                     "[--rpy roll pitch yaw]\n";
        return 0;
      } else {
        throw reach_trajopt::ReachError("unknown argument '" + a + "'");
      }
    }
    reach_trajopt::requireFinite("--rpy", rpy);
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
  } catch (const reach_trajopt::ReachError& e) {
    std::cerr << "wrench_cone: " << e.what() << "\n";
    return 2;
  } catch (const std::exception& e) {
    std::cerr << "wrench_cone: " << e.what() << "\n";
    return 2;
  }
}
