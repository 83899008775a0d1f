"""scripts/bench_results.py (the writer of bench/results.md, run by every `make bench`) on a
saved log of BENCH lines (test/fixtures/bench_sample.log): each headline figure is read from
its line and compared with its target as the issues state them; the expected verdicts below
are worked out by hand from the sample's numbers, not from the writer's output."""

import subprocess
import sys

from conftest import REPO

WRITER = REPO / "scripts" / "bench_results.py"
SAMPLE = REPO / "test" / "fixtures" / "bench_sample.log"


def run(tmp_path, log_text=None):
    log = SAMPLE
    if log_text is not None:
        log = tmp_path / "bench.log"
        log.write_text(log_text)
    out = tmp_path / "results.md"
    r = subprocess.run([sys.executable, str(WRITER), str(log), "--out", str(out), "--commit",
                        "0123abc", "--date", "2000-01-02 03:04 UTC"],
                       capture_output=True, text=True, timeout=60)
    return r, (out.read_text() if out.exists() else "")


def rows(text):
    out = {}
    for line in text.splitlines():
        if line.startswith("| ") and not line.startswith("| figure") and "---" not in line:
            cells = [c.strip() for c in line.strip("|").split(" | ")]
            out[cells[0]] = cells[1:]
    return out


def test_sample_figures_and_verdicts(tmp_path):
    r, text = run(tmp_path)
    assert r.returncode == 0, r.stderr
    assert "commit 0123abc, 2000-01-02 03:04 UTC" in text
    assert ("Benchmarks in this run: dynamics, qp, reach, walk_check, verdict, ocp, ocp_talos, "
            "envelope, ros_walk, sim.controller; failed: ros_walk.") in text
    t = rows(text)
    # measured, target, met: 0.0712 s <= 0.1 s (the 2-thread line, not the 1-thread 0.1412)
    assert t["one reachability check, bench case, 2 threads"][:3] == ["0.0712 s", "<= 0.1 s",
                                                                     "yes"]
    # the bidirectional speed-up line (no mode key), not the walk horizon's 1.78
    assert t["its speed-up 1 -> 2 threads"][0] == "1.98"
    assert t["its speed-up 1 -> 2 threads"][2] == "yes"
    # the largest peak over every reach.check line: 210 MiB <= 256
    assert t["peak memory of a check (largest reach.check line)"][0] == "210 MiB"
    assert t["check per step, demo walk, 2 threads: mean"][0::2] == ["0.098 s", "yes"]
    assert t["check per step, demo walk, 2 threads: max"][0::2] == ["0.206 s", "yes"]
    # OCP 0.321 s > 0.1 s; check + OCP 0.846 s > 0.2 s
    assert t["transition OCP per step of the walk: mean"][0::2] == ["0.321 s", "**no**"]
    assert t["a step's plan (check + OCP): p95, else the max"][0::2] == ["0.846 s", "**no**"]
    # 0 false reachable, 0 false unreachable <= 8.1 (10 % of 81)
    assert t["verdicts: false reachable / false unreachable of the OCP-converged"][0::2] == [
        "0 / 0 of 81", "yes"]
    assert t["OCP on a TALOS step vs Crocoddyl FDDP, time ratio"][2] == "**no**"  # 0.41 > 0.2
    # 26 < 28: not more than kinematic
    assert t["pushes survived, proposed / kinematic / baseline"][0::2] == ["26 / 28 / 24 of 48",
                                                                         "**no**"]
    assert t["envelope radius of the proposed preset"][0].startswith("0.2 m/s")
    # ros_walk failed in the sample: no line, so not measured and never "met"
    assert t["node-wired walk, wall time / in process"][0::2] == ["not measured in this run",
                                                                 "-"]
    # targets with a test: 14; met: bench case, speed-up, memory, walk mean and max, verdicts,
    # agreement, TALOS verdicts = 8
    assert "8 of 14 targets met in this run." in text


def test_targets_met_when_the_numbers_are(tmp_path):
    log = "\n".join([
        "BENCH ocp.walk mean_s=0.08 max_s=0.15",
        "BENCH walk.plan_latency p50_s=0.1 p95_s=0.19 max_s=0.3",
        "BENCH walk.envelope preset=baseline protocol=standing pushes=10 survived=2 radii_mps=0.6/0.6",
        "BENCH walk.envelope preset=kinematic protocol=standing pushes=10 survived=4 radii_mps=0.6/0.6",
        "BENCH walk.envelope preset=proposed protocol=standing pushes=10 survived=5 radii_mps=0.6/0.7",
        "BENCH ocp.talos_step ours_s=0.1 violation=1e-9 ref=crocoddyl_fddp ref_s=1 ref_violation=0.3 ratio=0.1",
    ])
    r, text = run(tmp_path, log)
    assert r.returncode == 0, r.stderr
    t = rows(text)
    assert t["transition OCP per step of the walk: mean"][0::2] == ["0.08 s", "yes"]
    assert t["a step's plan (check + OCP): p95, else the max"][0::2] == ["0.19 s", "yes"]
    assert t["pushes survived, proposed / kinematic / baseline (standing)"][2] == "yes"  # 5 > 4, 5 >= 4
    assert t["envelope radius of the proposed preset (standing)"][2] == "yes"
    assert t["OCP on a TALOS step vs Crocoddyl FDDP, time ratio"][2] == "yes"
    assert t["one reachability check, bench case, 2 threads"][0] == "not measured in this run"


def test_the_envelope_figures_are_the_bipeds(tmp_path):
    # TALOS's baseline line (robot=talos, scripts/bench_envelope.sh) comes last; the figures
    # are the biped's: 5 > 4 and 5 >= 2 x 2 met (TALOS's 9 would fail 5 >= 2 x 9).
    log = "\n".join([
        "BENCH walk.envelope preset=baseline protocol=standing pushes=10 survived=2 radii_mps=0.6/0.6",
        "BENCH walk.envelope preset=kinematic protocol=standing pushes=10 survived=4 radii_mps=0.6/0.6",
        "BENCH walk.envelope preset=proposed protocol=standing pushes=10 survived=5 radii_mps=0.6/0.7",
        "BENCH walk.envelope robot=talos preset=baseline protocol=standing pushes=16 survived=9 radii_mps=0.4/0.4",
    ])
    r, text = run(tmp_path, log)
    assert r.returncode == 0, r.stderr
    t = rows(text)
    assert t["pushes survived, proposed / kinematic / baseline (standing)"][0::2] == [
        "5 / 4 / 2 of 10", "yes"]


def test_the_talos_radius_is_its_proposed_presets_against_0_4(tmp_path):
    # TALOS's lines (robot=talos) give their own row: the proposed preset's smallest radius,
    # 0.2 of 0.4/0.2/0.4 (not met), then 0.4 of 0.4/0.6 (met); its baseline's 0.6 is not read,
    # nor the biped's 0.1.
    def table(talos_radii):
        log = "\n".join([
            "BENCH walk.envelope preset=proposed protocol=standing pushes=10 survived=5 radii_mps=0.1/0.6",
            "BENCH walk.envelope robot=talos preset=baseline protocol=standing pushes=16 survived=16 radii_mps=0.6/0.6",
            "BENCH walk.envelope robot=talos preset=proposed protocol=standing pushes=16 survived=9 "
            "radii_mps=" + talos_radii,
        ])
        r, text = run(tmp_path, log)
        assert r.returncode == 0, r.stderr
        return rows(text)["envelope radius of the proposed preset on TALOS (standing)"][0::2]
    assert table("0.4/0.2/0.4") == ["0.2 m/s (min of 3 directions)", "**no**"]
    assert table("0.4/0.6") == ["0.4 m/s (min of 2 directions)", "yes"]


def test_the_envelope_paying_for_its_plans_is_compared_with_the_paused_one(tmp_path):
    # The measured line comes last: the pause figures stay the reference lines' (5 > 4), and the
    # measured row compares 4 with 5 (at most one fewer: met), then 3 with 5 (not met).
    def table(measured_survived):
        log = "\n".join([
            "BENCH walk.envelope preset=baseline protocol=midswing pushes=10 survived=2 radii_mps=0.6",
            "BENCH walk.envelope preset=kinematic protocol=midswing pushes=10 survived=4 radii_mps=0.6",
            "BENCH walk.envelope preset=proposed protocol=midswing pushes=10 survived=5 radii_mps=0.6",
            "BENCH walk.envelope preset=proposed protocol=midswing pushes=10 survived=%d "
            "radii_mps=0.2 plan_latency=measured bounds=off" % measured_survived,
        ])
        r, text = run(tmp_path, log)
        assert r.returncode == 0, r.stderr
        return rows(text)
    t = table(4)
    assert t["pushes survived, proposed / kinematic / baseline (midswing)"][0::2] == [
        "5 / 4 / 2 of 10", "yes"]
    assert t["envelope radius of the proposed preset (midswing)"][0].startswith("0.6 m/s")
    key = "pushes survived by the proposed preset, plan latency measured vs pause (midswing)"
    assert t[key][0::2] == ["4 vs 5 of 10", "yes"]
    assert table(3)[key][0::2] == ["3 vs 5 of 10", "**no**"]


def test_bad_input_is_named(tmp_path):
    r, _ = run(tmp_path, "no benchmark lines here\n")
    assert r.returncode == 2 and "holds no BENCH line" in r.stderr
    r = subprocess.run([sys.executable, str(WRITER), str(tmp_path / "missing.log")],
                       capture_output=True, text=True, timeout=60)
    assert r.returncode == 2 and "missing.log" in r.stderr
