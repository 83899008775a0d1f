"""The walk report (scripts/analyze_bag -> index.html) in a real browser, headless Chromium
(Debian's `chromium`, installed by scripts/bootstrap).

The bags are recorded here as `make demo` records them (launch/walk.launch record:=true, the
demo's 0.4 m/s lateral push, baseline and proposed), with fewer steps, on a private ROS master.
Then analyze_bag writes the report of both side by side, and Chromium
  - loads it with no console message at all (the page logs nothing; an uncaught exception or a
    failed resource is a console message): --enable-logging=stderr shows them as CONSOLE lines;
  - runs its animation: after 1.5 s and after 3 s of virtual time the frame the page writes
    into the DOM (#frame data-frame) has advanced, and so has the time;
  - renders the robot and the footholds: in the screenshot, pixels of the robot's colour in
    both runs' views and of the executed and planned footholds' colours (exact RGB values the
    page draws with, counted per half of the page, one half per run; the legend's swatches
    are far below the thresholds).
The page is self-contained: it names no http(s) URL, no external script, style or font.
"""

import os
import re
import socket
import struct
import subprocess
import time
import zlib

import pytest

from conftest import REPO

STEPS = 3
ROBOT = (0x1F, 0x77, 0xB4)
ROBOT_LEFT = (0x0D, 0x3D, 0x66)
PLANNED = (0x2C, 0xA0, 0x2C)
EXECUTED = (0xFF, 0x7F, 0x0E)
CHROMIUM_TIMEOUT_S = 120


def free_port():
    s = socket.socket()
    s.bind(("127.0.0.1", 0))
    port = s.getsockname()[1]
    s.close()
    return port


def chromium():
    for name in ("chromium", "chromium-browser"):
        for d in os.environ.get("PATH", "").split(":") + ["/usr/bin"]:
            p = os.path.join(d, name)
            if os.path.isfile(p) and os.access(p, os.X_OK):
                return p
    pytest.fail("no chromium: scripts/bootstrap installs Debian's chromium package")


def record_walk(policy, bag, env, log):
    cmd = ["roslaunch", "-p", env["ROS_MASTER_URI"].rsplit(":", 1)[1],
           str(REPO / "launch" / "walk.launch"), "policy:=" + policy, "steps:=%d" % STEPS,
           "push_vy:=0.4", "seed:=1", "record:=true", "bag:=" + str(bag)]
    with open(log, "w") as out:
        r = subprocess.run(cmd, env=env, stdout=out, stderr=subprocess.STDOUT, timeout=600)
    assert r.returncode == 0, "roslaunch %s exited %d (%s)" % (policy, r.returncode, log)
    assert bag.is_file(), "no bag %s (%s)" % (bag, log)


@pytest.fixture(scope="module")
def report(tmp_path_factory):
    d = tmp_path_factory.mktemp("report_browser")
    env = dict(os.environ)
    env["ROS_MASTER_URI"] = "http://localhost:%d" % free_port()
    env["ROS_HOME"] = str(d / "ros_home")
    env.setdefault("OMP_NUM_THREADS", "2")
    bags = []
    for policy in ("baseline", "proposed"):
        bag = d / ("walk_%s.bag" % policy)
        record_walk(policy, bag, env, d / ("roslaunch_%s.log" % policy))
        bags.append(bag)
    out = d / "compare"
    r = subprocess.run(["/usr/bin/python3", str(REPO / "scripts" / "analyze_bag"),
                        str(bags[0]), str(bags[1]), "--out", str(out)],
                       capture_output=True, text=True, timeout=600, env=env)
    assert r.returncode == 0, r.stdout + r.stderr
    page = out / "index.html"
    assert page.is_file()
    return page


def run_chromium(page, tmp, *args, budget_ms):
    profile = tmp / ("profile_%d" % time.monotonic_ns())
    cmd = [chromium(), "--headless", "--no-sandbox", "--disable-gpu", "--no-first-run",
           "--user-data-dir=" + str(profile), "--enable-logging=stderr", "--v=0",
           "--window-size=1400,1000", "--virtual-time-budget=%d" % budget_ms,
           *args, page.as_uri()]
    r = subprocess.run(cmd, capture_output=True, text=True, timeout=CHROMIUM_TIMEOUT_S)
    assert r.returncode == 0, r.stderr[-2000:]
    return r


def console_lines(stderr):
    return [l for l in stderr.splitlines() if ":CONSOLE" in l]


def frame_of(dom):
    m = re.search(r'id="frame" data-frame="(\d+)"', dom)
    assert m, "no #frame in the dumped DOM"
    t = re.search(r'id="time">([0-9.]+)<', dom)
    return int(m.group(1)), float(t.group(1))


def test_self_contained(report):
    text = report.read_text()
    assert not re.search(r"""(src|href)\s*=\s*["']?(https?:)?//""", text)
    assert "@import" not in text and "url(" not in text
    assert "<script src" not in text and "<link" not in text


def test_loads_without_console_messages_and_animates(report, tmp_path):
    frames = []
    for budget in (1500, 3000):
        r = run_chromium(report, tmp_path, "--dump-dom", budget_ms=budget)
        assert console_lines(r.stderr) == [], console_lines(r.stderr)
        frames.append(frame_of(r.stdout))
        # both runs were built into the page
        assert r.stdout.count('class="run"') == 2
    (f1, t1), (f2, t2) = frames
    assert f1 > 10, "the animation did not run in 1.5 s of virtual time (frame %d)" % f1
    assert f2 > f1 and t2 != t1


def read_png(path):
    """(width, height, rows of (r, g, b)) of an 8-bit RGB or RGBA, non-interlaced PNG."""
    data = path.read_bytes()
    assert data[:8] == b"\x89PNG\r\n\x1a\n"
    pos, idat, w = 8, b"", None
    while pos < len(data):
        n, kind = struct.unpack(">I4s", data[pos:pos + 8])
        body = data[pos + 8:pos + 8 + n]
        if kind == b"IHDR":
            w, h, depth, ctype, _, _, interlace = struct.unpack(">IIBBBBB", body)
            assert depth == 8 and ctype in (2, 6) and interlace == 0, (depth, ctype, interlace)
            bpp = 3 if ctype == 2 else 4
        elif kind == b"IDAT":
            idat += body
        pos += 12 + n
    raw = zlib.decompress(idat)
    stride = w * bpp
    rows, prev, i = [], bytearray(stride), 0
    for _ in range(h):
        f, line = raw[i], bytearray(raw[i + 1:i + 1 + stride])
        i += 1 + stride
        for x in range(stride):
            a = line[x - bpp] if x >= bpp else 0
            b = prev[x]
            c = prev[x - bpp] if x >= bpp else 0
            if f == 1:
                line[x] = (line[x] + a) & 255
            elif f == 2:
                line[x] = (line[x] + b) & 255
            elif f == 3:
                line[x] = (line[x] + (a + b) // 2) & 255
            elif f == 4:
                p = a + b - c
                pa, pb, pc = abs(p - a), abs(p - b), abs(p - c)
                line[x] = (line[x] + (a if pa <= pb and pa <= pc else b if pb <= pc else c)) & 255
        rows.append([tuple(line[x:x + 3]) for x in range(0, stride, bpp)])
        prev = line
    return w, h, rows


def test_screenshot_shows_robot_and_footholds(report, tmp_path):
    shot = tmp_path / "shot.png"
    r = run_chromium(report, tmp_path, "--screenshot=" + str(shot), budget_ms=2500)
    assert console_lines(r.stderr) == []
    w, h, rows = read_png(shot)
    counts = [{}, {}]  # per half of the page (baseline left, proposed right)
    for y in range(h):
        for x, px in enumerate(rows[y]):
            half = counts[0 if x < w // 2 else 1]
            half[px] = half.get(px, 0) + 1
    for k, name in enumerate(("baseline", "proposed")):
        c = counts[k]
        robot = c.get(ROBOT, 0) + c.get(ROBOT_LEFT, 0)
        assert robot > 1000, "%s: %d robot pixels" % (name, robot)
        assert c.get(EXECUTED, 0) > 1000, "%s: %d executed-foothold pixels" % (name,
                                                                          c.get(EXECUTED, 0))
        assert c.get(PLANNED, 0) > 300, "%s: %d planned-foothold pixels" % (name,
                                                                       c.get(PLANNED, 0))
