#pragma once
/// \file contact_config.h
/// Contact parameters of the biped: friction coefficient and sole size of the contact wrench
/// cone (eq. 7-8), the names of the sole frames whose constraints are eq. (5), and how far
/// apart the legs stay along a swing (a state constraint of eq. 4).

#include <string>

#include "reach_trajopt/contact/contact_mode.h"

namespace reach_trajopt {

class YamlSection;
template <typename Config>
class ConfigFields;

/// Rectangular-sole contact parameters. Defaults: a Valkyrie-like sole (docs/method.md).
struct ContactConfig {
  double mu = 0.7;                          ///< friction coefficient, > 0
  double half_length = 0.135;               ///< X: sole half-length along the sole's x axis [m]
  double half_width = 0.08;                 ///< Y: sole half-width along the sole's y axis [m]
  std::string left_sole_frame = "l_sole";   ///< frame at the left sole centre, z out of the sole
  std::string right_sole_frame = "r_sole";  ///< frame at the right sole centre
  /// Swing-path constraint: the legs' collision capsules (model/leg_clearance.h) stay
  /// leg_clearance_margin apart along a swing, or as far apart as at x_0 when closer.
  bool leg_clearance = true;
  /// [m]; 0 already keeps the shapes apart: the capsules overhang them (by 8 mm at the
  /// biped's sole boxes' sides, 6 cm at its thighs' ends). 0.01 m made the forward walk's
  /// swing bulge around the stance foot and land 3 cm short once.
  double leg_clearance_margin = 0.0;

  /// Throws ConfigError with the offending value when mu <= 0, a size <= 0, non-finite values
  /// or empty frame names.
  void validate() const;
  /// The YAML keys of section `contact:` (the member names), their units and meaning.
  static const ConfigFields<ContactConfig>& fields();
  /// Reads fields() from a YAML section (missing keys keep the defaults, unknown keys throw),
  /// then validates.
  static ContactConfig fromYaml(const YamlSection& section);

  /// The leg margin of a swing starting where the legs' capsules are `distance_at_start` apart
  /// [m]: min(leg_clearance_margin, distance_at_start); -inf when leg_clearance is off.
  double legMarginFrom(double distance_at_start) const;

  /// The frame of the sole on `side`.
  const std::string& soleFrame(Side side) const {
    return side == Side::kLeft ? left_sole_frame : right_sole_frame;
  }
};

}  // namespace reach_trajopt
