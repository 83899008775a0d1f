#pragma once
/// \file json_error.h
/// How the JSON tools (plan_transition, check_transition) answer an error: one JSON object
/// {"status": "error", "reason": what} on stdout, where a caller reads their answers; their
/// main() is runJsonTool.

#include <exception>
#include <functional>
#include <iostream>
#include <nlohmann/json.hpp>

#include "reach_trajopt/common/cli_options.h"

namespace reach_trajopt {

/// Prints `e` as {"status": "error", "reason": e.what()}. A message may quote bytes of the
/// input that are not UTF-8: they are replaced, the dump never throws.
inline void printJsonError(const std::exception& e) {
  const nlohmann::json out = {{"status", "error"}, {"reason", e.what()}};
  std::cout << out.dump(-1, ' ', false, nlohmann::json::error_handler_t::replace) << "\n";
}

/// A JSON tool's main: tool.run with the error printed by printJsonError (exit status 2).
inline int runJsonTool(const CliTool& tool, int argc, char** argv,
                       const std::function<int(const CliArgs&)>& body) {
  return tool.run(argc, argv, body, printJsonError);
}

}  // namespace reach_trajopt
