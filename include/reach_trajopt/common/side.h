#pragma once
/// \file side.h
/// The two sides of a legged robot (its left and right sole, leg, ...). Below both `model`
/// (robot_config.h names each leg's joints by side) and `contact` (a contact mode holds soles
/// by side), so neither area includes the other for it.

namespace reach_trajopt {

/// A side of the robot: its left or right sole (leg).
enum class Side { kLeft = 0, kRight = 1 };

/// The other side.
inline Side opposite(Side s) { return s == Side::kLeft ? Side::kRight : Side::kLeft; }
/// "left" / "right".
inline const char* sideName(Side s) { return s == Side::kLeft ? "left" : "right"; }

}  // namespace reach_trajopt
