#!/usr/bin/python3
"""rostest checker of walk_bag.test (baseline) and proposed_walk_bag.test: waits for the walk to
end, stops the recorder so the bag is closed, then checks the bag with two independent readers
(rosbag, and the `rosbags` PyPI package of the project venv) and `rosbag info`:
  - every topic of the run is present;
  - the TF tree is complete: every link of robot_description reaches "world";
  - every marker is in the "world" frame, footholds and CoM path are drawn;
  - the step reports are consistent with the simulation: indices 1..N, alternating swing sides
    (with walk.lift_off: timed),
    increasing touchdown times, header stamps equal to the touchdown times, touchdown_error equal
    to |executed - planned|, the executed foothold equal to the swing sole position given by the
    recorded TF at touchdown, and the count equal to the one of walk_result;
  - a policy with a check (proposed): one reachability_result, one reachability_markers array and one
    transition_trajectory and transition_markers per checked step, in step order, consistent
    with the step reports
    (verdict, swing sole, checked foothold = the TVR foothold, d_H, stamp = the sim time of the
    check: the first control tick reachability horizon before the nominal touchdown), all in
    "world", trajectory knot times increasing up to the horizon; baseline: none of these
    topics and no step checked.
Private parameters: ~bag (path), ~steps (expected steps), ~recorder (node name of rosbag record),
~policy (the walk's policy preset: baseline | unbounded | kinematic | proposed).
"""
import json
import math
import os
import subprocess
import sys
import time
import unittest
import xml.etree.ElementTree as ET

import numpy as np
import yaml
import rosbag
import rosnode
import rospy
import rostest
from std_msgs.msg import String

PKG = "reach_trajopt"
TOPICS = ["/clock", "/tf", "/joint_states", "/com_state", "/contact_state",
          "/contact_wrench/l_sole", "/contact_wrench/r_sole", "/step_report", "/markers",
          "/walk_result", "/contact_plan"]
# Published by sim_node once per checked step, with a policy that checks footholds only.
CHECK_TOPICS = ["/reachability_result", "/reachability_markers", "/transition_trajectory",
                "/transition_markers"]
# StepReport verdicts of a step whose check ran (a "check_error" step has no check messages).
CHECKED_VERDICTS = ("reachable", "unreachable", "kinematically_infeasible")


def quat_to_matrix(q):
    x, y, z, w = q.x, q.y, q.z, q.w
    return np.array([[1 - 2 * (y * y + z * z), 2 * (x * y - z * w), 2 * (x * z + y * w)],
                     [2 * (x * y + z * w), 1 - 2 * (x * x + z * z), 2 * (y * z - x * w)],
                     [2 * (x * z - y * w), 2 * (y * z + x * w), 1 - 2 * (x * x + y * y)]])


def to_matrix(t):
    T = np.eye(4)
    T[:3, :3] = quat_to_matrix(t.rotation)
    T[:3, 3] = [t.translation.x, t.translation.y, t.translation.z]
    return T


def world_pose(frame, edges):
    """Pose of `frame` in "world" by composing the parent -> child transforms in `edges`."""
    T = np.eye(4)
    hops = 0
    while frame != "world":
        parent, rel = edges[frame]
        T = rel @ T
        frame = parent
        hops += 1
        if hops > 100:
            raise RuntimeError("TF loop")
    return T


ROSBAGS_SCRIPT = r"""
import json, sys
from pathlib import Path
from rosbags.highlevel import AnyReader
from rosbags.typesys import Stores, get_typestore
out = {"counts": {}, "steps": []}
with AnyReader([Path(sys.argv[1])], default_typestore=get_typestore(Stores.ROS1_NOETIC)) as r:
    for c in r.connections:
        out["counts"][c.topic] = out["counts"].get(c.topic, 0) + c.msgcount
    cons = [c for c in r.connections if c.topic == "/step_report"]
    for c, t, raw in r.messages(connections=cons):
        m = r.deserialize(raw, c.msgtype)
        out["steps"].append([int(m.index), m.swing_side, m.executed.x, m.executed.y,
                             m.planned.x, m.planned.y, m.touchdown_time])
print(json.dumps(out))
"""


class WalkBagTest(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        rospy.init_node("check_walk_bag", anonymous=True)
        cls.bag_path = rospy.get_param("~bag")
        cls.expected_steps = int(rospy.get_param("~steps", 4))
        cls.mode = rospy.get_param("~policy", "baseline")
        cls.checked = cls.mode in ("kinematic", "proposed")  # policies with a foothold check
        # "fall" / "walk": the walk must fall / walk every step (the pushed comparison of the
        # paper's Sec. IV); "any": only the plumbing is checked when it falls.
        cls.expect = rospy.get_param("~expect", "any")
        cls.topics = TOPICS + (CHECK_TOPICS if cls.checked else [])
        recorder = rospy.get_param("~recorder", "/walk_recorder")
        # 1. The walk's end (walk_result is latched), in wall time: sim time runs in bursts.
        result = []
        sub = rospy.Subscriber("/walk_result", String, lambda m: result.append(m.data))
        deadline = time.time() + 150.0
        while not result and time.time() < deadline and not rospy.is_shutdown():
            time.sleep(0.1)
        sub.unregister()
        if not result:
            raise AssertionError("no walk_result within 150 s")
        cls.walk_result = result[0]
        rospy.loginfo("walk_result: %s", cls.walk_result)
        time.sleep(1.0)  # the recorder drains its queues
        # 2. Stop the recorder: rosbag closes the bag (".active" renamed) on shutdown.
        rosnode.kill_nodes([recorder])
        deadline = time.time() + 30.0
        while time.time() < deadline:
            if os.path.exists(cls.bag_path) and not os.path.exists(cls.bag_path + ".active"):
                break
            time.sleep(0.2)
        fields = dict(kv.split("=", 1) for kv in cls.walk_result.split()[1:] if "=" in kv)
        cls.result_steps = int(fields["steps"])
        cls.fell = fields.get("fell") == "yes"
        # 3. Read everything once.
        cls.msgs = {}
        with rosbag.Bag(cls.bag_path) as bag:
            cls.bag_topics = set(bag.get_type_and_topic_info().topics.keys())
            for topic, msg, _ in bag.read_messages():
                cls.msgs.setdefault(topic, []).append(msg)
        cls.urdf_links = [l.get("name") for l in
                          ET.fromstring(rospy.get_param("/robot_description")).findall("link")]
        # The walk's configuration (sim_node's ~config): swing duration, check horizon.
        with open(rospy.get_param("/sim_node/config")) as f:
            cls.config = yaml.safe_load(f)
        sim_path = rospy.get_param("/sim_node/sim_config", "")
        sim = cls.config
        if sim_path:
            with open(sim_path) as f:
                sim = yaml.safe_load(f)
        cls.dt = float(sim.get("sim", {}).get("time_step", 1e-3))  # control tick [s]
        # walk.lift_off (the struct default when the file does not set it: capture_point).
        cls.lift_off = (cls.config.get("walk") or {}).get("lift_off", "capture_point")

    def test_topics_present(self):
        for t in self.topics:
            self.assertIn(t, self.bag_topics, "topic %s missing from the bag" % t)
            self.assertGreater(len(self.msgs.get(t, [])), 0, t)
        clock = [m.clock.to_sec() for m in self.msgs["/clock"]]
        self.assertTrue(all(b > a for a, b in zip(clock, clock[1:])), "/clock not increasing")

    def test_steps_walked(self):
        if self.expect == "fall":
            self.assertTrue(self.fell, "expected a fall: " + self.walk_result)
        elif self.expect == "walk":
            self.assertFalse(self.fell, "expected no fall: " + self.walk_result)
        if self.fell:
            rospy.logwarn("the walk fell (%s): checking the plumbing only", self.walk_result)
            self.assertTrue(any(r.fell for r in self.msgs["/step_report"]),
                            "a fallen walk must end with a StepReport with fell = true")
        else:
            self.assertEqual(self.result_steps, self.expected_steps, self.walk_result)
        touched = [r for r in self.msgs["/step_report"] if r.touched_down]
        self.assertEqual(len(touched), self.result_steps)

    def test_tf_tree_complete(self):
        edges = {}
        for m in self.msgs["/tf"]:
            for t in m.transforms:
                edges[t.child_frame_id] = t.header.frame_id
        self.assertEqual(edges.get("pelvis"), "world")
        for link in self.urdf_links:
            frame, hops = link, 0
            while frame != "world":
                self.assertIn(frame, edges, "link %s is not connected to world" % link)
                frame = edges[frame]
                hops += 1
                self.assertLess(hops, 100)
        # Every TF message carries every link (one sendTransform per tick).
        for m in self.msgs["/tf"]:
            self.assertEqual(len(m.transforms), len(self.urdf_links))

    def test_markers_in_world(self):
        namespaces = set()
        for arr in self.msgs["/markers"]:
            for mk in arr.markers:
                self.assertEqual(mk.header.frame_id, "world", mk.ns)
                namespaces.add(mk.ns)
        for ns in ("footholds_planned", "footholds_executed", "com_path", "swing_path"):
            self.assertIn(ns, namespaces)
        last = {mk.ns: mk for mk in self.msgs["/markers"][-1].markers}
        touched = [r for r in self.msgs["/step_report"] if r.touched_down]
        self.assertEqual(len(last["footholds_executed"].points), len(touched))
        for p, r in zip(last["footholds_executed"].points, touched):
            self.assertAlmostEqual(p.x, r.executed.x, places=9)
            self.assertAlmostEqual(p.y, r.executed.y, places=9)
        for p, r in zip(last["footholds_planned"].points, touched):
            self.assertAlmostEqual(p.x, r.planned.x, places=9)
            self.assertAlmostEqual(p.y, r.planned.y, places=9)

    def test_step_reports_consistent_with_simulation(self):
        reports = [r for r in self.msgs["/step_report"] if r.touched_down]
        self.assertGreater(len(reports), 0)
        tf_msgs = self.msgs["/tf"]
        tf_times = np.array([m.transforms[0].header.stamp.to_sec() for m in tf_msgs])
        prev_t = 0.0
        for k, r in enumerate(reports):
            self.assertEqual(r.index, k + 1)
            self.assertEqual(r.header.frame_id, "world")
            self.assertEqual(r.mode, self.mode)
            # The sides alternate with the timed lift-off; with the capture-point lift-off a
            # capture point that leaves the soles lifts the sole on its side, maybe again.
            if k > 0 and self.lift_off == "timed":
                self.assertNotEqual(r.swing_side, reports[k - 1].swing_side)
            self.assertGreater(r.touchdown_time, r.plan_time)
            self.assertGreater(r.touchdown_time, prev_t)
            prev_t = r.touchdown_time
            self.assertAlmostEqual(r.header.stamp.to_sec(), r.touchdown_time, places=6)
            err = math.hypot(r.executed.x - r.planned.x, r.executed.y - r.planned.y)
            self.assertAlmostEqual(r.touchdown_error, err, places=9)
            # The executed foothold is where the recorded TF puts the swing sole at touchdown
            # (TF at 100 Hz: the nearest sample is at most 5 ms away; the sole has landed).
            i = int(np.argmin(np.abs(tf_times - r.touchdown_time)))
            self.assertLessEqual(abs(tf_times[i] - r.touchdown_time), 0.0051)
            edges = {t.child_frame_id: (t.header.frame_id, to_matrix(t.transform))
                     for t in tf_msgs[i].transforms}
            sole = "l_sole" if r.swing_side == "left" else "r_sole"
            p = world_pose(sole, edges)[:3, 3]
            self.assertLess(np.linalg.norm(p - [r.executed.x, r.executed.y, r.executed.z]), 0.01,
                            "step %d: executed %s vs TF %s" % (r.index, r.executed, p))
        # The planner node's plans: one per step, alternating sides, valid modes.
        plans = self.msgs["/contact_plan"]
        self.assertGreaterEqual(len(plans), len(reports))
        for plan, r in zip(plans, reports):
            self.assertEqual(plan.header.frame_id, "world")
            self.assertEqual(plan.foothold_sides[0], r.swing_side)
            self.assertEqual(len(plan.modes), len(plan.durations))
            self.assertTrue(all(d > 0 for d in plan.durations))

    def test_joint_states_and_contacts(self):
        js = self.msgs["/joint_states"][-1]
        self.assertEqual(len(js.name), len(js.position))
        self.assertEqual(len(js.name), len(js.effort))
        self.assertTrue(all(math.isfinite(v) for v in js.position + js.velocity + js.effort))
        for m in self.msgs["/contact_state"]:
            self.assertEqual(m.header.frame_id, "world")
            self.assertEqual(len(m.frames), 2)
            self.assertIn(m.contact_mode, ("DS", "SS-L", "SS-R"))
        # In double support at the end, both soles carry the weight (measured normal forces).
        last = self.msgs["/contact_state"][-1]
        if not self.fell and last.contact_mode == "DS":
            fz = sum(w.force.z for w in last.measured)
            self.assertGreater(fz, 100.0)

    def test_checks_match_step_reports(self):
        if not self.checked:  # no check: nothing checked, nothing published about it
            for t in CHECK_TOPICS:
                self.assertNotIn(t, self.bag_topics, "%s in a %s walk" % (t, self.mode))
            for r in self.msgs["/step_report"]:
                self.assertEqual(r.verdict, "not_checked", "step %d" % r.index)
                self.assertEqual(r.ocp_status, "none", "step %d" % r.index)
            return
        walk = self.config.get("walk", {})
        swing = float(walk.get("single_support_duration", 0.22))
        # The walking check's horizon (WalkConfig::check_horizon replaces reach.horizon).
        horizon = float(walk.get("check_horizon", 0.2))
        # With replanning during the swing, plan_time is no longer the lift-off.
        lift_off_is_plan_time = float(walk.get("replan_fraction", 0.0)) == 0.0
        reports = [r for r in self.msgs["/step_report"] if r.verdict in CHECKED_VERDICTS]
        results = self.msgs.get("/reachability_result", [])
        markers = self.msgs.get("/reachability_markers", [])
        trajectories = self.msgs.get("/transition_trajectory", [])
        transition_markers = self.msgs.get("/transition_markers", [])
        self.assertGreater(len(reports), 0, "no checked step in a proposed walk")
        self.assertEqual(len(results), len(reports), "one reachability_result per checked step")
        self.assertEqual(len(markers), len(reports), "one reachability_markers per checked step")
        self.assertEqual(len(trajectories), len(reports),
                         "one transition_trajectory per checked step")
        self.assertEqual(len(transition_markers), len(reports),
                         "one transition_markers per checked step")
        prev = -1.0
        for res, rep, arr, traj, tm in zip(results, reports, markers, trajectories,
                                           transition_markers):
            what = "step %d" % rep.index
            stamp = res.header.stamp.to_sec()
            # The check runs between planning and touchdown, steps in order.
            self.assertGreater(stamp, rep.plan_time, what)
            if rep.touched_down:
                self.assertLess(stamp, rep.touchdown_time, what)
            self.assertGreater(stamp, prev, what)
            prev = stamp
            if lift_off_is_plan_time:  # the first tick with t - lift-off >= swing - horizon
                since = stamp - rep.plan_time
                self.assertGreaterEqual(since, swing - horizon - 1e-6, what)
                self.assertLessEqual(since, swing - horizon + self.dt + 1e-6, what)
            self.assertEqual(res.header.frame_id, "world", what)
            # A ring point that stood in for the target (on_fail=nearest_reachable): its check,
            # certified. A kinematically infeasible foothold is "unreachable" with the IK's
            # reason and no sets, as reachability_node answers it.
            stand_in = rep.foothold_source == "nearest_reachable"
            if stand_in:
                self.assertEqual(res.verdict, "reachable", what)
                self.assertGreater(len(res.slices), 0, what)
            elif rep.verdict == "kinematically_infeasible":
                self.assertEqual(res.verdict, "unreachable", what)
                self.assertTrue(res.message.startswith("kinematically infeasible foothold"),
                                res.message)
                self.assertEqual(len(res.slices), 0, what)
            else:
                self.assertEqual(res.verdict, rep.verdict, what)
                self.assertGreater(len(res.slices), 0, what)
                for s in res.slices:
                    self.assertEqual(s.header.frame_id, "world", what)
                if rep.hausdorff_distance >= 0 and res.hausdorff_distance >= 0:
                    self.assertAlmostEqual(res.hausdorff_distance, rep.hausdorff_distance,
                                           delta=1e-12, msg=what)
            self.assertEqual(res.swing_frame, "l_sole" if rep.swing_side == "left" else "r_sole")
            # The checked foothold is the TVR foothold (no bounds in the proposed mode), or the
            # ring point aimed at in its place, on the ground.
            aimed = rep.planned if stand_in else rep.planned_tvr
            tol = 1e-3 if stand_in else 1e-9  # "planned": the strict OCP's landing there
            self.assertAlmostEqual(res.foothold.x, aimed.x, delta=tol, msg=what)
            self.assertAlmostEqual(res.foothold.y, aimed.y, delta=tol, msg=what)
            if rep.touched_down:
                self.assertLess(abs(res.foothold.z - rep.executed.z), 0.01, what)
            # Markers: in "world", from the check on, the checked foothold among them.
            self.assertGreater(len(arr.markers), 0, what)
            for mk in arr.markers:
                self.assertEqual(mk.header.frame_id, "world", "%s %s" % (what, mk.ns))
                self.assertGreaterEqual(mk.header.stamp.to_sec(), stamp - 1e-9, mk.ns)
            feet = [mk for mk in arr.markers if mk.ns == "checked_foothold"]
            self.assertEqual(len(feet), 1, what)
            self.assertAlmostEqual(feet[0].pose.position.x, res.foothold.x, places=9)
            self.assertAlmostEqual(feet[0].pose.position.y, res.foothold.y, places=9)
            # The OCP's trajectory from the same x_0: knot times increasing, row-major sizes.
            self.assertEqual(traj.header.frame_id, "world", what)
            self.assertAlmostEqual(traj.header.stamp.to_sec(), stamp, places=9, msg=what)
            self.assertIn(traj.status, ("converged", "relaxed", "failed"), what)
            self.assertEqual(traj.status, rep.ocp_status, what)
            t = list(traj.time)
            self.assertTrue(all(b > a for a, b in zip(t, t[1:])), "%s: knot times %s" % (what, t))
            self.assertEqual(len(traj.q), len(t) * len(traj.joint_names), what)
            self.assertEqual(len(traj.u), len(t) * len(traj.actuated_joint_names), what)
            if t:  # the OCP ran: knots from x_0 to t_f = t_0 + horizon
                self.assertEqual(t[0], 0.0, what)
                self.assertAlmostEqual(t[-1], horizon, places=9, msg=what)
                self.assertTrue(all(math.isfinite(v) for v in traj.q), what)
                # The swing sole's path: one point per trajectory sample, in "world", ending
                # on the trajectory's landing point.
                path = [mk for mk in tm.markers if mk.ns == "transition_swing_path"]
                self.assertEqual(len(path), 1, what)
                self.assertEqual(path[0].header.frame_id, "world", what)
                self.assertEqual(len(path[0].points), len(t), what)
                end = path[0].points[-1]
                self.assertLess(math.dist((end.x, end.y, end.z),
                                          (traj.final_foothold.x, traj.final_foothold.y,
                                           traj.final_foothold.z)), 1e-6, what)
            else:
                self.assertEqual(traj.status, "failed", what)
                self.assertEqual(len(tm.markers), 0, what)

    def test_rosbag_info(self):
        out = subprocess.run(["rosbag", "info", self.bag_path], capture_output=True, text=True,
                             timeout=60)
        self.assertEqual(out.returncode, 0, out.stderr)
        for t in self.topics:
            self.assertIn(t, out.stdout)

    def test_rosbags_independent_reader(self):
        repo = os.environ.get("REACH_REPO") or os.path.abspath(
            os.path.join(os.path.dirname(os.path.realpath(__file__)), "..", ".."))
        python = os.path.join(repo, ".venv", "bin", "python")
        if not os.path.exists(python):
            self.skipTest("project venv (with rosbags) not found at %s" % python)
        out = subprocess.run([python, "-c", ROSBAGS_SCRIPT, self.bag_path], capture_output=True,
                             text=True, timeout=120)
        self.assertEqual(out.returncode, 0, out.stderr)
        data = json.loads(out.stdout)
        for t in self.topics:
            self.assertEqual(data["counts"].get(t), len(self.msgs[t]), t)
        ours = [[int(r.index), r.swing_side, r.executed.x, r.executed.y, r.planned.x,
                 r.planned.y, r.touchdown_time] for r in self.msgs["/step_report"]]
        self.assertEqual(data["steps"], ours)


if __name__ == "__main__":
    rostest.rosrun(PKG, "walk_bag", WalkBagTest, sys.argv)
