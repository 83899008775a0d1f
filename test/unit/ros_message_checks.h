#pragma once
// Checks shared by the ROS layer's message conversion tests (test_ros_*_msgs.cpp): a value that
// came back through a message has the same bits, and a malformed request is rejected with a
// RequestError naming its field.

#include <gtest/gtest.h>

#include <Eigen/Core>
#include <algorithm>
#include <functional>
#include <random>
#include <string>

#include "reach_trajopt/common/error.h"

namespace reach_trajopt {
namespace test {

/// Same sizes and every double bit for bit (a float32 or a printed decimal would not be).
inline bool sameBits(const Eigen::MatrixXd& a, const Eigen::MatrixXd& b) {
  return a.rows() == b.rows() && a.cols() == b.cols() &&
         std::equal(a.data(), a.data() + a.size(), b.data());
}

/// n numbers with every bit of the mantissa in use (a float32 or a printed decimal would lose
/// some), the same for the same seed.
inline Eigen::VectorXd awkward(int n, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  Eigen::VectorXd v(n);
  for (int i = 0; i < n; ++i) v[i] = u(rng) / 3.0;
  return v;
}

/// `f` throws a RequestError whose message names `field`.
inline void expectRejected(const std::function<void()>& f, const std::string& field) {
  try {
    f();
    ADD_FAILURE() << "accepted; expected a rejection naming " << field;
  } catch (const RequestError& e) {
    EXPECT_NE(std::string(e.what()).find(field), std::string::npos) << e.what();
  }
}

}  // namespace test
}  // namespace reach_trajopt
