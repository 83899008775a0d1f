#pragma once
/// \file fuzz_common.h
/// Shared by the libFuzzer targets of test/fuzz/ (built by test/sanitized/CMakeLists.txt with
/// ASan + UBSan): a ReachError (or std::exception from a reader) is the expected answer to bad
/// input; anything else (a crash, a sanitizer report, an uncaught exception) is a finding.

#include <cstddef>
#include <cstdint>
#include <memory>
#include <string>

#include "reach_trajopt/common/error.h"
#include "reach_trajopt/model/robot_model.h"

namespace reach_fuzz {

inline std::string text(const uint8_t* data, size_t size) {
  return std::string(reinterpret_cast<const char*>(data), size);
}

/// Our biped (urdf/biped.urdf), loaded once.
inline const std::shared_ptr<const reach_trajopt::RobotModel>& biped() {
  static const auto model = reach_trajopt::RobotModel::fromUrdfFile(
      std::string(REACH_TRAJOPT_SOURCE_DIR) + "/urdf/biped.urdf");
  return model;
}

}  // namespace reach_fuzz
