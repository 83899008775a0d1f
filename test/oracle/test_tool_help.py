"""Every command-line tool of nodes/tools/ answers --help (and -h) with its usage and options on
stdout and exit status 0, and an unknown option with an error naming it (exit status 2).

The expected options are the ones the tools' header comments document and the scripts, tests
and benchmarks call (scripts/, test/, bench/): a tool that lost or renamed one fails here."""

import pytest

from conftest import BIN, run_tool

# tool -> the options its --help must list (the documented usage of each tool).
TOOLS = {
    "check_transition": ["--config", "--urdf", "--threshold"],
    "model_info": ["--fixed-base", "--json", "--state", "--frames", "--config"],
    "parameter_table": [],
    "plan_transition": ["--urdf", "--config", "--stride"],
    "push_envelope": ["--config", "--urdf", "--policies", "--directions", "--magnitudes",
                      "--fine", "--seeds", "--steps", "--jobs", "--svg", "--csv"],
    "qp_solve": [],
    "reach_check": ["--config", "--threads", "--samples"],
    "verdict_grid": ["--config", "--urdf", "--requests", "--bench-case", "--grid", "--half-width",
                     "--max-states", "--details", "--reach-config", "--reference-config"],
    "walk_experiment": ["--config", "--urdf", "--policy", "--mode", "--steps", "--seed", "--push",
                        "--forward-speed", "--settle", "--records", "--plan-requests",
                        "--ocp-requests"],
    "wrench_cone": ["--mu", "--half-length", "--half-width", "--rpy"],
}


def test_every_tool_is_listed():
    """A new tool in nodes/tools/ gets a row here (its options checked by the tests below)."""
    built = {p.name for p in BIN.iterdir() if p.is_file() and p.name in TOOLS}
    assert built == set(TOOLS), f"not built: {set(TOOLS) - built}"
    from conftest import REPO
    sources = {p.stem for p in (REPO / "nodes" / "tools").glob("*.cpp")}
    assert sources == set(TOOLS), f"tools without a row: {sources - set(TOOLS)}"


@pytest.mark.parametrize("tool", sorted(TOOLS))
@pytest.mark.parametrize("flag", ["--help", "-h"])
def test_help_prints_usage_and_options(tool, flag):
    run = run_tool(tool, flag, timeout=30)
    assert run.returncode == 0, run.describe()
    assert f"usage: {tool}" in run.stdout, run.describe()
    lines = run.stdout.splitlines()
    for option in TOOLS[tool] + ["--help"]:
        # Each option on an option line of its own (two spaces, the option, ...).
        assert any(line.lstrip().startswith(option) or f", {option}" in line
                   for line in lines), f"--help of {tool} does not list {option}\n" + run.describe()


@pytest.mark.parametrize("tool", sorted(TOOLS))
def test_unknown_option_is_named(tool):
    run = run_tool(tool, "--no-such-option", timeout=30)
    assert run.returncode == 2, run.describe()
    assert "--no-such-option" in run.output, run.describe()
    assert "unknown option" in run.output, run.describe()


@pytest.mark.parametrize("tool,option", [(t, o) for t, opts in sorted(TOOLS.items())
                                         for o in opts if o not in (
                                             "--fixed-base", "--json", "--fine", "--samples",
                                             "--bench-case", "--details")])
def test_option_without_its_value_is_named(tool, option):
    """An option that takes a value, given last without it: an error naming the option."""
    run = run_tool(tool, option, timeout=30)
    assert run.returncode == 2, run.describe()
    assert f"{option}: missing value" in run.output, run.describe()
