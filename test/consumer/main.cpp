/// consumer <urdf>: loads a robot through reach_trajopt's core library and prints
/// "nq=<n> nu=<n> mass_kg=<m>" (exit 0), or the error (exit 2).
#include <cstdio>

#include "reach_trajopt/model/robot_model.h"

int main(int argc, char** argv) {
  if (argc != 2) {
    std::fprintf(stderr, "usage: consumer <urdf>\n");
    return 2;
  }
  try {
    const auto model = reach_trajopt::RobotModel::fromUrdfFile(argv[1]);
    std::printf("nq=%d nu=%d mass_kg=%.3f\n", model->nq(), model->nu(), model->totalMass());
  } catch (const reach_trajopt::ReachError& e) {
    std::fprintf(stderr, "consumer: %s\n", e.what());
    return 2;
  }
  return 0;
}
