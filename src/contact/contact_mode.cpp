#include "reach_trajopt/contact/contact_mode.h"

#include "reach_trajopt/common/error.h"

namespace reach_trajopt {

Side ContactMode::stance() const {
  if (!isSingleSupport()) throw ReachError("contact mode " + name() + " has no single stance sole");
  return left ? Side::kLeft : Side::kRight;
}

std::string ContactMode::name() const {
  if (left && right) return "DS";
  if (left) return "SS-L";
  if (right) return "SS-R";
  return "flight";
}

ContactMode ContactMode::fromName(const std::string& name) {
  if (name == "DS") return doubleSupport();
  if (name == "SS-L") return singleSupport(Side::kLeft);
  if (name == "SS-R") return singleSupport(Side::kRight);
  throw RequestError("unknown contact mode '" + name + "' (expected DS, SS-L or SS-R)");
}

}  // namespace reach_trajopt
