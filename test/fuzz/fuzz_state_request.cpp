/// \file fuzz_state_request.cpp
/// Fuzzes `model_info --state`'s reader (readStates) and the biped's evaluation at each state
/// read (M, b, CoM, sole Jacobians), as the tool does.

#include "fuzz_common.h"
#include "reach_trajopt/common/json_reader.h"
#include "reach_trajopt/common/state_json.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  using namespace reach_trajopt;
  const auto& model = reach_fuzz::biped();
  try {
    const nlohmann::json doc = JsonReader::parse(reach_fuzz::text(data, size), "fuzz.json");
    const auto states = readStates(JsonReader(doc, "fuzz.json"), model->nq());
    Workspace ws(*model);
    Eigen::MatrixXd M(model->nq(), model->nq());
    Eigen::VectorXd b(model->nq());
    Matrix6Xd J(6, model->nq());
    for (std::size_t i = 0; i < states.size() && i < 4; ++i) {
      model->update(ws, states[i].q, states[i].qd);
      model->massMatrix(ws, M);
      model->bias(ws, b);
      model->frameJacobian(ws, model->frameId("l_sole"), J);
    }
  } catch (const ReachError&) {
  }
  return 0;
}
