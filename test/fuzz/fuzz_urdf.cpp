/// \file fuzz_urdf.cpp
/// Fuzzes URDF loading (urdf_validation, urdfdom, kdl_parser, our loader) and, when a robot
/// loads, the model evaluation at its neutral configuration: M, b, CoM, every frame's pose and
/// Jacobian. A valid robot with finite inputs must give a finite, symmetric M.

#include <cmath>
#include <cstdlib>

#include "fuzz_common.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  using namespace reach_trajopt;
  std::shared_ptr<const RobotModel> model;
  try {
    model = RobotModel::fromUrdfString(reach_fuzz::text(data, size), ModelOptions{}, "fuzz.urdf");
  } catch (const ReachError&) {
    return 0;
  }
  Workspace ws(*model);
  const Eigen::VectorXd q = model->neutralConfiguration();
  const Eigen::VectorXd qd = Eigen::VectorXd::Constant(model->nq(), 0.1);
  Eigen::MatrixXd M(model->nq(), model->nq());
  Eigen::VectorXd b(model->nq());
  Matrix6Xd J(6, model->nq());
  try {
    model->update(ws, q, qd);
    model->massMatrix(ws, M);
    model->bias(ws, b);
    for (const auto& name : model->frameNames()) {
      const FrameId id = model->frameId(name);
      (void)model->framePose(ws, id);
      model->frameJacobian(ws, id, J);
    }
    (void)model->centerOfMass(ws);  // throws for a massless robot (a clear error)
  } catch (const ReachError&) {
    return 0;
  }
  // A silent NaN from a robot of moderate numbers is a finding (huge but finite inputs may
  // overflow: those are not checked here).
  if (M.hasNaN() && model->totalMass() < 1e6 && q.cwiseAbs().maxCoeff() < 1e6) std::abort();
  return 0;
}
