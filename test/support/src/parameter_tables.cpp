/// \file parameter_tables.cpp
/// The list of config tables (see the header).

#include "reach_trajopt/testing/parameter_tables.h"

#include "reach_trajopt/contact/contact_config.h"
#include "reach_trajopt/control/whole_body_controller.h"
#include "reach_trajopt/model/robot_config.h"
#include "reach_trajopt/ocp/ocp_config.h"
#include "reach_trajopt/planner/kinematic_feasibility.h"
#include "reach_trajopt/planner/nearest_feasible_foothold.h"
#include "reach_trajopt/planner/tvr_planner.h"
#include "reach_trajopt/reach/reach_config.h"
#include "reach_trajopt/sim/sim_config.h"
#include "reach_trajopt/walk/walking_experiment.h"

namespace reach_trajopt {

std::vector<ParameterTable> parameterTables() {
  return {RobotConfig::fields().table(),
          ContactConfig::fields().table(),
          TvrConfig::fields().table(),
          KinematicFeasibilityConfig::fields().table(),
          ReachConfig::fields().table(),
          WbcConfig::fields().table(),
          WalkConfig::fields().table(),
          TransitionOcpConfig::fields().table(),
          NearestFootholdConfig::fields().table(),
          SimConfig::fields().table()};
}

}  // namespace reach_trajopt
