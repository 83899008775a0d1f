"""push_envelope's --policies: presets separated by ',' or policies by ';' (a policy with parts
has ',' inside), as its --help and docs/walking.md write them. Each policy gets its own BENCH
walk.envelope line, named as WalkingPolicy names it (a preset by its name, anything else
`custom`); the walks are one push of 2 steps, so the lines are cheap."""

import re

import pytest

from conftest import run_tool

GRID = ["--directions", "1", "--magnitudes", "0.2", "--seeds", "1", "--steps", "2", "--jobs", "1"]


def envelope_presets(policies):
    """The preset= names of push_envelope's BENCH lines for --policies `policies`."""
    r = run_tool("push_envelope", "--policies", policies, *GRID)
    assert r.returncode == 0, r.describe()
    lines = [l for l in r.stdout.splitlines() if l.startswith("BENCH walk.envelope ")]
    return [re.search(r" preset=(\S+)", l).group(1) for l in lines]


@pytest.mark.parametrize("policies, presets", [
    ("baseline,unbounded", ["baseline", "unbounded"]),
    ("baseline;unbounded", ["baseline", "unbounded"]),
    ("unbounded", ["unbounded"]),
    ("baseline;unbounded,bounds=on", ["baseline", "baseline"]),
    ("unbounded,check=kinematic,on_fail=clip_to_bounds", ["custom"]),
])
def test_each_policy_of_the_list_gets_its_envelope_line(policies, presets):
    assert envelope_presets(policies) == presets
