/// \file fuzz_yaml_config.cpp
/// Fuzzes the YAML config readers: YamlSection (duplicate keys, types) and every component's
/// fromYaml() on the sections of config/biped.yaml and config/sim.yaml.

#include "fuzz_common.h"
#include "reach_trajopt/common/config_yaml.h"
#include "reach_trajopt/contact/contact_config.h"
#include "reach_trajopt/control/whole_body_controller.h"
#include "reach_trajopt/ocp/ocp_config.h"
#include "reach_trajopt/planner/kinematic_feasibility.h"
#include "reach_trajopt/planner/tvr_planner.h"
#include "reach_trajopt/reach/reach_config.h"
#include "reach_trajopt/sim/sim_config.h"
#include "reach_trajopt/step/footstep_transition_planner.h"
#include "reach_trajopt/walk/walking_experiment.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  using namespace reach_trajopt;
  try {
    const YamlSection root = YamlSection::loadString(reach_fuzz::text(data, size), "fuzz.yaml");
    root.requireOnlyKeys(configSections());
    auto each = [&](const char* key, auto read) {
      if (!root.has(key)) return;
      try {
        read(root.section(key));
      } catch (const ReachError&) {
      }
    };
    each("contact", [](const YamlSection& s) { ContactConfig::fromYaml(s); });
    each("planner", [](const YamlSection& s) { TvrConfig::fromYaml(s); });
    each("kinematic_feasibility",
         [](const YamlSection& s) { KinematicFeasibilityConfig::fromYaml(s); });
    each("reach", [](const YamlSection& s) { ReachConfig::fromYaml(s).estimatedQps(); });
    each("wbc", [](const YamlSection& s) { WbcConfig::fromYaml(s); });
    each("walk", [](const YamlSection& s) { WalkConfig::fromYaml(s); });
    each("ocp", [](const YamlSection& s) { TransitionOcpConfig::fromYaml(s); });
    each("sim", [](const YamlSection& s) { SimConfig::fromYaml(s); });
    FootstepPlannerConfig::fromYaml(root);
  } catch (const ReachError&) {
  }
  return 0;
}
