"""Shared fixtures of the oracle tests (pytest, run with the project venv's python).

Where things are:
  REACH_REPO  repository root (default: two levels above this file)
  REACH_BIN   directory of the built executables (default: $REACH_WS/devel/lib/reach_trajopt,
              REACH_WS defaulting to <repo>/.build_ws, as in scripts/env.sh)
  reference robots: the example-robot-data wheel installed in the running interpreter's
              site-packages (cmeel.prefix/share/example-robot-data/robots/).

A tool that has not been built is a test failure, not a skip: the oracle tests exist to check
the built tools.
"""

import json
import math
import os
import subprocess
import sysconfig
from dataclasses import dataclass
from pathlib import Path

import pytest

REPO = Path(os.environ.get("REACH_REPO", Path(__file__).resolve().parents[2])).resolve()
_WS = Path(os.environ.get("REACH_WS", REPO / ".build_ws"))
BIN = Path(os.environ.get("REACH_BIN", _WS / "devel" / "lib" / "reach_trajopt"))
SITE_PACKAGES = Path(sysconfig.get_paths()["purelib"])
CMEEL_PREFIX = SITE_PACKAGES / "cmeel.prefix"
EXAMPLE_ROBOTS = CMEEL_PREFIX / "share" / "example-robot-data" / "robots"
# config/talos.yaml names its URDF through ${EXAMPLE_ROBOT_DATA} (scripts/env.sh sets it too).
os.environ.setdefault("EXAMPLE_ROBOT_DATA", str(EXAMPLE_ROBOTS))

# A tool that hangs is a failure; generous because the machine is shared (2 cores).
TOOL_TIMEOUT_S = 300


@dataclass
class ToolRun:
    """Outcome of one run of a command-line tool."""

    args: list
    returncode: int
    stdout: str
    stderr: str

    @property
    def output(self):
        """stdout and stderr together: error messages may go to either."""
        return self.stdout + "\n" + self.stderr

    def describe(self, limit=2000):
        return (f"command: {' '.join(map(str, self.args))}\nexit code: {self.returncode}\n"
                f"stdout: {self.stdout[:limit]}\nstderr: {self.stderr[:limit]}")

    def json(self):
        """Parses stdout as JSON; fails the test with the tool's output when it is not."""
        assert self.returncode == 0, self.describe()
        try:
            return json.loads(self.stdout)
        except json.JSONDecodeError as e:
            pytest.fail(f"stdout is not JSON ({e})\n{self.describe()}")


def tool_path(name):
    """Path of a built executable; fails the test when it is missing."""
    path = BIN / name
    if not (path.is_file() and os.access(path, os.X_OK)):
        pytest.fail(f"tool '{name}' not built: {path} does not exist (REACH_BIN={BIN}); "
                    "build with scripts/build first")
    return path


def run_tool(name, *args, timeout=TOOL_TIMEOUT_S):
    """Runs BIN/<name> with `args` from the repository root and returns a ToolRun."""
    cmd = [str(tool_path(name))] + [str(a) for a in args]
    try:
        p = subprocess.run(cmd, cwd=REPO, capture_output=True, text=True, timeout=timeout)
    except subprocess.TimeoutExpired:
        pytest.fail(f"{' '.join(cmd)} did not finish within {timeout} s")
    return ToolRun(cmd, p.returncode, p.stdout, p.stderr)


def write_json(path, obj):
    """Writes `obj` as JSON with full double precision (repr round-trips); NaN stays NaN."""
    path = Path(path)
    path.write_text(json.dumps(obj, allow_nan=True))
    return path


def finite_or_none(x):
    """JSON cannot hold +-inf: tools may print null for an unlimited bound."""
    return x if x is not None and math.isfinite(x) else None


# Lines a test wants in the run's output even when it passes (e.g. how many robots an oracle
# checked); printed at the end of the pytest run. With pytest-xdist (scripts/run_tests runs two
# workers) each worker hands its lines to the controller, which prints them all.
SUMMARY_LINES = []


def pytest_sessionfinish(session):
    workeroutput = getattr(session.config, "workeroutput", None)
    if workeroutput is not None:  # an xdist worker
        workeroutput["summary_lines"] = list(SUMMARY_LINES)


@pytest.hookimpl(optionalhook=True)
def pytest_testnodedown(node, error):
    SUMMARY_LINES.extend(getattr(node, "workeroutput", {}).get("summary_lines", []))


def pytest_terminal_summary(terminalreporter):
    for line in SUMMARY_LINES:
        terminalreporter.write_line(line)


@pytest.fixture(scope="session")
def repo():
    return REPO


@pytest.fixture(scope="session")
def reach_bin():
    return BIN


@pytest.fixture(scope="session")
def example_robots():
    """Directory of the example-robot-data URDFs (mesh files are not needed for dynamics)."""
    if not EXAMPLE_ROBOTS.is_dir():
        pytest.fail(f"example-robot-data not found at {EXAMPLE_ROBOTS}: run scripts/bootstrap")
    return EXAMPLE_ROBOTS
