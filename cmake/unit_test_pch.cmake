# The unit tests' precompiled header, shared by the catkin build (CMakeLists.txt) and the
# sanitized build (test/sanitized/CMakeLists.txt): gtest's and Eigen's headers, parsed once by
# the first test target of a build and reused by the others (about half of a test's compile
# time; make test compiles every test twice).
function(reach_unit_test_pch target)
  get_property(first GLOBAL PROPERTY REACH_FIRST_UNIT_TEST)
  if(first)
    target_precompile_headers(${target} REUSE_FROM ${first})
  else()
    target_precompile_headers(${target} PRIVATE <gtest/gtest.h> <Eigen/Dense>)
    set_property(GLOBAL PROPERTY REACH_FIRST_UNIT_TEST ${target})
  endif()
endfunction()
