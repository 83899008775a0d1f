#pragma once
// The rostests' footstep: SS-L (the left sole held), the right sole to (0.05, -0.2, 0) m in
// 'world', the nodes' default x_0 and swing duration. Every rostest request and action goal
// starts from it.

namespace reach_trajopt {
namespace test {

/// Fills the fields a check_reachability / plan_transition request and their action goals
/// share (header.frame_id, contact_mode, foothold [m]); the rest keeps its message default.
template <typename Msg>
void fillReferenceStep(Msg& m) {
  m.header.frame_id = "world";
  m.contact_mode = "SS-L";
  m.foothold.x = 0.05;
  m.foothold.y = -0.2;
  m.foothold.z = 0.0;
}

}  // namespace test
}  // namespace reach_trajopt
