/// \file fuzz_transition_request.cpp
/// Fuzzes plan_transition's request reader (readTransitionRequest) for our biped's n_q.

#include "fuzz_common.h"
#include "reach_trajopt/common/json_reader.h"
#include "reach_trajopt/ocp/transition_request_json.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  using namespace reach_trajopt;
  try {
    const nlohmann::json doc = JsonReader::parse(reach_fuzz::text(data, size), "fuzz.json");
    const TransitionRequestJson r = readTransitionRequest(JsonReader(doc, "fuzz.json"), 18);
    if (r.request.q0.size() != 18 || (r.has_qf && r.request.qf.size() != 18)) std::abort();
  } catch (const ReachError&) {
  }
  return 0;
}
