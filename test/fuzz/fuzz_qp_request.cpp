/// \file fuzz_qp_request.cpp
/// Fuzzes qp_solve's request reader (JsonReader + readQpProblem) and, for small problems, the
/// solve itself (the tool's whole path).

#include "fuzz_common.h"
#include "reach_trajopt/common/json_reader.h"
#include "reach_trajopt/qp/dual_active_set_qp.h"
#include "reach_trajopt/qp/qp_problem_json.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  using namespace reach_trajopt;
  try {
    const nlohmann::json doc = JsonReader::parse(reach_fuzz::text(data, size), "fuzz.json");
    qp::QpProblem p = qp::readQpProblem(JsonReader(doc, "fuzz.json"));
    if (p.g.size() > 30 || p.Aeq.rows() + p.Ain.rows() > 60) return 0;
    p.config.max_iterations = std::min(p.config.max_iterations, 200);
    qp::DualActiveSetQp solver(static_cast<int>(p.g.size()), static_cast<int>(p.Aeq.rows()),
                               static_cast<int>(p.Ain.rows()), p.config);
    solver.solve(p.G, p.g, p.Aeq, p.beq, p.Ain, p.bin, p.has_warm_start ? &p.warm_start : nullptr);
  } catch (const ReachError&) {
  }
  return 0;
}
