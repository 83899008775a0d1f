# The unit tests' precompiled header, shared by the catkin build (CMakeLists.txt) and the
# sanitized build (test/sanitized/CMakeLists.txt): gtest's and Eigen's headers, parsed once by
# the first test target of a build and reused by the others (about half of a test's compile
# time; make test compiles every test twice). A precompiled header is only valid for the flags
# it was made with (the optimization level among them): targets compiled with other flags name
# another FLAVOR and share a header of their own.
function(reach_unit_test_pch target)
  set(flavor "${ARGV1}")
  get_property(first GLOBAL PROPERTY REACH_FIRST_UNIT_TEST${flavor})
  if(first)
    target_precompile_headers(${target} REUSE_FROM ${first})
  else()
    target_precompile_headers(${target} PRIVATE <gtest/gtest.h> <Eigen/Dense>)
    set_property(GLOBAL PROPERTY REACH_FIRST_UNIT_TEST${flavor} ${target})
  endif()
endfunction()
