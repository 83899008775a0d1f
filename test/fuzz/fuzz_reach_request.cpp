/// \file fuzz_reach_request.cpp
/// Fuzzes reach_check's request reader (readReachCheckRequest, with its "config" overrides) for
/// our biped's n_q, and the resource estimate a check runs first.

#include "fuzz_common.h"
#include "reach_trajopt/common/json_reader.h"
#include "reach_trajopt/reach/reach_request_json.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  using namespace reach_trajopt;
  try {
    const nlohmann::json doc = JsonReader::parse(reach_fuzz::text(data, size), "fuzz.json");
    const ReachCheckRequest r = readReachCheckRequest(JsonReader(doc, "fuzz.json"), 18, {});
    r.config.requireResourcesWithinLimits(18);
    (void)r.stance.pose();
    (void)r.target.pose();
  } catch (const ReachError&) {
  }
  return 0;
}
