"""The house's structure, checked from the sources (no build needed):

- the areas of the core library (include/reach_trajopt/<area>/, src/<area>/) include each other
  without a cycle, and only downstream in the order data flows through them (DESIGN.md, "Areas
  of the core library"): an area may include the areas listed before it, never one after it;
- no core header or source includes ROS (roscpp, tf2_ros, message headers, reach_trajopt/ros/,
  or the package's generated message headers).

The checker is tested on small made-up graphs too, so that it cannot pass by accident.
"""

import re
from pathlib import Path

import pytest

from conftest import REPO

# The core's areas in the order data flows through them; `ros` (src/ros/, the only ROS-aware
# library code) sits above all of them and is not part of the core.
AREA_ORDER = ["common", "model", "qp", "contact", "planner", "reach", "ocp", "control", "sim",
              "step", "walk"]
ROS_AREA = "ros"

_PROJECT_INCLUDE = re.compile(r'^\s*#\s*include\s*[<"]reach_trajopt/([a-z_]+)/', re.M)
_ANY_INCLUDE = re.compile(r'^\s*#\s*include\s*[<"]([^>"]+)[>"]', re.M)
# ROS headers: roscpp and friends, message packages, and the package's own generated messages
# (reach_trajopt/CamelCase.h, reach_trajopt/CamelCaseAction.h, ...).
_ROS_HEADER = re.compile(
    r"^(ros/|rosbag/|tf2_ros/|tf2_msgs/|actionlib/|actionlib_msgs/|std_msgs/|std_srvs/|"
    r"geometry_msgs/|sensor_msgs/|visualization_msgs/|rosgraph_msgs/|nav_msgs/|"
    r"reach_trajopt/ros/|reach_trajopt/[A-Z][A-Za-z0-9]*\.h$)")


def area_files(repo, area):
    """Every header and source of `area`."""
    files = []
    for root in (repo / "include" / "reach_trajopt" / area, repo / "src" / area):
        if root.is_dir():
            files += sorted(p for p in root.rglob("*") if p.suffix in (".h", ".hpp", ".cpp"))
    return files


def areas_on_disk(repo):
    """The area folders under include/reach_trajopt/ and src/."""
    found = set()
    for root in (repo / "include" / "reach_trajopt", repo / "src"):
        found |= {p.name for p in root.iterdir() if p.is_dir()}
    return found


def include_graph(repo, areas):
    """area -> {included area: first file that includes it}, other areas only."""
    graph = {}
    for area in areas:
        edges = {}
        for path in area_files(repo, area):
            for other in _PROJECT_INCLUDE.findall(path.read_text(errors="replace")):
                if other != area:
                    edges.setdefault(other, path.relative_to(repo))
        graph[area] = edges
    return graph


def find_cycle(graph):
    """A list of areas forming a cycle (first == last), or None."""
    state = {}

    def visit(node, stack):
        state[node] = "open"
        stack.append(node)
        for nxt in sorted(graph.get(node, {})):
            if state.get(nxt) == "open":
                return stack[stack.index(nxt):] + [nxt]
            if nxt not in state:
                cycle = visit(nxt, stack)
                if cycle:
                    return cycle
        stack.pop()
        state[node] = "done"
        return None

    for node in sorted(graph):
        if node not in state:
            cycle = visit(node, [])
            if cycle:
                return cycle
    return None


def upstream_violations(graph, order):
    """Edges from an area to one listed after it in `order` (or not listed at all)."""
    rank = {a: i for i, a in enumerate(order)}
    bad = []
    for area, edges in sorted(graph.items()):
        for other, where in sorted(edges.items()):
            if other not in rank or rank[other] >= rank.get(area, -1):
                bad.append(f"{area} -> {other} ({where})")
    return bad


def ros_includes(repo, areas):
    """(file, header) of every ROS header included by the core."""
    found = []
    for area in areas:
        for path in area_files(repo, area):
            for header in _ANY_INCLUDE.findall(path.read_text(errors="replace")):
                if _ROS_HEADER.match(header):
                    found.append((str(path.relative_to(repo)), header))
    return found


def test_every_area_is_known():
    unknown = areas_on_disk(REPO) - set(AREA_ORDER) - {ROS_AREA}
    assert not unknown, (f"areas {sorted(unknown)} are not in AREA_ORDER of this test: add them "
                         "where data flows through them (and to DESIGN.md's table)")


def test_core_areas_include_only_upstream_and_without_cycle():
    graph = include_graph(REPO, AREA_ORDER)
    assert find_cycle(graph) is None, f"include cycle between areas: {find_cycle(graph)}"
    assert upstream_violations(graph, AREA_ORDER) == []


def test_ros_layer_is_above_the_core():
    graph = include_graph(REPO, [ROS_AREA])
    assert set(graph[ROS_AREA]) <= set(AREA_ORDER)


def test_no_core_file_includes_ros():
    assert ros_includes(REPO, AREA_ORDER) == []


# --- the checker itself, on graphs whose answer is known ---

def test_checker_finds_a_cycle_and_an_upstream_edge():
    graph = {"a": {"b": "x"}, "b": {"c": "y"}, "c": {"a": "z"}}
    assert find_cycle(graph) == ["a", "b", "c", "a"]
    assert find_cycle({"a": {"b": "x"}, "b": {}, "c": {"a": "z", "b": "w"}}) is None
    assert upstream_violations({"b": {"a": "f"}, "a": {}}, ["a", "b"]) == []
    assert upstream_violations({"a": {"b": "f"}, "b": {}}, ["a", "b"]) == ["a -> b (f)"]


@pytest.mark.parametrize("header,is_ros", [
    ("ros/ros.h", True), ("tf2_ros/transform_broadcaster.h", True),
    ("reach_trajopt/CheckFootstep.h", True), ("reach_trajopt/ros/conversions.h", True),
    ("visualization_msgs/MarkerArray.h", True), ("reach_trajopt/reach/forward_step.h", False),
    ("Eigen/Core", False), ("kdl/tree.hpp", False), ("urdf_model/model.h", False),
])
def test_checker_tells_ros_headers(header, is_ros):
    assert bool(_ROS_HEADER.match(header)) == is_ros


def test_checker_sees_a_ros_include_in_a_core_file(tmp_path):
    (tmp_path / "include" / "reach_trajopt" / "model").mkdir(parents=True)
    (tmp_path / "src" / "model").mkdir(parents=True)
    (tmp_path / "src" / "model" / "a.cpp").write_text('#include "reach_trajopt/model/a.h"\n'
                                                      "#include <ros/ros.h>\n")
    assert ros_includes(tmp_path, ["model"]) == [("src/model/a.cpp", "ros/ros.h")]
