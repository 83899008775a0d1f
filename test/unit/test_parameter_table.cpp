// The config field tables (common/config_fields.h): docs/parameters.md is what they generate,
// every struct default equals the value of the shipped config files, every section of those
// files has a table, removed keys are clear errors, and the robot facts (sole frames, pelvis
// height) are read from one place.
#include <gtest/gtest.h>

#include <Eigen/Core>
#include <cmath>
#include <cstdint>
#include <fstream>
#include <set>
#include <sstream>
#include <string>

#include "reach_trajopt/common/config_fields.h"
#include "reach_trajopt/common/config_yaml.h"
#include "reach_trajopt/ocp/ocp_config.h"
#include "reach_trajopt/sim/sim_config.h"
#include "reach_trajopt/step/footstep_transition_planner.h"
#include "reach_trajopt/testing/parameter_tables.h"
#include "reach_trajopt/walk/walking_experiment.h"
#include "thrown_message.h"

using namespace reach_trajopt;

namespace {

const std::string kRepo = REACH_TRAJOPT_SOURCE_DIR;

std::string readFile(const std::string& path) {
  std::ifstream in(path);
  std::ostringstream os;
  os << in.rdbuf();
  return os.str();
}

/// The message of the ConfigError that `f` throws.
template <typename F>
std::string configError(F f) {
  return test::thrownMessage<ConfigError>(f);
}

/// Reading `yaml` (named `file`) as Config's `section` throws a ConfigError containing `words`.
template <typename Config>
void expectSectionError(const std::string& yaml, const std::string& file,
                        const std::string& section, const std::string& words) {
  const std::string message =
      configError([&] { Config::fromYaml(YamlSection::loadString(yaml, file).section(section)); });
  EXPECT_NE(message.find(words), std::string::npos) << message;
}

/// A config struct as a component would write it (see config_fields.h).
struct ToyConfig {
  double length = 0.5;  ///< [m]
  std::uint64_t seed = 1;
  Eigen::Vector3d gravity = Eigen::Vector3d(0, 0, -9.81);
  double angle = 0.0;  ///< [rad], written in degrees in the YAML
  void validate() const { fields().checkRanges(*this); }
  static const ConfigFields<ToyConfig>& fields() {
    static const ConfigFields<ToyConfig> f =
        ConfigFields<ToyConfig>("ToyConfig", "toy", "test/unit/test_parameter_table.cpp", "A toy.")
            .add("length", &ToyConfig::length, "m", Range::positive(), "a length")
            .add("seed", &ToyConfig::seed, "", "random stream")
            .add("gravity", &ToyConfig::gravity, "m/s^2", "world frame")
            .custom(
                "angle_deg", "number",
                [](const YamlSection& s, const std::string& k, ToyConfig& c) {
                  double deg = 0.0;
                  s.read(k, deg);
                  c.angle = deg * M_PI / 180.0;
                },
                [](const ToyConfig& c) { return parameterText(c.angle * 180.0 / M_PI); }, "deg",
                "an angle in degrees")
            .removed("size", "removed: use toy.length");
    return f;
  }
};

}  // namespace

TEST(ParameterTable, TheMechanismOnAToyConfig) {
  const auto section = [](const std::string& yaml) {
    return YamlSection::loadString(yaml, "toy.yaml").section("toy");
  };
  ToyConfig base;
  base.length = 2.0;
  const ToyConfig c = ToyConfig::fields().read(
      section("toy: {seed: 7, gravity: [0, 0, -1.62], angle_deg: 90}"), base);
  EXPECT_EQ(c.length, 2.0);  // missing: the base's value
  EXPECT_EQ(c.seed, 7u);
  EXPECT_EQ(c.gravity.z(), -1.62);
  EXPECT_NEAR(c.angle, M_PI / 2, 1e-15);
  EXPECT_EQ(ToyConfig::fields().keys(),
            (std::vector<std::string>{"length", "seed", "gravity", "angle_deg"}));
  const std::vector<ParameterRow> rows = ToyConfig::fields().rows(c);
  ASSERT_EQ(rows.size(), 4u);
  EXPECT_EQ(rows[2].type, "3 numbers");
  EXPECT_EQ(rows[2].value, "[0, 0, -1.62]");
  EXPECT_EQ(rows[3].value, "90");
  EXPECT_NE(configError([&] {
              ToyConfig::fields().read(section("toy: {seed: -1}"));
            }).find("toy.yaml: toy.seed: must be >= 0"),
            std::string::npos);
  EXPECT_NE(configError([&] {
              ToyConfig::fields().read(section("toy: {size: 1}"));
            }).find("toy.yaml: toy.size: removed: use toy.length"),
            std::string::npos);
  EXPECT_NE(configError([&] {
              ToyConfig::fields().read(section("toy: {length: -1}"));
            }).find("toy.yaml: toy: ToyConfig: length must be positive and finite, got -1"),
            std::string::npos);
  const std::string md = parameterTableMarkdown({ToyConfig::fields().table()});
  EXPECT_NE(md.find("| `length` | number | 0.5 | m | > 0 | a length |"), std::string::npos) << md;
  EXPECT_NE(md.find("| `angle_deg` | number | 0 | deg |  | an angle in degrees |"),
            std::string::npos)
      << md;
  EXPECT_NE(md.find("- `size`: removed: use toy.length"), std::string::npos) << md;
}

TEST(ParameterTable, DocsAreUpToDate) {
  const std::string generated = parameterTableMarkdown(parameterTables());
  const std::string file = readFile(kRepo + "/docs/parameters.md");
  EXPECT_EQ(file, generated)
      << "docs/parameters.md is out of date: regenerate it with\n"
         "  .build_ws/devel/lib/reach_trajopt/parameter_table > docs/parameters.md";
}

TEST(ParameterTable, DefaultsEqualTheShippedFiles) {
  const YamlSection biped = YamlSection::loadFile(kRepo + "/config/biped.yaml");
  const YamlSection sim = YamlSection::loadFile(kRepo + "/config/sim.yaml");
  std::set<std::string> tabled;
  for (const ParameterTable& t : parameterTables()) {
    tabled.insert(t.section);
    const YamlSection* file = biped.has(t.section) ? &biped : sim.has(t.section) ? &sim : nullptr;
    if (!file) continue;  // a section the files leave at its defaults (nearest_foothold)
    const std::vector<std::string> shipped = t.values_in(file->section(t.section));
    ASSERT_EQ(shipped.size(), t.rows.size());
    for (std::size_t i = 0; i < t.rows.size(); ++i)
      EXPECT_EQ(t.rows[i].value, shipped[i])
          << t.struct_name << "::" << t.rows[i].key << ": the struct default differs from "
          << t.section << "." << t.rows[i].key << " of the shipped file";
  }
  // Every section of the shipped files is tabled.
  for (const YamlSection* file : {&biped, &sim})
    for (const std::string& section : file->keys())
      EXPECT_TRUE(tabled.count(section)) << section << " has no table";
}

TEST(ParameterTable, ValueTextReadsBackExactly) {
  EXPECT_EQ(parameterText(0.001), "0.001");
  EXPECT_EQ(parameterText(-0.16), "-0.16");
  EXPECT_EQ(parameterText(1e-6), "1e-06");
  EXPECT_EQ(parameterText(1000.0), "1000");
  EXPECT_EQ(parameterText(0.1 + 0.2), "0.30000000000000004");
  EXPECT_EQ(parameterText(std::vector<double>{0.0, -9.81}), "[0, -9.81]");
}

TEST(ParameterTable, UnknownAndBadKeysNameTheFileAndKey) {
  expectSectionError<WalkConfig>("walk: {stpes: 3}", "w.yaml", "walk",
                                 "w.yaml: walk.stpes: unknown key (known: policy steps");
  expectSectionError<WalkConfig>("walk: {policy: fast}", "w.yaml", "walk",
                                 "w.yaml: walk.policy: walking policy: unknown preset 'fast'");
  expectSectionError<WalkConfig>(
      "walk: {first_swing: up}", "w.yaml", "walk",
      "walk.first_swing: expected 'capture_point', 'left' or 'right', got 'up'");
  expectSectionError<WalkConfig>("walk: {initial_com_velocity: [1]}", "w.yaml", "walk",
                                 "walk.initial_com_velocity: expected 2 numbers, got 1");
  // Values read by name and through the table.
  const WalkConfig w = WalkConfig::fromYaml(
      YamlSection::loadString("walk: {policy: proposed, first_swing: left, seed: 7}", "w.yaml")
          .section("walk"));
  EXPECT_EQ(w.policy.name, "proposed");
  EXPECT_EQ(w.first_swing, WalkConfig::FirstSwing::kLeft);
  EXPECT_EQ(w.seed, 7u);
}

TEST(ParameterTable, RobotFactsLiveInOnePlace) {
  // The sole frames are the contact section's; an old sim.yaml that names them is an error.
  expectSectionError<SimConfig>("sim: {left_sole_frame: l_sole}", "old_sim.yaml", "sim",
                                "old_sim.yaml: sim.left_sole_frame: removed: the sole frames are "
                                "contact.left_sole_frame");
  // The relaxed OCP's landing height is the IK's pelvis height.
  expectSectionError<TransitionOcpConfig>(
      "ocp: {terminal_pelvis_height: 1.0}", "o.yaml", "ocp",
      "ocp.terminal_pelvis_height: removed: the relaxed landing height is "
      "kinematic_feasibility.pelvis_height");
  const FootstepPlannerConfig shipped =
      FootstepPlannerConfig::fromYaml(YamlSection::loadFile(kRepo + "/config/biped.yaml"));
  EXPECT_EQ(shipped.ocp.terminal_pelvis_height, shipped.kinematics.pelvis_height);
  const FootstepPlannerConfig lowered = FootstepPlannerConfig::fromYaml(
      YamlSection::loadString("kinematic_feasibility: {pelvis_height: 0.98}", "k.yaml"));
  EXPECT_EQ(lowered.ocp.terminal_pelvis_height, 0.98);
}
