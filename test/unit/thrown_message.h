#pragma once
// The message of the exception a call throws, for the tests that check what an error says.

#include <gtest/gtest.h>

#include <exception>
#include <string>

namespace reach_trajopt {
namespace test {

/// The message of the E that `f` throws ("" and a test failure when it throws none, or another
/// exception).
template <typename E, typename F>
std::string thrownMessage(F&& f) {
  try {
    f();
  } catch (const E& e) {
    return e.what();
  } catch (const std::exception& e) {
    ADD_FAILURE() << "wrong exception type: " << e.what();
    return "";
  }
  ADD_FAILURE() << "nothing thrown";
  return "";
}

}  // namespace test
}  // namespace reach_trajopt
