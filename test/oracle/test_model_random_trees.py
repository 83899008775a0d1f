"""Random URDF trees through `model_info`, checked against Pinocchio.

Seeded random trees (model_oracle.random_urdf: chains and branches of revolute, continuous,
prismatic and fixed joints with random origins and rotations, chains of rotated fixed joints,
rotated inertial frames, massless links, a massless root carrying its mass on a rotated fixed
child, axes of random length) are loaded with a floating base; at random states M, b, the CoM and
its Jacobian, and the pose, Jacobian and Jdot*qd of every link agree with Pinocchio to 1e-8.
"""

import numpy as np

from conftest import SUMMARY_LINES

from model_oracle import ModelCheck, random_urdf

N_TREES = 300


def test_random_trees_agree_with_pinocchio(tmp_path):
    rng = np.random.default_rng(1234)
    failures = []
    for i in range(N_TREES):
        path = tmp_path / f"tree{i}.urdf"
        path.write_text(random_urdf(rng, f"tree{i}"))
        check = ModelCheck(path, tmp_path, f"tree{i}", floating=True, n_states=3, seed=i)
        failures += [f"{f} ({path})" for f in check.failures]
        if len(failures) > 40:
            break
    SUMMARY_LINES.append(f"model oracle: {N_TREES} random URDF trees checked against Pinocchio")
    assert not failures, "\n".join(failures[:40])
