#!/usr/bin/python3
"""bench_results: bench/results.md from the BENCH lines of one `make bench` run.

    scripts/bench_results.py LOG [--out bench/results.md] [--commit C] [--date D]

LOG is the output of scripts/bench (every line; the `BENCH <area.name> key=value ...` lines
are read, the rest ignored). Writes one table: each headline figure, its target (from the
issues that set it), met or not, the command that prints it; then the commit and date of the
run and every BENCH line it printed. A figure whose line is missing from the log (its bench
failed or was skipped) is written as "not measured", never as met.
Exit status: 0 written, 2 bad input (no LOG, no BENCH line in it).
"""
import argparse
import datetime
import os
import re
import subprocess
import sys

REPO = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))


def parse(text):
    """[(name, {key: value})] of every BENCH line, in order."""
    out = []
    for line in text.splitlines():
        m = re.search(r"(?:^|\s)BENCH\s+(\S+)(.*)$", line)
        if not m or "=" not in m.group(2) and m.group(2).strip():
            continue
        kv = {}
        for tok in m.group(2).split():
            if "=" in tok:
                k, v = tok.split("=", 1)
                kv.setdefault(k, v)
        out.append((m.group(1), kv))
    return out


def num(v):
    try:
        return float(v)
    except (TypeError, ValueError):
        return None


def find(lines, name, **sel):
    """The last line called `name` whose keys match `sel` (value None: key absent)."""
    hit = None
    for n, kv in lines:
        if n != name:
            continue
        if all((kv.get(k) is None) if v is None else
               (kv.get(k) == v if not callable(v) else v(kv.get(k))) for k, v in sel.items()):
            hit = kv
    return hit


def fmt(x, unit=""):
    if x is None:
        return "-"
    if isinstance(x, str):
        return x
    s = ("%.3g" % x) if abs(x) < 1000 else ("%.0f" % x)
    return s + (" " + unit if unit else "")


# Each figure: label, how to get the value from the lines, target text, test, command.
# get(lines) -> (value text, met: True/False/None) or None when not measured.

def single(name, key, unit, test=None, sel=None):
    def get(lines):
        kv = find(lines, name, **(sel or {}))
        if kv is None or num(kv.get(key)) is None:
            return None
        x = num(kv[key])
        return fmt(x, unit), (test(x) if test else None)
    return get


def first_of(*getters):
    def get(lines):
        for g in getters:
            r = g(lines)
            if r is not None:
                return r
        return None
    return get


def peak_rss(lines):
    vals = [num(kv.get("peak_rss_mib")) for n, kv in lines if n == "reach.check"]
    vals = [v for v in vals if v is not None]
    if not vals:
        return None
    return fmt(max(vals), "MiB"), max(vals) <= 256


def verdict(lines):
    kv = find(lines, "reach.verdict")
    if kv is None:
        return None
    fr, fu, k = (num(kv.get(x)) for x in ("false_reachable", "false_unreachable", "ocp_converged"))
    if None in (fr, fu, k):
        return None
    return ("%d / %d of %d" % (fr, fu, k)), (fr == 0 and fu <= 0.1 * k)


def verdict_fast(lines):
    kv = find(lines, "reach.verdict_fast")
    if kv is None or num(kv.get("agreement")) is None:
        return None
    a, fr = num(kv["agreement"]), num(kv.get("false_reachable"))
    return "%.4f, false_reachable %s" % (a, fmt(fr)), (a >= 0.98 and fr == 0)


def verdict_talos(lines):
    kv = find(lines, "reach.verdict_talos")
    if kv is None or num(kv.get("false_reachable")) is None:
        return None
    fr = num(kv["false_reachable"])
    return "%d of %s reachable" % (fr, kv.get("reachable", "?")), fr == 0


def talos_ocp(lines):
    kv = find(lines, "ocp.talos_step", ref="crocoddyl_fddp")
    if kv is None or num(kv.get("ratio")) is None:
        return None
    r, v, rv = num(kv["ratio"]), num(kv.get("violation")), num(kv.get("ref_violation"))
    ok = r <= 0.2 and v is not None and rv is not None and v <= rv
    return "%s (violation %s vs %s)" % (fmt(r), fmt(v), fmt(rv)), ok


def envelope(protocol):
    def get(lines):
        sel = {} if protocol is None else {"protocol": protocol}
        got = {p: find(lines, "walk.envelope", preset=p, **sel, **PAUSED)
               for p in ("proposed", "kinematic", "baseline")}
        if any(v is None or num(v.get("survived")) is None for v in got.values()):
            return None
        s = {p: int(num(v["survived"])) for p, v in got.items()}
        n = got["proposed"].get("pushes", "?")
        ok = s["proposed"] > s["kinematic"] and s["proposed"] >= 2 * s["baseline"]
        return "%d / %d / %d of %s" % (s["proposed"], s["kinematic"], s["baseline"], n), ok
    return get


def envelope_radius(protocol, robot=None, least_mps=0.6):
    """The proposed preset's smallest radius over the directions (the biped's lines, or those
    marked robot=`robot`), met at >= least_mps."""
    def get(lines):
        sel = {} if protocol is None else {"protocol": protocol}
        which = PAUSED if robot is None else dict(PAUSED, robot=robot)
        kv = find(lines, "walk.envelope", preset="proposed", **sel, **which)
        if kv is None or not kv.get("radii_mps"):
            return None
        radii = [num(r) for r in kv["radii_mps"].split("/")]
        if None in radii or not radii:
            return None
        return ("%s m/s (min of %d directions)" % (fmt(min(radii)), len(radii)),
                min(radii) >= least_mps)
    return get


def envelope_measured(protocol):
    """The proposed preset paying for its plans' wall time (plan_latency=measured) beside the
    same grid pausing for them: at most one push fewer."""
    def get(lines):
        sel = {} if protocol is None else {"protocol": protocol}
        paused = find(lines, "walk.envelope", preset="proposed", **sel, **PAUSED)
        paying = find(lines, "walk.envelope", preset="proposed", plan_latency="measured", **sel,
                      **BIPED)
        if paused is None or paying is None:
            return None
        a, b = num(paying.get("survived")), num(paused.get("survived"))
        if a is None or b is None:
            return None
        return "%d vs %d of %s" % (a, b, paying.get("pushes", "?")), a >= b - 1
    return get


def protocols(lines):
    ps = sorted({kv.get("protocol") for n, kv in lines
                 if n == "walk.envelope" and kv.get("robot") in (None, "biped")},
                key=lambda p: (p is not None, p or ""))
    return ps or [None]


# The biped's lines of a figure measured on both robots (a line without robot= is the biped's).
BIPED = {"robot": lambda r: r in (None, "biped")}
# The envelope's reference lines: the simulation waits for each plan (no plan_latency= key).
PAUSED = dict(BIPED, plan_latency=None)


def walk_time(title, limit_s, name, key, walk_check_key):
    """A figure row of a time of the biped's walk: `key` of the BENCH line `name`, else
    `walk_check_key` of reach.walk_check's 2-thread line; it passes at <= limit_s."""
    within = lambda x: x <= limit_s  # noqa: E731
    return (title,
            first_of(single(name, key, "s", within, BIPED),
                     single("reach.walk_check", walk_check_key, "s", within, {"threads": "2"})),
            "<= %g s" % limit_s, "scripts/bench_walk_check.sh")


def figures(lines):
    F = [
        ("rigid-body dynamics (M, b, Jacobians) of the biped, time / Pinocchio's",
         single("dynamics.full", "ratio", "", None,
                {"robot": lambda r: r is not None and "biped" in r}),
         "- (reference)", "scripts/bench_dynamics.sh"),
        ("contact QP, cold start, time / eiquadprog's",
         single("qp.contact.cold", "ratio", ""), "- (reference)", "scripts/bench_qp.sh"),
        ("one reachability check, bench case, 2 threads",
         single("reach.check", "ours_s", "s", lambda x: x <= 0.1,
                {"mode": "bidirectional", "threads": "2"}),
         "<= 0.1 s", "scripts/bench_reach.sh"),
        ("its speed-up 1 -> 2 threads",
         single("reach.speedup", "ratio", "", lambda x: x >= 1.8, {"mode": None}),
         ">= 1.8", "scripts/bench_reach.sh"),
        ("peak memory of a check (largest reach.check line)", peak_rss, "<= 256 MiB",
         "scripts/bench_reach.sh"),
        ("check per step, demo walk, 2 threads: mean",
         single("reach.walk_check", "mean_s", "s", lambda x: x <= 0.15, {"threads": "2"}),
         "<= 0.15 s", "scripts/bench_walk_check.sh"),
        ("check per step, demo walk, 2 threads: max",
         single("reach.walk_check", "max_s", "s", lambda x: x <= 0.3, {"threads": "2"}),
         "<= 0.3 s", "scripts/bench_walk_check.sh"),
        walk_time("transition OCP per step of the walk: mean", 0.1, "ocp.walk", "mean_s",
                  "ocp_mean_s"),
        ("transition OCP per step: max (ocp.walk, else the walks of seeds 2-5)",
         first_of(single("ocp.walk", "max_s", "s", lambda x: x <= 0.2, BIPED),
                  single("reach.walk_check_seeds", "ocp_max_s", "s", lambda x: x <= 0.2)),
         "<= 0.2 s", "scripts/bench_walk_check.sh"),
        walk_time("a step's plan (check + OCP): p95, else the max", 0.2, "walk.plan_latency",
                  "p95_s", "step_max_s"),
        ("transition OCP per step of the TALOS walk: mean",
         single("ocp.walk", "mean_s", "s", lambda x: x <= 0.15, {"robot": "talos"}),
         "<= 0.15 s", "scripts/bench_walk_check.sh"),
        ("verdicts: false reachable / false unreachable of the OCP-converged", verdict,
         "0 / <= 10 %", "scripts/bench_verdict.sh"),
        ("shipped check vs the full-budget reference: agreement", verdict_fast,
         ">= 0.98, false_reachable 0", "scripts/bench_verdict.sh"),
        ("TALOS verdicts: false reachable", verdict_talos, "0", "scripts/bench_verdict.sh"),
        ("OCP vs IPOPT on the same NLP (step_015), time ratio",
         single("ocp.step_015", "ratio", ""), "- (reference)", "scripts/bench_ocp.sh"),
        ("OCP on a TALOS step vs Crocoddyl FDDP, time ratio", talos_ocp,
         "<= 0.2 at lower violation", "scripts/bench_ocp_talos.sh"),
    ]
    for p in protocols(lines):
        tag = "" if p is None else " (%s)" % p
        F.append(("pushes survived, proposed / kinematic / baseline" + tag, envelope(p),
                  "proposed > kinematic, >= 2 x baseline", "scripts/bench_envelope.sh"))
        F.append(("envelope radius of the proposed preset" + tag, envelope_radius(p),
                  ">= 0.6 m/s in every direction", "scripts/bench_envelope.sh"))
        F.append(("pushes survived by the proposed preset, plan latency measured vs pause" + tag,
                  envelope_measured(p), ">= pause - 1", "scripts/bench_envelope.sh"))
    if find(lines, "walk.envelope", robot="talos", preset="proposed") is not None:
        F.append(("envelope radius of the proposed preset on TALOS (standing)",
                  envelope_radius("standing", "talos", 0.4), ">= 0.4 m/s in every direction",
                  "scripts/bench_envelope.sh"))
    F += [
        ("node-wired walk, wall time / in process",
         single("ros.walk_overhead", "ratio", "", lambda x: x <= 1.1), "<= 1.1",
         "scripts/bench_ros_walk.sh"),
        ("simulation with the controller, real-time factor (one core)",
         single("sim.controller", "rtf", ""), "- (reference)", "scripts/bench (sim.controller)"),
    ]
    return F


def git_commit():
    try:
        c = subprocess.run(["git", "-C", REPO, "rev-parse", "--short", "HEAD"],
                           capture_output=True, text=True, check=True).stdout.strip()
        dirty = subprocess.run(["git", "-C", REPO, "status", "--porcelain", "--untracked-files=no"],
                               capture_output=True, text=True).stdout.strip()
        return c + (" with uncommitted changes" if dirty else "")
    except (OSError, subprocess.CalledProcessError):
        return "unknown"


def sections(text):
    """(benchmarks run, benchmarks failed) from the `=== bench: X ===` and `[bench] X failed`
    lines of scripts/bench."""
    ran = re.findall(r"^=== bench: (\S+) ===", text, re.M)
    failed = re.findall(r"^\[bench\] (\S+) failed", text, re.M)
    return ran, failed


def render(lines, commit, date, ran=(), failed=()):
    L = ["# Benchmark results", "",
         "Written by `make bench` (`scripts/bench_results.py` from the BENCH lines of the run, all",
         "of it or the benchmarks named below); do not edit by hand. What each benchmark",
         "measures: [README.md](README.md).", "",
         "Run: commit %s, %s, on %s (%d cores, load average %s at the end)." % (
             commit, date, os.uname().machine, os.cpu_count() or 0,
             "%.2f" % os.getloadavg()[0]), "",
         ]
    load, cores = os.getloadavg()[0], os.cpu_count() or 1
    if load > cores:
        L += ["The machine was busy while this run ended (load average %.1f on %d cores): its"
              " times are pessimistic; the ratios to references run alongside hold better." % (
                  load, cores), ""]
    if ran:
        L += ["Benchmarks in this run: %s%s." % (", ".join(ran), "; failed: " + ", ".join(failed)
                                                  if failed else ""), ""]
    L += ["| figure | measured | target | met | command |", "|---|---|---|---|---|"]
    met_n = total = 0
    for label, get, target, cmd in figures(lines):
        r = get(lines)
        if r is None:
            value, met = "not measured in this run", "-"
        else:
            value, ok = r
            met = "-" if ok is None else ("yes" if ok else "**no**")
            if ok is not None:
                total += 1
                met_n += bool(ok)
        L.append("| %s | %s | %s | %s | `%s` |" % (label, value, target, met, cmd))
    L += ["", "%d of %d targets met in this run." % (met_n, total), "",
          "## Every BENCH line of the run", "", "```"]
    for n, kv in lines:
        L.append("BENCH %s %s" % (n, " ".join("%s=%s" % x for x in kv.items())))
    L += ["```", ""]
    return "\n".join(L)


def main(argv):
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("log")
    ap.add_argument("--out", default=os.path.join(REPO, "bench", "results.md"))
    ap.add_argument("--commit")
    ap.add_argument("--date")
    a = ap.parse_args(argv)
    if not os.path.isfile(a.log):
        print("bench_results: no log file '%s'" % a.log, file=sys.stderr)
        return 2
    with open(a.log, errors="replace") as f:
        log_text = f.read()
    lines = parse(log_text)
    if not lines:
        print("bench_results: '%s' holds no BENCH line" % a.log, file=sys.stderr)
        return 2
    date = a.date or datetime.datetime.now(datetime.timezone.utc).strftime("%Y-%m-%d %H:%M UTC")
    text = render(lines, a.commit or git_commit(), date, *sections(log_text))
    with open(a.out, "w") as f:
        f.write(text)
    print("bench_results: %s (%d BENCH lines)" % (a.out, len(lines)))
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
