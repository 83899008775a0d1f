#include "reach_trajopt/contact/contact_config.h"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "reach_trajopt/common/config_fields.h"
#include "reach_trajopt/common/error.h"
#include "reach_trajopt/contact/contact_wrench_cone.h"

namespace reach_trajopt {

void ContactConfig::validate() const {
  fields().checkRanges(*this);
  if (left_sole_frame.empty() || right_sole_frame.empty()) {
    throw ConfigError("ContactConfig: sole frame names must not be empty");
  }
  if (left_sole_frame == right_sole_frame) {
    throw ConfigError("ContactConfig: left and right sole frames are both '" + left_sole_frame +
                      "'");
  }
}

const ConfigFields<ContactConfig>& ContactConfig::fields() {
  using C = ContactConfig;
  static const ConfigFields<C> f =
      ConfigFields<C>("ContactConfig", "contact", "include/reach_trajopt/contact/contact_config.h",
                      "Contact wrench cone (eq. 7-8) and the sole frames of the contact "
                      "constraints (eq. 5); the only place the sole frames are named.")
          .add("mu", &C::mu, "", Range::positiveAtMost(ContactWrenchCone::kMaxFriction),
               "friction coefficient")
          .add("half_length", &C::half_length, "m",
               Range::positiveAtMost(ContactWrenchCone::kMaxSoleHalfSize),
               "X: sole half-length along its x axis")
          .add("half_width", &C::half_width, "m",
               Range::positiveAtMost(ContactWrenchCone::kMaxSoleHalfSize),
               "Y: sole half-width along its y axis")
          .add("left_sole_frame", &C::left_sole_frame, "",
               "frame at the left sole centre, z out of the sole")
          .add("right_sole_frame", &C::right_sole_frame, "",
               "frame at the right sole centre (not the left one)")
          .add("leg_clearance", &C::leg_clearance, "",
               "a swing keeps the legs' collision capsules (model/leg_clearance.h) "
               "leg_clearance_margin apart: in the reachable sets' samples, the certificates' "
               "and the OCP's 1 ms re-checks and the OCP's constraint grid (eq. 4's h_state)")
          .add("leg_clearance_margin", &C::leg_clearance_margin, "m", Range::nonNegative(),
               "smallest distance between a left-leg and a right-leg capsule along a swing "
               "(or the distance at x_0 when smaller)");
  return f;
}

double ContactConfig::legMarginFrom(double distance_at_start) const {
  if (!leg_clearance) return -HUGE_VAL;
  return std::min(leg_clearance_margin, distance_at_start);
}

ContactConfig ContactConfig::fromYaml(const YamlSection& s) { return fields().read(s); }

}  // namespace reach_trajopt
