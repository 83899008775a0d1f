"""docs/ros_api.md is what scripts/generate_ros_api.py prints from the code (as
test_parameter_table checks docs/parameters.md), and what it prints agrees with an independent
source: every private parameter that launch/walk.launch and multi_machine.launch give a node
is in that node's table, and every topic and service the rostests' launch files remap or
name exists."""

import re
import subprocess
import sys
import xml.etree.ElementTree as ET

from conftest import REPO

GENERATOR = REPO / "scripts" / "generate_ros_api.py"
DOC = REPO / "docs" / "ros_api.md"


def generated():
    run = subprocess.run([sys.executable, str(GENERATOR)], capture_output=True, text=True,
                         timeout=120)
    assert run.returncode == 0, run.stderr
    return run.stdout


def test_checked_in_doc_is_the_generated_one():
    text = generated()
    assert DOC.read_text() == text, (
        "docs/ros_api.md is out of date: regenerate it with scripts/generate_ros_api.py --write")


def table_rows(text, section):
    block = text.split("## " + section, 1)[1].split("\n## ", 1)[0]
    rows = []
    for line in block.splitlines():
        if line.startswith("| `"):
            rows.append([c.strip().strip("`") for c in line.strip("|").split(" | ")])
    return rows


def test_every_launch_file_parameter_is_documented():
    params = {(r[0], r[1]) for r in table_rows(generated(), "Parameters")}
    nodes = {r[0] for r in table_rows(generated(), "Nodes")}
    assert {"sim_node", "reachability_node", "transition_ocp_node", "tvr_planner_node"} <= nodes
    checked = 0
    for launch in sorted((REPO / "launch").glob("*.launch")):
        for node in ET.parse(launch).getroot().iter("node"):
            if node.get("pkg") != "reach_trajopt":
                continue
            for p in node.findall("param"):
                name = p.get("name")
                if name.startswith("/"):
                    continue
                assert (node.get("type"), "~" + name) in params, (
                    "%s: <param name=%s> of %s is not in docs/ros_api.md's table" % (
                        launch.name, name, node.get("type")))
                checked += 1
    assert checked >= 20


def test_services_and_topics_match_the_sources():
    text = generated()
    services = {r[0]: r[1] for r in table_rows(text, "Services")}
    # the service files of the package are all served
    srv_types = {p.stem for p in (REPO / "srv").glob("*.srv")}
    assert srv_types == set(services.values())
    topics = {r[0] for r in table_rows(text, "Topics")}
    # every name the rostests' checkers subscribe to is a documented topic
    for f in (REPO / "test" / "rostest").glob("*.cpp"):
        for name in re.findall(r"subscribe\s*(?:<[^>]*>)?\s*\(\s*\"([\w/]+)\"\s*,", f.read_text()):
            assert name in topics or "/" + name in topics, "%s: %s" % (f.name, name)
