#pragma once
/// \file violations_json.h
/// ConstraintViolations as the JSON object the tools print ({family: value, ..., "max"}), shared
/// by plan_transition and check_transition so both spell the families alike.

#include <nlohmann/json.hpp>

#include "reach_trajopt/ocp/transition_result.h"

namespace reach_trajopt {

inline nlohmann::json violationsJson(const ConstraintViolations& v) {
  return {{"dynamics", v.dynamics},
          {"stance_contact", v.stance_contact},
          {"stance_cone", v.stance_cone},
          {"new_contact", v.new_contact},
          {"new_cone", v.new_cone},
          {"torque", v.torque},
          {"joint_limits", v.joint_limits},
          {"velocity_limits", v.velocity_limits},
          {"reachable_set", v.reachable_set},
          {"leg_clearance", v.leg_clearance},
          {"initial_state", v.initial_state},
          {"final_state", v.final_state},
          {"max", v.max()}};
}

}  // namespace reach_trajopt
