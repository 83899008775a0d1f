#pragma once
// The serialized bytes of a ROS message: two messages are the same when their bytes are (the
// rostests compare what the nodes publish with what the in-process walk or check gives).

#include <ros/serialization.h>

#include <cstdint>
#include <vector>

namespace reach_trajopt {
namespace test {

/// `m` serialized as ROS sends it.
template <typename M>
std::vector<uint8_t> bytes(const M& m) {
  const uint32_t n = ros::serialization::serializationLength(m);
  std::vector<uint8_t> b(n);
  ros::serialization::OStream s(b.data(), n);
  ros::serialization::serialize(s, m);
  return b;
}

}  // namespace test
}  // namespace reach_trajopt
