/// \file reach_request_json.cpp
/// Strict reading of reach_check requests (reach_request_json.h).

#include "reach_trajopt/reach/reach_request_json.h"

#include "reach_trajopt/common/config_yaml.h"

namespace reach_trajopt {

FlatContact readFoothold(const JsonReader& r) {
  r.requireObject("{\"position\": [x, y, z], \"yaw\": rad}");
  r.requireOnlyKeys({"position", "yaw"});
  FlatContact c;
  c.position = r.vector("position", 3);
  r.optionalNumber("yaw", c.yaw);
  return c;
}

namespace {

void readState(const JsonReader& r, int nq, Eigen::VectorXd& q, Eigen::VectorXd& qd) {
  r.requireObject("{\"q\": [n_q numbers], \"qd\": [n_q numbers]}");
  r.requireOnlyKeys({"q", "qd"});
  q = r.vector("q", nq);
  qd = r.vector("qd", nq);
}

}  // namespace

ReachCheckRequest readReachCheckRequest(const JsonReader& r, int nq,
                                        const ReachConfig& base_config) {
  r.requireObject("a request object");
  r.requireOnlyKeys({"mode", "x0", "swing", "stance", "target", "xf", "config"});
  ReachCheckRequest q;
  r.optionalChoice("mode", {"SS-L", "SS-R", "none"}, q.mode);
  const bool contacts = q.mode != "none";
  if (contacts) {
    q.stance = readFoothold(r.at("stance"));
    q.target = readFoothold(r.at("target"));
  } else {
    for (const char* key : {"stance", "target", "swing"})
      if (r.has(key)) r.at(key).fail("not used with mode none (fixed base, no contacts)");
  }
  if (r.has("x0") && r.has("swing")) r.fail("give either x0 or swing, not both");
  if (r.has("x0")) {
    q.has_x0 = true;
    readState(r.at("x0"), nq, q.q0, q.qd0);
  } else if (r.has("swing")) {
    const JsonReader s = r.at("swing");
    s.requireObject("{\"position\": [x, y, z], \"velocity\": [vx, vy, vz], ...}");
    s.requireOnlyKeys({"position", "velocity", "yaw", "q_init"});
    q.swing_position = s.vector("position", 3);
    q.swing_velocity = s.vector("velocity", 3);
    s.optionalNumber("yaw", q.swing_yaw);
    s.optionalVector("q_init", nq, q.q_init);
  } else {
    r.fail(contacts ? "needs \"x0\" or \"swing\"" : "needs \"x0\"");
  }
  if (r.has("xf")) {
    q.has_xf = true;
    readState(r.at("xf"), nq, q.qf, q.qdf);
  } else if (!contacts) {
    r.fail("mode none needs \"xf\"");
  }
  q.config = base_config;
  if (r.has("config")) {
    const JsonReader c = r.at("config");
    c.requireObject("an object of reach: keys");
    // JSON is YAML: the config keys go through ReachConfig's strict reader.
    q.config =
        ReachConfig::fromYaml(YamlSection::loadString(c.value().dump(), c.where()), base_config);
  }
  return q;
}

}  // namespace reach_trajopt
