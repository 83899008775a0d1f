"""The package as a downstream user sees it: the core library links no ROS library, and a
plain CMake project (test/consumer/) finds reach_trajopt through its CMake config, links the
imported target reach_trajopt::reach_trajopt_core and runs.

Needs the workspace's devel space on CMAKE_PREFIX_PATH (scripts/env.sh sources its setup.bash).
"""

import os
import shutil
import subprocess

import pytest

from conftest import BIN, REPO

CORE = BIN.parent / "libreach_trajopt_core.so"


def linked_libraries(path):
    """The libraries `path` links directly (its DT_NEEDED entries)."""
    out = subprocess.run(["readelf", "-d", str(path)], capture_output=True, text=True,
                         check=True).stdout
    return [line.split("[", 1)[1].rstrip("]") for line in out.splitlines() if "(NEEDED)" in line]


def test_core_library_links_no_ros():
    assert CORE.is_file(), f"{CORE} not built"
    libs = linked_libraries(CORE)
    ros = [lib for lib in libs if any(k in lib for k in ("roscpp", "rosconsole", "tf2_ros",
                                                         "roslib", "rostime", "xmlrpcpp"))]
    assert not ros, f"the core library links ROS libraries: {ros}"
    assert any("kdl_parser" in lib for lib in libs), f"expected kdl_parser among {libs}"


def test_downstream_cmake_project_builds_and_runs(tmp_path):
    if not shutil.which("cmake"):
        pytest.fail("cmake not found")
    prefix = os.environ.get("CMAKE_PREFIX_PATH", "")
    assert "devel" in prefix, f"CMAKE_PREFIX_PATH has no devel space: '{prefix}'"
    build = tmp_path / "build"
    cfg = subprocess.run(["cmake", "-S", str(REPO / "test" / "consumer"), "-B", str(build),
                          "-DCMAKE_BUILD_TYPE=Release"], capture_output=True, text=True)
    assert cfg.returncode == 0, cfg.stdout[-3000:] + cfg.stderr[-3000:]
    bld = subprocess.run(["cmake", "--build", str(build), "-j2"], capture_output=True, text=True)
    assert bld.returncode == 0, bld.stdout[-3000:] + bld.stderr[-3000:]
    run = subprocess.run([str(build / "consumer"), str(REPO / "urdf" / "biped.urdf")],
                         capture_output=True, text=True)
    assert run.returncode == 0, run.stderr
    assert run.stdout.startswith("nq=18 nu=12 "), run.stdout
    bad = subprocess.run([str(build / "consumer"), str(tmp_path / "missing.urdf")],
                         capture_output=True, text=True)
    assert bad.returncode == 2 and "missing.urdf" in bad.stderr, bad.stderr
