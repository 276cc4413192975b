"""FK, Jacobians and IK through the Python API, against independent computations (the Robotics
Toolbox's reference data, finite differences, round trips) and against the Rust library's own
answers (the `armlab` command line)."""

import json

import numpy as np
import pytest

import armlab

REFERENCE_MODELS = [
    "planar2", "planar3", "anthropomorphic3r", "spherical_arm",
    "anthropomorphic_spherical_wrist", "puma560", "lwr4", "panda",
]


def _as_array(v):
    return np.array(json.loads(v) if isinstance(v, str) else v, dtype=float)


@pytest.mark.parametrize("model", REFERENCE_MODELS)
def test_fk_matches_the_robotics_toolbox_single_and_batch(model, reference):
    data = reference(f"fk_{model}.json")
    q = _as_array(data["q"])
    T = _as_array(data["T"])
    r = armlab.Robot.builtin(model)
    batch = r.fk(q)
    assert batch.shape == (len(q), 4, 4)
    assert np.abs(batch - T).max() < 1e-12
    for i in range(0, len(q), 50):
        single = r.fk(q[i])
        assert single.shape == (4, 4)
        assert np.array_equal(single, batch[i])


def test_fk_frames_batch_equals_single_and_ends_at_the_flange():
    r = armlab.Robot.builtin("puma560")
    Q = np.random.default_rng(3).uniform(-2, 2, (40, 6))
    frames = r.fk(Q, frames=True)
    assert frames.shape == (40, len(r.frame_names), 4, 4)
    for i in (0, 17, 39):
        assert np.array_equal(frames[i], r.fk(Q[i], frames=True))
    # The Puma's tool is the identity: the last joint frame is the tool frame.
    assert np.abs(frames[:, -1] - r.fk(Q)).max() < 1e-15


def test_fk_out_writes_in_place_and_accepts_lists_and_ints():
    r = armlab.Robot.builtin("puma560")
    Q = np.random.default_rng(4).uniform(-2, 2, (1000, 6))
    out = np.empty((1000, 4, 4))
    res = r.fk(Q, out=out)
    assert res is out
    assert np.array_equal(out, r.fk(Q))
    assert np.array_equal(r.fk([0, 1, 0, 0, 0, 0]), r.fk(np.array([0.0, 1.0, 0, 0, 0, 0])))
    assert np.array_equal(r.fk(Q[::2]), r.fk(np.ascontiguousarray(Q[::2])))  # strided input


def _twist_fd(r, q, h=1e-6):
    """The geometric Jacobian by central differences of FK: linear rows from the position,
    angular rows from (R(q+h) - R(q-h)) R^T / 2h, written here apart from the library."""
    J = np.zeros((6, r.dof))
    R = r.fk(q)[:3, :3]
    for k in range(r.dof):
        dq = np.zeros(r.dof)
        dq[k] = h
        Tp, Tm = r.fk(q + dq), r.fk(q - dq)
        J[:3, k] = (Tp[:3, 3] - Tm[:3, 3]) / (2 * h)
        S = (Tp[:3, :3] - Tm[:3, :3]) / (2 * h) @ R.T
        J[3:, k] = [S[2, 1], S[0, 2], S[1, 0]]
    return J


@pytest.mark.parametrize("model", ["puma560", "stanford", "dlr", "scara", "panda"])
def test_jacobian_against_finite_differences(model):
    r = armlab.Robot.builtin(model)
    q = np.random.default_rng(5).uniform(-1, 1, r.dof)
    J = r.jacobian(q)
    assert J.shape == (6, r.dof)
    assert np.abs(J - _twist_fd(r, q)).max() < 1e-7


def test_manipulability_of_the_two_link_arm_is_a1_a2_sin_q2():
    r = armlab.Robot.builtin("planar2")  # a1 = a2 = 1 m
    for q2 in (0.3, 1.2, -2.0, 0.0):
        assert abs(r.manipulability([0.4, q2]) - abs(np.sin(q2))) < 1e-12


def _rotation_error(A, B):
    c = (np.trace(A[:3, :3].T @ B[:3, :3]) - 1) / 2
    return float(np.arccos(np.clip(c, -1, 1)))


def test_puma_ik_gives_8_labelled_solutions_equal_to_the_command_line(cli):
    r = armlab.Robot.builtin("puma560")
    T = r.fk([0.1] * 6)
    sols = r.ik(T, all=True)
    assert len(sols) == 8 and sols.status == "ok"
    assert len({s.posture for s in sols}) == 8
    for s in sols:
        back = r.fk(s.q)
        assert np.abs(back[:3, 3] - T[:3, 3]).max() < 1e-12
        assert _rotation_error(back, T) < 1e-9
    pose = ",".join(repr(float(v)) for v in T.reshape(-1))
    theirs = cli("ik", "puma560", "--pose", pose, "--all", "--format", "json")[0]["solutions"]
    assert [s.posture for s in sols] == [s["posture"] for s in theirs]
    for mine, other in zip(sols, theirs):
        assert np.array_equal(mine.q, np.array(other["q"]))
        assert mine.within_limits == other["within_limits"]
        assert mine.parts == other["posture_parts"]
    # The fields spell the label (written here from the textbook's words, not by the library).
    words = {"no_flip": "no flip"}
    for s in sols:
        p = s.parts
        assert p["solver"] == "closed_form" and p["branch"] is None
        label = f"shoulder {p['shoulder']}, elbow {p['elbow']}, wrist {words.get(p['wrist'], p['wrist'])}"
        assert s.posture == label
    # The one asked for by posture, and the closest to a seed.
    one = r.ik(T, posture="shoulder left, elbow up, wrist flip")
    assert one.posture == "shoulder left, elbow up, wrist flip"
    assert np.abs(r.ik(T, seed=[0.1] * 6).q - 0.1).max() < 1e-9


def test_ik_batch_equals_single_calls_and_round_trips():
    r = armlab.Robot.builtin("puma560")
    Q = np.random.default_rng(6).uniform(r.limits[:, 0], r.limits[:, 1], (300, 6))
    Ts = r.fk(Q)
    b = r.ik(Ts)
    assert b.q.shape == (300, 8, 6) and b.valid.shape == (300, 8)
    assert (b.counts() <= 8).all()
    for i in range(0, 300, 7):
        single = r.ik(Ts[i], all=True)
        got = {(b.labels[int(c)], tuple(np.round(q, 9))) for q, c, v in zip(b.q[i], b.posture[i], b.valid[i]) if v}
        want = {(s.posture, tuple(np.round(s.q, 9))) for s in single}
        assert got == want
    # Every valid slot is a solution (FK in batch), and the original configuration is among them.
    flat = b.q[b.valid]
    back = r.fk(flat)
    idx = np.nonzero(b.valid)[0]
    assert np.abs(back[:, :3, 3] - Ts[idx, :3, 3]).max() < 1e-10
    for i in range(300):
        d = np.abs(((b.q[i, b.valid[i]] - Q[i]) + np.pi) % (2 * np.pi) - np.pi).max(axis=1)
        assert d.min() < 1e-9
    assert armlab.posture_label(106) == "shoulder right, elbow up, wrist no flip"
    assert b.labels[106] == "shoulder right, elbow up, wrist no flip"


def test_ur5_urdf_gives_8_labelled_solutions(root, cli):
    r = armlab.Robot.load(root / "tests/data/urdf_corpus/ur5_robot.urdf")
    assert r.dof == 6 and r.closed_form is not None
    q = np.array([0.3, -1.1, 1.4, -0.6, 1.2, 0.5])
    T = r.fk(q)
    sols = r.ik(T, all=True)
    assert len(sols) == 8 and len({s.posture for s in sols}) == 8
    for s in sols:
        assert np.abs(r.fk(s.q) - T).max() < 1e-10
    pose = ",".join(repr(float(v)) for v in T.reshape(-1))
    theirs = cli("ik", root / "tests/data/urdf_corpus/ur5_robot.urdf", "--pose", pose, "--all", "--format", "json")
    assert [s.posture for s in sols] == [s["posture"] for s in theirs[0]["solutions"]]
    b = r.ik(T[None])
    assert int(b.counts()[0]) == 8


def test_batch_ik_of_an_arm_without_closed_form_is_numerical_and_equals_single_calls():
    r = armlab.Robot.builtin("panda")
    Q = np.random.default_rng(8).uniform(r.limits[:, 0], r.limits[:, 1], (40, 7))
    Ts = r.fk(Q)
    b = r.ik(Ts, seed=Q + 0.05)
    assert b.q.shape == (40, 1, 7) and b.labels == {0: "numerical"}
    assert b.valid.all() and (b.position_error < 1e-10).all()
    assert np.abs(r.fk(b.q[:, 0]) - Ts).max() < 1e-9
    for i in (0, 13, 39):
        single = r.ik_numerical(Ts[i], q0=Q[i] + 0.05)
        assert np.array_equal(single.q, b.q[i, 0])


def test_numerical_ik_converges_and_reports():
    r = armlab.Robot.builtin("panda")
    q = np.array([0.2, -0.4, 0.1, -2.0, 0.3, 1.8, 0.5])
    T = r.fk(q)
    rep = r.ik_numerical(T, q0=q + 0.2)
    assert rep.converged and rep.position_error < 1e-10
    assert np.abs(r.fk(rep.q) - T).max() < 1e-9
    sol = r.ik(T)  # no closed form: the numerical solver, seeded from "ready"
    assert sol is not None and sol.posture.startswith("numerical")
    assert sol.parts == {"solver": "numerical", "converged": True}


def test_reach_equals_the_command_line(cli, tmp_path):
    r = armlab.Robot.builtin("anthropomorphic3r")
    pts = np.array([[0.5, 0.2, 0.3], [2.5, 0.0, 0.0], [0.0, 0.0, 1.0], [1.0, 1.0, 0.5]])
    mine = r.reach(pts)
    f = tmp_path / "points.csv"
    f.write_text("\n".join(",".join(repr(float(v)) for v in p) for p in pts))
    theirs = cli("reach", "anthropomorphic3r", "--input", f, "--format", "json")
    assert list(mine.reachable) == [t["reachable"] for t in theirs]
    assert list(mine.distance) == [t["distance"] for t in theirs]
    assert mine.postures == [t["postures"] for t in theirs]


def test_workspace_statistics_and_png_equal_the_command_line(cli, tmp_path):
    r = armlab.Robot.builtin("anthropomorphic_spherical_wrist")
    w = r.workspace(point="flange", size=(600, 450))
    out = tmp_path / "w.png"
    theirs = cli("workspace", "anthropomorphic_spherical_wrist", "--point", "flange", "--size", "600x450",
                 "--out", out, "--format", "json")
    assert w.volume == theirs["volume"] and w.max_reach == theirs["max_reach"]
    assert w.reach_exact and abs(w.max_reach - 1.1) < 1e-12 and w.min_reach == 0.0
    assert abs(w.volume - 4 / 3 * np.pi * 1.1 ** 3) < 1e-3 * w.volume  # the ball of radius 1.1 m
    assert w.figure.png == out.read_bytes()
    assert w.figure.size == (600, 450)


def test_self_motion_equals_the_command_line(cli):
    r = armlab.Robot.builtin("dlr")
    T = r.fk(np.array([0.3, 0.5, -0.2, 1.1, 0.4, -0.6, 0.2]))
    m = r.self_motion(T, samples=72, figure=False)
    pose = ",".join(repr(float(v)) for v in T.reshape(-1))
    theirs = cli("self-motion", "dlr", "--pose", pose, "--samples", "72", "--format", "json")
    assert m.parameter == theirs["parameter"] and m.exact
    assert {k: [list(iv) for iv in v] for k, v in m.feasible.items()} == theirs["feasible"]
    # Every sample of every branch holds the hand (FK written apart: the batch call).
    for name, q in m.q.items():
        ok = ~np.isnan(q).any(axis=1)
        assert np.abs(r.fk(q[ok]) - T).max() < 1e-9


def test_symbolic_equals_the_command_line(cli):
    s = armlab.Robot.builtin("planar3").symbolic()
    assert s.text == cli("symbolic", "planar3", json_out=False)
    assert "c123" in s.text and "\\begin{bmatrix}" in s.latex


def test_dh_table_and_description():
    r = armlab.Robot.builtin("puma560")
    dh = r.dh
    assert len(dh) == 6 and dh.convention == "standard"
    assert abs(dh[1].a - 0.4318) < 1e-12 and abs(dh[0].alpha - np.pi / 2) < 1e-12
    assert dh.to_array().shape == (6, 4)
    assert r.limits.shape == (6, 2) and r.end_effectors == ["tool"]
    assert "puma560" in armlab.Robot.builtins()
