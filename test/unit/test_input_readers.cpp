// The strict input readers of issue 17: JsonReader (key paths, sizes, finiteness, unknown keys),
// the request readers built on it, strict CLI numbers, YAML duplicate keys and unknown sections,
// and the URDF validation (loops, roots, axes, masses, inertias, numbers). Each bad input must
// throw a ReachError whose message names the key, option, link or joint.

#include <gtest/gtest.h>

#include <cstdio>
#include <fstream>
#include <string>

#include "reach_trajopt/common/cli_args.h"
#include "reach_trajopt/common/config_yaml.h"
#include "reach_trajopt/common/json_reader.h"
#include "reach_trajopt/common/state_json.h"
#include "reach_trajopt/model/robot_model.h"
#include "reach_trajopt/ocp/transition_request_json.h"
#include "reach_trajopt/qp/qp_problem_json.h"
#include "reach_trajopt/reach/reach_config.h"
#include "reach_trajopt/reach/reach_request_json.h"
#include "thrown_message.h"

using namespace reach_trajopt;

namespace {

/// The message of the ReachError `f` throws ("" and a test failure when it throws none).
template <typename F>
std::string errorOf(F&& f) {
  return test::thrownMessage<ReachError>(f);
}

#define EXPECT_ERROR_NAMES(expr, word)                                                    \
  do {                                                                                    \
    const std::string msg_ = errorOf([&] { (void)(expr); });                              \
    EXPECT_NE(msg_.find(word), std::string::npos) << "'" << word << "' not in: " << msg_; \
  } while (0)

nlohmann::json J(const std::string& text) { return JsonReader::parse(text, "t.json"); }

const char* kTwoLinks = R"(<robot name="two"><link name="world"/>
  <link name="upper"><inertial><mass value="1.0"/>
    <inertia ixx="0.01" ixy="0" ixz="0" iyy="0.01" iyz="0" izz="0.01"/></inertial></link>
  <joint name="shoulder" type="revolute"><parent link="world"/><child link="upper"/>
    <axis xyz="0 0 1"/><limit lower="-1" upper="1" effort="10" velocity="2"/></joint></robot>)";

std::string twoLinksWith(const std::string& from, const std::string& to) {
  std::string s = kTwoLinks;
  const auto at = s.find(from);
  EXPECT_NE(at, std::string::npos) << from;
  if (at != std::string::npos) s.replace(at, from.size(), to);
  return s;
}

std::shared_ptr<const RobotModel> load(const std::string& xml) {
  return RobotModel::fromUrdfString(xml, ModelOptions{}, "t.urdf");
}

}  // namespace

TEST(JsonReader, NamesKeyPathAndShape) {
  const auto doc = J(R"({"swing": {"velocity": [], "position": [1, 2, "x"]}, "n": 1.5})");
  const JsonReader r(doc, "t.json");
  EXPECT_ERROR_NAMES(r.at("swing").vector("velocity", 3),
                     "t.json: swing.velocity: expected 3 numbers, got 0");
  EXPECT_ERROR_NAMES(r.at("swing").vector("position", 3), "swing.position[2]: expected a number");
  EXPECT_ERROR_NAMES(r.at("swing").requireOnlyKeys({"velocity"}), "swing.position: unknown key");
  EXPECT_ERROR_NAMES(r.at("missing"), "missing: missing key");
  EXPECT_ERROR_NAMES(r.at("n").integer(0, 10), "n: expected an integer");
  EXPECT_EQ(r.at("n").number(), 1.5);
}

TEST(JsonReader, RejectsOverflowAndNonFinite) {
  EXPECT_ERROR_NAMES(J(R"({"G": [[1e400]]})"), "1e400");
  EXPECT_ERROR_NAMES(J("{not json"), "not valid JSON");
  const auto doc = J(R"({"v": ["nan", "inf"], "w": [1, null]})");
  const JsonReader r(doc, "t.json");
  EXPECT_ERROR_NAMES(r.at("v").vector(2), "v[0]");
  const Eigen::VectorXd v = r.at("v").vector(2, NonFinite::kAllow);
  EXPECT_TRUE(std::isnan(v[0]));
  EXPECT_TRUE(std::isinf(v[1]));
  EXPECT_ERROR_NAMES(r.at("w").vector(2), "w[1]");
}

TEST(JsonReader, MatrixRowsMustAgree) {
  const auto doc = J(R"({"A": [[1, 2], [3]]})");
  EXPECT_ERROR_NAMES(JsonReader(doc, "t.json").at("A").matrix(-1, -1), "row 1 has 1 entries");
}

TEST(RequestReaders, QpProblemSizes) {
  EXPECT_ERROR_NAMES(qp::readQpProblem(JsonReader(J(R"({"G": [[1]], "g": [1, 2]})"), "t")),
                     "G: expected 2 rows");
  EXPECT_ERROR_NAMES(
      qp::readQpProblem(JsonReader(J(R"({"G": [[1]], "g": [1], "Aeq": [[1]]})"), "t")),
      "beq: missing key");
  EXPECT_ERROR_NAMES(
      qp::readQpProblem(JsonReader(J(R"({"G": [[1]], "g": [1], "Ain": [[1]], "bin": [0],
                               "warm_start": [3]})"),
                                   "t")),
      "warm_start");
  const auto p = qp::readQpProblem(
      JsonReader(J(R"({"G": [[2]], "g": [1], "bin": [], "options": {"max_iterations": 5}})"), "t"));
  EXPECT_EQ(p.config.max_iterations, 5);
  EXPECT_EQ(p.Ain.rows(), 0);
  EXPECT_EQ(p.Ain.cols(), 1);
}

TEST(RequestReaders, ReachCheckRequest) {
  const std::string base =
      R"("mode": "SS-L", "stance": {"position": [0, 0.1, 0]}, "target": {"position": [0.1, -0.1, 0]})";
  auto read = [&](const std::string& rest) {
    return readReachCheckRequest(JsonReader(J("{" + base + rest + "}"), "r.json"), 18, {});
  };
  EXPECT_ERROR_NAMES(read(R"(, "swing": {"position": [0, 0, 0], "velocity": []})"),
                     "swing.velocity: expected 3 numbers, got 0");
  EXPECT_ERROR_NAMES(read(R"(, "swing": {"position": [0, 0], "velocity": [0, 0, 0]})"),
                     "swing.position: expected 3 numbers, got 2");
  EXPECT_ERROR_NAMES(read(R"(, "x0": {"q": [0,0,0,0,0,0,0,0,0,0], "qd": []})"),
                     "x0.q: expected 18 numbers, got 10");
  EXPECT_ERROR_NAMES(read(R"(, "xF": {}, "swing": {"position": [0,0,0], "velocity": [0,0,0]})"),
                     "xF: unknown key");
  EXPECT_ERROR_NAMES(read(R"(, "swing": {"position": [0,0,0], "velocity": [0,0,0]},
                              "config": {"budgets": {"full": {"initial_samples": 10000000}}})"),
                     "budgets.full.initial_samples");
  const ReachCheckRequest ok = read(R"(, "swing": {"position": [0,0,0], "velocity": [0.1,0,0]})");
  EXPECT_FALSE(ok.has_x0);
  EXPECT_DOUBLE_EQ(ok.swing_velocity.x(), 0.1);
}

TEST(RequestReaders, TransitionRequest) {
  std::string q = "[0.0";
  for (int i = 1; i < 18; ++i) q += ", 0.0";
  q += "]";
  auto read = [&](const std::string& horizon, const std::string& rest) {
    return readTransitionRequest(
        JsonReader(J(R"({"stance": "left", "stance_pose": {"position": [0, 0.1, 0]},
                         "swing_target": {"position": [0.2, -0.1, 0]}, "q0": )" +
                     q + R"(, "horizon": )" + horizon + rest + "}"),
                   "p.json"),
        18);
  };
  EXPECT_ERROR_NAMES(read("1000", ""), "horizon: expected a swing duration in (0, 5] s");
  EXPECT_ERROR_NAMES(read("\"abc\"", ""), "horizon: expected a number");
  EXPECT_ERROR_NAMES(read("0.4", R"(, "qdf": [])"), "qdf: given without");
  EXPECT_ERROR_NAMES(read("0.4", R"(, "slices": [{"time": 0.1, "A": [[1, 0, 0]], "b": [1]}])"),
                     "slices[0].A");
  EXPECT_FALSE(read("0.4", "").has_qf);
}

TEST(RequestReaders, States) {
  EXPECT_ERROR_NAMES(readStates(JsonReader(J(R"({"states": []})"), "s.json"), 2), "states");
  EXPECT_ERROR_NAMES(
      readStates(JsonReader(J(R"({"states": [{"q": [0, 0], "qd": [0]}]})"), "s.json"), 2),
      "s.json: states[0].qd: expected 2 numbers, got 1");
  EXPECT_EQ(readStates(JsonReader(J(R"({"q": [0, 1], "qd": [2, 3]})"), "s.json"), 2).size(), 1u);
}

TEST(CliArgs, WholeTextInRange) {
  EXPECT_ERROR_NAMES(parseIntOption("--steps", "5x", 0, 100), "--steps");
  EXPECT_ERROR_NAMES(parseIntOption("--steps", "", 0, 100), "--steps");
  EXPECT_ERROR_NAMES(parseIntOption("--steps", "99999999999999999999", 0, 100), "--steps");
  EXPECT_ERROR_NAMES(parseIntOption("--steps", "101", 0, 100), "[0, 100]");
  EXPECT_EQ(parseIntOption("--steps", "-3", -5, 5), -3);
  EXPECT_ERROR_NAMES(parseDoubleOption("--mu", "0.7x"), "--mu");
  EXPECT_ERROR_NAMES(parseDoubleOption("--mu", "nan"), "--mu");
  EXPECT_ERROR_NAMES(parseDoubleOption("--mu", "1e999"), "--mu");
  EXPECT_DOUBLE_EQ(parseDoubleOption("--mu", "0.7"), 0.7);
  EXPECT_ERROR_NAMES(parseThreadsOption("--threads", "100000"), "--threads");
  EXPECT_EQ(parseThreadsOption("--threads", "1"), 1);
  // The configs' `threads` keys share one rule and one message with the option.
  EXPECT_EQ(threadsBeyondHardware(0), "");
  EXPECT_EQ(threadsBeyondHardware(hardwareThreads()), "");
  EXPECT_NE(threadsBeyondHardware(hardwareThreads() + 1)
                .find("hardware threads of this machine (0: OpenMP's default), got " +
                      std::to_string(hardwareThreads() + 1)),
            std::string::npos);
}

TEST(YamlConfig, DuplicateKeysAndUnknownSections) {
  EXPECT_ERROR_NAMES(YamlSection::loadString("reach:\n  dt: 0.001\n  dt: 0.002\n", "d.yaml"),
                     "d.yaml: reach.dt: duplicate key (line 3)");
  EXPECT_ERROR_NAMES(YamlSection::loadString("a: 1\na: 2\n", "d.yaml"), "d.yaml: a: duplicate");
  EXPECT_ERROR_NAMES(YamlSection::loadString("x: {y: 1, y: 2}\n", "d.yaml"), "x.y: duplicate");
  const std::string path = testing::TempDir() + "/misspelled.yaml";
  std::ofstream(path) << "reahc:\n  dt: 0.001\n";
  EXPECT_ERROR_NAMES(YamlSection::loadFile(path), "reahc: unknown key");
  std::remove(path.c_str());
}

TEST(ReachLimits, BoundsThreadsAndEstimates) {
  ReachConfig c;
  c.budgets.full.initial_samples = 10000000;
  EXPECT_ERROR_NAMES(c.validate(), "initial_samples");
  c = ReachConfig();
  c.threads = 100000;
  EXPECT_ERROR_NAMES(c.validate(), "threads");
  c = ReachConfig();
  c.horizon = 1000.0;
  EXPECT_ERROR_NAMES(c.validate(), "horizon");
  c = ReachConfig();
  c.horizon = 1e-300;
  c.window_start = c.window_end = 0.0;
  EXPECT_ERROR_NAMES(c.validate(), "at least one time step");
  c = ReachConfig();
  c.budgets.full.max_boundary = 5000;
  c.budgets.full.children_per_parent = 500;
  c.validate();
  EXPECT_ERROR_NAMES(c.requireResourcesWithinLimits(18), "QPs");
  c = ReachConfig();
  c.budgets.full.initial_samples = 100000;
  EXPECT_ERROR_NAMES(c.requireResourcesWithinLimits(2000), "MiB");  // a 2000-dof robot
  ReachConfig shipped;  // the defaults are the paper's: well inside the limits
  EXPECT_NO_THROW(shipped.requireResourcesWithinLimits(18));
  EXPECT_LT(shipped.estimatedMemoryBytes(18), ReachLimits::kMaxMemoryBytes / 4);
}

TEST(UrdfValidation, StructureAndNumbers) {
  EXPECT_NO_THROW(load(kTwoLinks));
  EXPECT_ERROR_NAMES(load(twoLinksWith("</robot>", R"(<link name="b"/><joint name="loop"
      type="fixed"><parent link="upper"/><child link="b"/></joint><joint name="back" type="fixed">
      <parent link="b"/><child link="upper"/></joint></robot>)")),
                     "link 'upper' of t.urdf is the child of two joints");
  EXPECT_ERROR_NAMES(load(R"(<robot name="r"><link name="a"/><link name="b"/><link name="c"/>
      <joint name="bc" type="fixed"><parent link="b"/><child link="c"/></joint>
      <joint name="cb" type="fixed"><parent link="c"/><child link="b"/></joint></robot>)"),
                     "form a loop");
  EXPECT_ERROR_NAMES(load(twoLinksWith("</robot>", R"(<link name="other"/></robot>)")),
                     "2 root links");
  EXPECT_ERROR_NAMES(load(twoLinksWith(R"(<mass value="1.0"/>)", R"(<mass value="1.0kg"/>)")),
                     "link 'upper'");
  EXPECT_ERROR_NAMES(load(twoLinksWith(R"(lower="-1")", R"(lower="-1e999")")), "joint 'shoulder'");
  EXPECT_ERROR_NAMES(load(twoLinksWith(R"(<axis xyz="0 0 1"/>)", R"(<axis xyz="0 0"/>)")),
                     "expected 3 numbers");
  EXPECT_ERROR_NAMES(load(twoLinksWith("<link name=\"upper\">", "<link name=\"world\">")),
                     "defined twice");
}

TEST(UrdfValidation, AxesMassesInertias) {
  EXPECT_ERROR_NAMES(load(twoLinksWith(R"(<axis xyz="0 0 1"/>)", R"(<axis xyz="0 0 0"/>)")),
                     "joint 'shoulder'");
  // A non-unit axis is normalized (as urdfdom and Pinocchio do), not an error.
  const auto scaled = load(twoLinksWith(R"(<axis xyz="0 0 1"/>)", R"(<axis xyz="0 0 3"/>)"));
  const auto unit = load(kTwoLinks);
  Workspace a(*scaled), b(*unit);
  const Eigen::VectorXd q = Eigen::VectorXd::Constant(1, 0.3), qd = q;
  scaled->update(a, q, qd);
  unit->update(b, q, qd);
  Eigen::MatrixXd Ma(1, 1), Mb(1, 1);
  scaled->massMatrix(a, Ma);
  unit->massMatrix(b, Mb);
  EXPECT_NEAR(Ma(0, 0), Mb(0, 0), 1e-12);
  EXPECT_ERROR_NAMES(load(twoLinksWith(R"(<mass value="1.0"/>)", R"(<mass value="-1"/>)")),
                     "negative mass");
  EXPECT_ERROR_NAMES(load(twoLinksWith(R"(<mass value="1.0"/>)", R"(<mass value="0"/>)")),
                     "massless link must have zero inertia");
  EXPECT_ERROR_NAMES(load(twoLinksWith(R"(ixx="0.01")", R"(ixx="-0.01")")),
                     "not positive semidefinite");
  EXPECT_ERROR_NAMES(load(twoLinksWith(R"(izz="0.01")", R"(izz="0.1")")), "triangle inequality");
  // Massless links with zero inertia are legal (sensor frames of real robots).
  EXPECT_NO_THROW(load(twoLinksWith(R"(<mass value="1.0"/>
    <inertia ixx="0.01" ixy="0" ixz="0" iyy="0.01" iyz="0" izz="0.01"/>)",
                                    R"(<mass value="0"/>
    <inertia ixx="0" ixy="0" ixz="0" iyy="0" iyz="0" izz="0"/>)")));
}
