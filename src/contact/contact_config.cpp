#include "reach_trajopt/contact/contact_config.h"

#include <cmath>
#include <sstream>

#include "reach_trajopt/common/config_yaml.h"
#include "reach_trajopt/common/error.h"

namespace reach_trajopt {

namespace {
void requirePositive(const char* name, double v) {
  requirePositiveFinite("ContactConfig", name, v);
}
}  // namespace

void ContactConfig::validate() const {
  requirePositive("mu", mu);
  requirePositive("half_length", half_length);
  requirePositive("half_width", half_width);
  if (left_sole_frame.empty() || right_sole_frame.empty()) {
    throw ReachError("ContactConfig: sole frame names must not be empty");
  }
  if (left_sole_frame == right_sole_frame) {
    throw ReachError("ContactConfig: left and right sole frames are both '" + left_sole_frame +
                     "'");
  }
}

ContactConfig ContactConfig::fromYaml(const YamlSection& s) {
  s.requireOnlyKeys({"mu", "half_length", "half_width", "left_sole_frame", "right_sole_frame"});
  ContactConfig c;
  s.read("mu", c.mu);
  s.read("half_length", c.half_length);
  s.read("half_width", c.half_width);
  s.read("left_sole_frame", c.left_sole_frame);
  s.read("right_sole_frame", c.right_sole_frame);
  return validatedIn(s, c);
}

}  // namespace reach_trajopt
