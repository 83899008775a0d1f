#pragma once
/// \file contact_mode.h
/// A contact mode m_k of the paper's Sec. II: which soles are in rigid contact (eq. 5).
/// The biped's modes are double support (DS), single support on the left sole (SS-L: the left
/// sole is the stance, the right sole swings) and single support on the right sole (SS-R).
/// Flight (no contact) is representable so it can be rejected with a clear message.

#include <string>

#include "reach_trajopt/common/side.h"

namespace reach_trajopt {

/// Which soles are in contact (the index set I_{m_k} of the paper).
struct ContactMode {
  bool left = true;   ///< left sole in contact
  bool right = true;  ///< right sole in contact

  static ContactMode doubleSupport() { return {true, true}; }
  /// Single support on `stance`: that sole in contact, the other swinging.
  static ContactMode singleSupport(Side stance) {
    return {stance == Side::kLeft, stance == Side::kRight};
  }
  bool inContact(Side s) const { return s == Side::kLeft ? left : right; }
  int contactCount() const { return (left ? 1 : 0) + (right ? 1 : 0); }
  bool isDoubleSupport() const { return left && right; }
  bool isSingleSupport() const { return contactCount() == 1; }
  /// The stance sole of a single-support mode; throws ReachError otherwise.
  Side stance() const;
  /// The swing sole of a single-support mode; throws ReachError otherwise.
  Side swing() const { return opposite(stance()); }
  /// "DS", "SS-L", "SS-R" or "flight".
  std::string name() const;
  /// Parses "DS", "SS-L", "SS-R" (as written by name()); throws ReachError otherwise.
  static ContactMode fromName(const std::string& name);

  bool operator==(const ContactMode& o) const { return left == o.left && right == o.right; }
  bool operator!=(const ContactMode& o) const { return !(*this == o); }
};

}  // namespace reach_trajopt
