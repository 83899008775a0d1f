"""Bad-input table of issue 17: every tool answers a bad input with a non-zero exit status (not a
signal, not a hang) and a message naming the offending key, option, file, link or joint, in the
four classes of the issue:
  crash     inputs that used to kill a tool (stack overflow, uncaught exception, segfault),
  silent    inputs that used to be accepted with garbage out,
  resource  inputs that used to run (or allocate) without bound,
  message   inputs whose error used to name the wrong thing.
Each row: (tool, arguments, files to write, words the message must contain)."""

import copy
import json
import time

import pytest

from conftest import REPO, run_tool

BIPED = REPO / "urdf" / "biped.urdf"
CONFIG = REPO / "config" / "biped.yaml"
NQ = 18


def biped_config_with(old, new):
    """config/biped.yaml's text with `old` replaced by `new` (which must occur)."""
    text = CONFIG.read_text()
    assert old in text, old
    return text.replace(old, new, 1)


def standing_q():
    q = [0.0] * NQ
    q[2] = 0.9
    return q


SWING_REQUEST = {
    "mode": "SS-L", "stance": {"position": [0.0, 0.1, 0.0], "yaw": 0.0},
    "target": {"position": [0.1, -0.1, 0.0]},
    "swing": {"position": [0.0, -0.1, 0.05], "velocity": [0.3, 0.0, 0.0]},
    "config": {"budgets": {"full": {"initial_samples": 200}}, "threads": 1},
}
TRANSITION_REQUEST = {
    "stance": "left", "stance_pose": {"position": [0.0, 0.1, 0.0], "yaw": 0.0},
    "swing_target": {"position": [0.2, -0.1, 0.0], "yaw": 0.0}, "horizon": 0.4,
    "q0": standing_q(),
}
TWO_LINKS = """<robot name="two">
  <link name="world"/>
  <link name="upper"><inertial><origin xyz="0 0 0.1"/><mass value="1.0"/>
    <inertia ixx="0.01" ixy="0" ixz="0" iyy="0.01" iyz="0" izz="0.01"/></inertial></link>
  <link name="lower"><inertial><mass value="0.5"/>
    <inertia ixx="0.002" ixy="0" ixz="0" iyy="0.002" iyz="0" izz="0.003"/></inertial></link>
  <joint name="shoulder" type="revolute"><parent link="world"/><child link="upper"/>
    <axis xyz="0 0 1"/><limit lower="-1" upper="1" effort="10" velocity="2"/></joint>
  <joint name="slide" type="prismatic"><parent link="upper"/><child link="lower"/>
    <origin xyz="0 0 0.2"/><axis xyz="1 0 0"/>
    <limit lower="-0.1" upper="0.1" effort="10" velocity="1"/></joint>
</robot>
"""


def edited(base, path, value):
    """A deep copy of `base` with the key path (a tuple) set to `value` (None deletes)."""
    out = copy.deepcopy(base)
    node = out
    for k in path[:-1]:
        node = node[k]
    if value is None:
        del node[path[-1]]
    else:
        node[path[-1]] = value
    return out


def urdf_with(old, new):
    assert old in TWO_LINKS
    return TWO_LINKS.replace(old, new, 1)


LOOP_URDF = """<robot name="loop"><link name="base"/><link name="thigh"/><link name="shin"/>
  <joint name="hip" type="fixed"><parent link="base"/><child link="thigh"/></joint>
  <joint name="knee" type="continuous"><parent link="thigh"/><child link="shin"/>
    <axis xyz="0 1 0"/></joint>
  <joint name="back" type="continuous"><parent link="shin"/><child link="thigh"/>
    <axis xyz="0 1 0"/></joint></robot>"""
ISLAND_LOOP_URDF = """<robot name="island"><link name="base"/><link name="a"/><link name="b"/>
  <joint name="ab" type="fixed"><parent link="a"/><child link="b"/></joint>
  <joint name="ba" type="fixed"><parent link="b"/><child link="a"/></joint></robot>"""
TWO_ROOTS_URDF = """<robot name="roots"><link name="base"/><link name="a"/><link name="b"/>
  <joint name="ab" type="fixed"><parent link="a"/><child link="b"/></joint></robot>"""

def alias_bomb(levels=9):
    """YAML whose aliases expand ninefold per level (issue 43: 306 bytes, 31 s in a config)."""
    y = "l0: &l0 [1, 1, 1, 1, 1, 1, 1, 1, 1]\n"
    for i in range(1, levels + 1):
        y += f"l{i}: &l{i} [" + ", ".join([f"*l{i - 1}"] * 9) + "]\n"
    return y


def trajectory_over(times):
    """A trajectory file of check_transition's format on the time axis `times`."""
    n = len(times)
    return {"time": times, "q": [standing_q()] * n, "qd": [[0.0] * NQ] * n,
            "qdd": [[0.0] * NQ] * n, "u": [[0.0] * (NQ - 6)] * n, "lambda": [[0.0] * 12] * n}


FIXTURE_REQUESTS = REPO / "test" / "fixtures" / "other_walks_requests.jsonl"

# (class, id, tool, args ({name} = a written file), files {name: text or JSON}, must mention)
CASES = [
    # ---- crash ------------------------------------------------------------------------------
    ("crash", "urdf_loop_model_info", "model_info", ["{u}"], {"u.urdf": LOOP_URDF},
     ["thigh", "tree"]),
    ("crash", "urdf_loop_reach_check", "reach_check", ["{u}", CONFIG, "{r}"],
     {"u.urdf": LOOP_URDF, "r.json": SWING_REQUEST}, ["thigh"]),
    ("crash", "urdf_loop_plan_transition", "plan_transition",
     ["{r}", "--urdf", "{u}"], {"u.urdf": LOOP_URDF, "r.json": TRANSITION_REQUEST}, ["thigh"]),
    ("crash", "urdf_island_loop", "model_info", ["{u}"], {"u.urdf": ISLAND_LOOP_URDF},
     ["loop"]),
    ("crash", "qp_number_overflow", "qp_solve", ["{p}"], {"p.json": '{"G":[[1e400]],"g":[1]}'},
     ["1e400"]),
    ("crash", "qp_deep_nesting", "qp_solve", ["{p}"], {"p.json": "[" * 20000 + "]" * 20000},
     ["object"]),
    ("crash", "reach_empty_swing_velocity", "reach_check", [BIPED, CONFIG, "{r}"],
     {"r.json": edited(SWING_REQUEST, ("swing", "velocity"), [])},
     ["swing.velocity: expected 3 numbers, got 0"]),
    ("crash", "reach_threads_100000", "reach_check", [BIPED, CONFIG, "{r}", "--threads", "100000"],
     {"r.json": SWING_REQUEST}, ["--threads"]),
    ("crash", "reach_config_not_object", "reach_check", [BIPED, CONFIG, "{r}"],
     {"r.json": edited(SWING_REQUEST, ("config",), [1, 2])}, ["config"]),
    # Found by fuzz_urdf (test/fuzz/regressions/urdf/massless_robot_com.urdf): a robot whose
    # every link is massless has no centre of mass.
    ("crash", "urdf_massless_robot", "model_info", ["{u}"],
     {"u.urdf": urdf_with('<mass value="1.0"/>\n    <inertia ixx="0.01" ixy="0" ixz="0" '
                          'iyy="0.01" iyz="0" izz="0.01"/>',
                          '<mass value="0"/><inertia ixx="0" ixy="0" ixz="0" iyy="0" '
                          'iyz="0" izz="0"/>').replace('<mass value="0.5"/>\n    <inertia '
                          'ixx="0.002" ixy="0" ixz="0" iyy="0.002" iyz="0" izz="0.003"/>',
                          '<mass value="0"/><inertia ixx="0" ixy="0" ixz="0" iyy="0" iyz="0" '
                          'izz="0"/>')}, ["no mass"]),
    ("crash", "state_empty_states", "model_info", [BIPED, "--state", "{s}"],
     {"s.json": {"states": []}}, ["states"]),
    ("crash", "transition_seed_ragged", "plan_transition", ["{r}"],
     {"r.json": edited(TRANSITION_REQUEST, ("seed",), {"time": [0, 0.4], "q": [[0.0]]})},
     ["seed.q"]),
    # ---- silent -----------------------------------------------------------------------------
    ("silent", "urdf_zero_axis", "model_info", ["{u}"],
     {"u.urdf": urdf_with('<axis xyz="0 0 1"/>', '<axis xyz="0 0 0"/>')}, ["shoulder", "axis"]),
    ("silent", "urdf_nan_axis", "model_info", ["{u}"],
     {"u.urdf": urdf_with('<axis xyz="1 0 0"/>', '<axis xyz="nan 0 0"/>')}, ["slide"]),
    ("silent", "urdf_negative_inertia", "model_info", ["{u}"],
     {"u.urdf": urdf_with('ixx="0.01"', 'ixx="-0.01"')}, ["upper", "semidefinite"]),
    ("silent", "urdf_triangle_inequality", "model_info", ["{u}"],
     {"u.urdf": urdf_with('izz="0.003"', 'izz="0.03"')}, ["lower", "triangle"]),
    ("silent", "urdf_negative_mass", "model_info", ["{u}"],
     {"u.urdf": urdf_with('<mass value="0.5"/>', '<mass value="-0.5"/>')}, ["lower", "mass"]),
    ("silent", "urdf_massless_with_inertia", "model_info", ["{u}"],
     {"u.urdf": urdf_with('<mass value="0.5"/>', '<mass value="0"/>')}, ["lower", "mass 0"]),
    ("silent", "urdf_unparsable_mass", "model_info", ["{u}"],
     {"u.urdf": urdf_with('<mass value="1.0"/>', '<mass value="1.0kg"/>')}, ["upper", "1.0kg"]),
    ("silent", "urdf_unparsable_origin", "model_info", ["{u}"],
     {"u.urdf": urdf_with('<origin xyz="0 0 0.2"/>', '<origin xyz="0 0 0.2x"/>')}, ["slide"]),
    ("silent", "urdf_two_roots", "model_info", ["{u}"], {"u.urdf": TWO_ROOTS_URDF},
     ["2 root links"]),
    ("silent", "urdf_child_of_two_joints", "model_info", ["{u}"],
     {"u.urdf": urdf_with("</robot>", '<joint name="extra" type="fixed"><parent link="world"/>'
                          '<child link="lower"/></joint></robot>')}, ["lower", "two joints"]),
    ("silent", "reach_short_swing_position", "reach_check", [BIPED, CONFIG, "{r}"],
     {"r.json": edited(SWING_REQUEST, ("swing", "position"), [0.0, -0.1])},
     ["swing.position", "3 numbers, got 2"]),
    ("silent", "reach_unknown_key_xF", "reach_check", [BIPED, CONFIG, "{r}"],
     {"r.json": edited(SWING_REQUEST, ("xF",), {"q": [], "qd": []})}, ["xF", "unknown key"]),
    ("silent", "reach_unknown_nested_key", "reach_check", [BIPED, CONFIG, "{r}"],
     {"r.json": edited(SWING_REQUEST, ("target", "yaww"), 0.1)}, ["target.yaww"]),
    ("silent", "transition_unknown_key", "plan_transition", ["{r}"],
     {"r.json": edited(TRANSITION_REQUEST, ("q_f",), standing_q())}, ["q_f"]),
    ("silent", "transition_target_inside_stance_sole", "plan_transition", ["{r}"],
     {"r.json": edited(TRANSITION_REQUEST, ("swing_target",),
                       {"position": [0.0, 0.1, 0.0], "yaw": 0.0})},
     ["swing_target", "infeasible"]),
    # The robot section (model/robot_config.h): a role without a joint, an unset variable, a
    # locked joint that does not exist or is held outside its limits, an unknown key.
    ("silent", "robot_role_unknown_joint", "walk_experiment", ["--config", "{c}", "--steps", "1"],
     {"c.yaml": biped_config_with("left_knee: l_knee", "left_knee: l_kneee")},
     ["robot.left_knee", "l_kneee"]),
    ("silent", "robot_urdf_unset_variable", "walk_experiment", ["--config", "{c}"],
     {"c.yaml": biped_config_with("urdf: urdf/biped.urdf", "urdf: ${NO_SUCH_VARIABLE_7}/b.urdf")},
     ["robot.urdf", "NO_SUCH_VARIABLE_7"]),
    ("silent", "robot_locked_joint_missing", "plan_transition", ["{r}", "--config", "{c}"],
     {"c.yaml": biped_config_with("locked_joints: {}", "locked_joints: {l_elbow: 0.1}"),
      "r.json": TRANSITION_REQUEST}, ["locked joint", "l_elbow"]),
    ("silent", "robot_locked_outside_limits", "model_info", ["--config", "{c}"],
     {"c.yaml": (REPO / "config" / "talos.yaml").read_text().replace(
         "arm_left_4_joint: -0.525366", "arm_left_4_joint: 5.0")},
     ["arm_left_4_joint", "limits"]),
    ("silent", "robot_locked_and_role", "walk_experiment", ["--config", "{c}"],
     {"c.yaml": biped_config_with("locked_joints: {}", "locked_joints: {l_hip_yaw: 0.0}")},
     ["left_hip_yaw", "locked_joints"]),
    ("silent", "robot_unknown_key", "reach_check", ["--config", "{c}", "{r}"],
     {"c.yaml": biped_config_with("  sim_sole_boxes:", "  sim_sole_box: true\n  sim_sole_boxes:"),
      "r.json": SWING_REQUEST}, ["robot.sim_sole_box", "unknown key"]),
    ("silent", "walk_steps_5x", "walk_experiment", ["--steps", "5x"], {}, ["--steps", "5x"]),
    ("silent", "walk_push_garbage", "walk_experiment", ["--push", "0,abc"], {}, ["--push"]),
    ("silent", "walk_unknown_policy", "walk_experiment", ["--policy", "fast"], {},
     ["unknown preset 'fast'"]),
    ("silent", "walk_ocp_swing_without_check", "walk_experiment",
     ["--policy", "baseline,swing=ocp"], {}, ["swing=ocp", "check"]),
    ("silent", "walk_yaml_mode_removed", "walk_experiment", ["--config", "{c}"],
     {"c.yaml": CONFIG.read_text().replace("  policy: baseline", "  mode: proposed")},
     ["walk.mode", "walk.policy"]),
    ("silent", "envelope_unknown_part", "push_envelope", ["--policies", "kinematic,speed=2"], {},
     ["unknown part 'speed'"]),
    ("silent", "envelope_decreasing_magnitudes", "push_envelope", ["--magnitudes", "0.4,0.2"],
     {}, ["magnitudes must increase"]),
    ("silent", "envelope_magnitude_garbage", "push_envelope", ["--magnitudes", "0.2,x"], {},
     ["--magnitudes"]),
    ("silent", "envelope_unwritable_svg", "push_envelope",
     ["--svg", "/nonexistent/dir/e.svg", "--steps", "1"], {}, ["--svg", "/nonexistent/dir/e.svg"]),
    ("silent", "transition_stride_2x", "plan_transition", ["{r}", "--stride", "2x"],
     {"r.json": TRANSITION_REQUEST}, ["--stride"]),
    ("silent", "wrench_cone_mu_garbage", "wrench_cone", ["--mu", "0.7x"], {}, ["--mu"]),
    ("silent", "yaml_misspelled_section", "reach_check", [BIPED, "{c}", "{r}"],
     {"c.yaml": "reahc:\n  initial_samples: 100\n", "r.json": SWING_REQUEST},
     ["reahc", "unknown key"]),
    ("silent", "yaml_duplicate_key", "reach_check", [BIPED, "{c}", "{r}"],
     {"c.yaml": "reach:\n  threads: 1\n  threads: 2\n", "r.json": SWING_REQUEST},
     ["reach.threads", "duplicate key", "c.yaml"]),
    ("silent", "yaml_duplicate_section", "plan_transition", ["{r}", "--config", "{c}"],
     {"c.yaml": "ocp:\n  segments: 4\nocp:\n  segments: 5\n", "r.json": TRANSITION_REQUEST},
     ["ocp", "duplicate key"]),
    ("silent", "qp_unknown_key", "qp_solve", ["{p}"], {"p.json": {"G": [[1]], "g": [1], "A": []}},
     ["A: unknown key"]),
    ("silent", "qp_inconsistent_sizes", "qp_solve", ["{p}"],
     {"p.json": {"G": [[1, 0], [0, 1]], "g": [1, 1], "Ain": [[1, 0]], "bin": [1, 2]}},
     ["bin", "expected 1 numbers, got 2"]),
    ("silent", "state_nan_string", "model_info", [BIPED, "--state", "{s}"],
     {"s.json": {"q": ["nan"] + [0.0] * (NQ - 1), "qd": [0.0] * NQ}}, ["q[0]"]),
    # ---- resource ---------------------------------------------------------------------------
    ("resource", "reach_initial_samples_1e7", "reach_check", [BIPED, CONFIG, "{r}"],
     {"r.json": edited(SWING_REQUEST, ("config", "budgets", "full", "initial_samples"),
                              10000000)},
     ["budgets.full.initial_samples"]),
    ("resource", "reach_max_boundary_1e6", "reach_check", [BIPED, CONFIG, "{r}"],
     {"r.json": edited(SWING_REQUEST, ("config", "budgets", "full", "max_boundary"),
                              1000000)}, ["budgets.full.max_boundary"]),
    ("resource", "reach_threads_in_config", "reach_check", [BIPED, CONFIG, "{r}"],
     {"r.json": edited(SWING_REQUEST, ("config", "threads"), 100000)}, ["threads"]),
    ("resource", "reach_long_horizon", "reach_check", [BIPED, CONFIG, "{r}"],
     {"r.json": edited(SWING_REQUEST, ("config",), {"horizon": 100.0, "window_start": 0.03,
                                                      "window_end": 0.05})}, ["horizon"]),
    ("resource", "reach_estimate_over_limit", "reach_check", [BIPED, CONFIG, "{r}"],
     {"r.json": edited(SWING_REQUEST, ("config",), {"budgets": {"full": {
         "max_boundary": 5000, "children_per_parent": 500}}})}, ["QPs"]),
    ("resource", "transition_horizon_1000", "plan_transition", ["{r}"],
     {"r.json": edited(TRANSITION_REQUEST, ("horizon",), 1000.0)}, ["horizon", "5"]),
    ("resource", "transition_many_slices", "plan_transition", ["{r}"],
     {"r.json": edited(TRANSITION_REQUEST, ("slices",),
                       [{"time": 0.1, "A": [[1, 0]], "b": [1]}] * 10001)}, ["slices"]),
    ("resource", "walk_steps_huge", "walk_experiment", ["--steps", "100000000000"], {},
     ["--steps"]),
    ("resource", "envelope_directions_huge", "push_envelope", ["--directions", "100000"], {},
     ["--directions"]),
    ("resource", "envelope_jobs_huge", "push_envelope", ["--jobs", "100000"], {}, ["--jobs"]),
    # Input files that never end: read up to their limit, then refused naming the file.
    ("resource", "walk_config_dev_zero", "walk_experiment", ["--config", "/dev/zero"], {},
     ["/dev/zero", "larger than"]),
    ("resource", "model_urdf_dev_zero", "model_info", ["/dev/zero"], {},
     ["/dev/zero", "larger than"]),
    ("resource", "transition_request_dev_zero", "plan_transition", ["/dev/zero"], {},
     ["/dev/zero", "larger than"]),
    ("resource", "verdict_grid_requests_dev_zero", "verdict_grid", ["--requests", "/dev/zero"],
     {}, ["/dev/zero", "larger than"]),
    # Config sizes that would allocate or run without bound, refused by key.
    ("resource", "walk_ocp_output_dt_tiny", "walk_experiment", ["--config", "{c}", "--steps", "2"],
     {"c.yaml": biped_config_with("output_dt: 0.001", "output_dt: 1.0e-9")}, ["c.yaml", "ocp", "output_dt"]),
    ("resource", "walk_ocp_segments_huge", "walk_experiment", ["--config", "{c}", "--steps", "2"],
     {"c.yaml": biped_config_with("segments: 4", "segments: 100000")}, ["c.yaml", "ocp", "segments"]),
    ("resource", "walk_max_sim_time_huge", "walk_experiment", ["--config", "{c}", "--steps", "2"],
     {"c.yaml": biped_config_with("fall_pelvis_height: 0.6",
                                  "fall_pelvis_height: 0.6\n  max_sim_time: 1.0e12")},
     ["c.yaml", "walk", "max_sim_time"]),
    # ---- message ----------------------------------------------------------------------------
    ("message", "qp_string_number", "qp_solve", ["{p}"], {"p.json": {"G": [[1]], "g": ["a"]}},
     ["g[0]"]),
    ("message", "qp_options_type", "qp_solve", ["{p}"],
     {"p.json": {"G": [[1]], "g": [1], "options": {"max_iterations": "ten"}}},
     ["options.max_iterations"]),
    ("message", "reach_x0_q_size", "reach_check", [BIPED, CONFIG, "{r}"],
     {"r.json": edited(edited(SWING_REQUEST, ("swing",), None), ("x0",),
                       {"q": [0.0] * 10, "qd": [0.0] * NQ})}, ["x0.q", "18"]),
    ("message", "reach_mode_unknown", "reach_check", [BIPED, CONFIG, "{r}"],
     {"r.json": edited(SWING_REQUEST, ("mode",), "SS-X")}, ["mode", "SS-X"]),
    ("message", "transition_horizon_string", "plan_transition", ["{r}"],
     {"r.json": edited(TRANSITION_REQUEST, ("horizon",), "abc")}, ["horizon"]),
    ("message", "transition_stance_pose_type", "plan_transition", ["{r}"],
     {"r.json": edited(TRANSITION_REQUEST, ("stance_pose", "position"), "here")},
     ["stance_pose.position"]),
    ("message", "state_qd_string", "model_info", [BIPED, "--state", "{s}"],
     {"s.json": {"q": standing_q(), "qd": [0.0, 0.0, 0.0, "x"] + [0.0] * (NQ - 4)}},
     ["qd[3]"]),
    ("message", "state_nested_size", "model_info", [BIPED, "--state", "{s}"],
     {"s.json": {"states": [{"q": standing_q(), "qd": [0.0] * NQ},
                            {"q": standing_q(), "qd": [0.0] * (NQ - 1)}]}}, ["states[1].qd"]),
    ("message", "qp_invalid_json", "qp_solve", ["{p}"], {"p.json": '{"G": [[1]], "g": [1'},
     ["p.json", "JSON"]),
    # check_transition: a trajectory with short wrench rows, a request without the x_f to check
    ("message", "check_transition_lambda_rows", "check_transition", ["{r}", "{t}"],
     {"r.json": edited(TRANSITION_REQUEST, ("qf",), standing_q()),
      "t.json": {"time": [0.0, 0.4], "q": [standing_q()] * 2, "qd": [[0.0] * NQ] * 2,
                 "qdd": [[0.0] * NQ] * 2, "u": [[0.0] * (NQ - 6)] * 2,
                 "lambda": [[0.0] * 11] * 2}}, ["t.json", "lambda"]),
    ("message", "check_transition_request_without_qf", "check_transition", ["{r}", "{r}"],
     {"r.json": TRANSITION_REQUEST}, ["r.json", "qf"]),
    # ---- issue 43 ---------------------------------------------------------------------------
    ("resource", "yaml_alias_bomb_config", "reach_check", [BIPED, "{c}", "{r}"],
     {"c.yaml": "reach:\n  initial_samples: 100\n" + alias_bomb(), "r.json": SWING_REQUEST},
     ["c.yaml", "line 4", "alias"]),
    ("resource", "yaml_alias_bomb_walk_config", "walk_experiment", ["--config", "{c}"],
     {"c.yaml": CONFIG.read_text() + alias_bomb()}, ["c.yaml", "alias"]),
    ("resource", "envelope_steps_over_time_limit", "push_envelope", ["--steps", "300"], {},
     ["--steps 300", "walk.max_sim_time"]),
    ("resource", "envelope_sweep_over_limit", "push_envelope",
     ["--directions", "64", "--fine", "--steps", "100"], {}, ["512000 footsteps", "--force"]),
    ("resource", "verdict_grid_over_limit", "verdict_grid",
     ["--requests", FIXTURE_REQUESTS, "--grid", "41"], {}, ["--grid 41", "--force"]),
    ("silent", "state_q_1e300", "model_info", [BIPED, "--state", "{s}"],
     {"s.json": {"q": [0.0, 0.0, 0.9, 1e300] + [0.0] * (NQ - 4), "qd": [0.0] * NQ}},
     ["s.json", "state 0", "q[3] = 1e+300"]),
    ("silent", "state_qd_1e300_b_not_finite", "model_info", [BIPED, "--state", "{s}"],
     {"s.json": {"q": standing_q(), "qd": [1e300] * NQ}}, ["s.json", "state 0", "qd[0]"]),
    ("silent", "frames_without_state", "model_info", [BIPED, "--frames", "l_sole"], {},
     ["--frames", "--state"]),
    ("silent", "check_transition_time_x10", "check_transition", ["{r}", "{t}"],
     {"r.json": edited(TRANSITION_REQUEST, ("qf",), standing_q()),
      "t.json": trajectory_over([0.0, 2.0, 4.0])}, ["t.json", "time", "[0, 0.4]"]),
    ("silent", "check_transition_time_shifted", "check_transition", ["{r}", "{t}"],
     {"r.json": edited(TRANSITION_REQUEST, ("qf",), standing_q()),
      "t.json": trajectory_over([1.0, 1.2, 1.4])}, ["t.json", "time", "[1, 1.4]"]),
    ("silent", "robot_joint_in_two_roles", "walk_experiment", ["--config", "{c}", "--steps", "1"],
     {"c.yaml": biped_config_with("left_knee: l_knee", "left_knee: r_knee")},
     ["robot.left_knee", "robot.right_knee", "r_knee"]),
    ("message", "qp_asymmetric_G", "qp_solve", ["{p}"],
     {"p.json": {"G": [[2, 1], [0, 2]], "g": [1, 1]}}, ["not symmetric", "G[1][0]"]),
    ("message", "transition_empty_hull", "plan_transition", ["{r}"],
     {"r.json": edited(TRANSITION_REQUEST, ("slices",),
                       [{"time": 0.2, "A": [[1, 0], [-1, 0]], "b": [0, -1]}])},
     ["slice 0", "empty hull"]),
    ("message", "walk_push_1e300", "walk_experiment", ["--push", "0,1e300"], {},
     ["--push", "1e300"]),
]


@pytest.mark.parametrize("cls,case_id,tool,args,files,words", CASES,
                         ids=[f"{c[0]}-{c[1]}" for c in CASES])
def test_bad_input(tmp_path, cls, case_id, tool, args, files, words):
    names = {}
    for name, content in files.items():
        path = tmp_path / name
        path.write_text(content if isinstance(content, str) else json.dumps(content))
        names[name.split(".")[0]] = path
    argv = [str(a).format(**names) if "{" in str(a) else a for a in args]
    start = time.monotonic()
    run = run_tool(tool, *argv, timeout=120)
    elapsed = time.monotonic() - start
    assert run.returncode > 0, ("expected a non-zero exit status, got " +
                                ("0" if run.returncode == 0 else f"signal {-run.returncode}") +
                                "\n" + run.describe())
    assert run.returncode < 128, "killed by a signal (or a sanitizer)\n" + run.describe()
    for w in words:
        assert w.lower() in run.output.lower(), f"message should name '{w}'\n" + run.describe()
    if cls == "resource":
        assert elapsed < 30, f"{tool} took {elapsed:.1f} s to reject an over-limit input"


def test_example_robot_data_still_loads():
    """The validation rejects no floating-base robot of example-robot-data the lead named."""
    from conftest import EXAMPLE_ROBOTS
    for rel in ["talos_data/robots/talos_reduced.urdf", "g1_description/urdf/g1_29dof.urdf",
                "romeo_description/urdf/romeo_small.urdf", "solo_description/robots/solo12.urdf",
                "anymal_c_simple_description/urdf/anymal.urdf", "icub_description/robots/icub.urdf",
                "go1_description/urdf/go1.urdf", "go2_description/urdf/go2.urdf",
                "hyq_description/robots/hyq_no_sensors.urdf", "bolt_description/robots/bolt.urdf"]:
        path = EXAMPLE_ROBOTS / rel
        if not path.exists():
            candidates = sorted(path.parent.glob("*.urdf"))
            assert candidates, f"no URDF in {path.parent}"
            path = candidates[0]
        run = run_tool("model_info", path)
        assert run.returncode == 0, run.describe()
