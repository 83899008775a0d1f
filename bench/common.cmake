# Included by the benchmark projects under bench/ (each a CMake project of its own, so the
# product never links the reference it is compared with): Release by default, C++17, REACH_REPO
# (the repository root), reach_bench_require_core() and reach_bench_target().
if(NOT CMAKE_BUILD_TYPE)
  set(CMAKE_BUILD_TYPE Release CACHE STRING "Build type" FORCE)
endif()
set(CMAKE_CXX_STANDARD 17)
set(CMAKE_CXX_STANDARD_REQUIRED ON)
get_filename_component(REACH_REPO "${CMAKE_CURRENT_LIST_DIR}/.." ABSOLUTE)

# REACH_CORE_LIBRARY: the catkin-built libreach_trajopt_core.so (a cache path the bench script
# passes); an error naming scripts/build when it does not exist.
macro(reach_bench_require_core)
  set(REACH_CORE_LIBRARY "" CACHE FILEPATH "the catkin-built libreach_trajopt_core.so")
  if(NOT EXISTS "${REACH_CORE_LIBRARY}")
    message(FATAL_ERROR "REACH_CORE_LIBRARY='${REACH_CORE_LIBRARY}' does not exist: build the "
                        "package first (scripts/build) and pass its "
                        "devel/lib/libreach_trajopt_core.so")
  endif()
endmacro()

# The project's headers (include/) and warnings for `target`; with CORE <library>, that library
# linked and its directory in the build rpath (its own dependencies, KDL, urdfdom, ROS from /usr,
# are found through its DT_NEEDED entries).
function(reach_bench_target target)
  cmake_parse_arguments(ARG "" "CORE" "" ${ARGN})
  target_include_directories(${target} PRIVATE "${REACH_REPO}/include")
  target_compile_options(${target} PRIVATE -Wall -Wextra)
  if(ARG_CORE)
    target_link_libraries(${target} PRIVATE "${ARG_CORE}")
    get_filename_component(_core_dir "${ARG_CORE}" DIRECTORY)
    set_target_properties(${target} PROPERTIES BUILD_RPATH "${_core_dir}")
  endif()
endfunction()
