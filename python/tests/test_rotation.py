"""armlab.rotation against rotations written out here with NumPy: every conversion round-trips on
10,000 random rotations and on the singular sets, both Euler solutions reproduce the matrix, and
the command line gives the same numbers."""

import numpy as np
import pytest

from armlab import rotation


def rx(a):
    c, s = np.cos(a), np.sin(a)
    o, z = np.ones_like(a), np.zeros_like(a)
    return np.stack([np.stack([o, z, z], -1), np.stack([z, c, -s], -1), np.stack([z, s, c], -1)], -2)


def ry(a):
    c, s = np.cos(a), np.sin(a)
    o, z = np.ones_like(a), np.zeros_like(a)
    return np.stack([np.stack([c, z, s], -1), np.stack([z, o, z], -1), np.stack([-s, z, c], -1)], -2)


def rz(a):
    c, s = np.cos(a), np.sin(a)
    o, z = np.ones_like(a), np.zeros_like(a)
    return np.stack([np.stack([c, -s, z], -1), np.stack([s, c, z], -1), np.stack([z, z, o], -1)], -2)


HAND = {
    "zyz": lambda a: rz(a[..., 0]) @ ry(a[..., 1]) @ rz(a[..., 2]),
    "zxz": lambda a: rz(a[..., 0]) @ rx(a[..., 1]) @ rz(a[..., 2]),
    "rpy": lambda a: rz(a[..., 0]) @ ry(a[..., 1]) @ rx(a[..., 2]),
}


def rodrigues(x):
    """R(theta, r) = cos I + (1 - cos) r r^T + sin S(r), written here."""
    theta, r = x[..., 0], x[..., 1:]
    r = r / np.linalg.norm(r, axis=-1, keepdims=True)
    c, s = np.cos(theta)[..., None, None], np.sin(theta)[..., None, None]
    S = np.zeros(r.shape[:-1] + (3, 3))
    S[..., 0, 1], S[..., 0, 2], S[..., 1, 2] = -r[..., 2], r[..., 1], -r[..., 0]
    S[..., 1, 0], S[..., 2, 0], S[..., 2, 1] = r[..., 2], -r[..., 1], r[..., 0]
    return c * np.eye(3) + (1 - c) * r[..., :, None] * r[..., None, :] + s * S


def random_rotations(n, seed=47):
    rng = np.random.default_rng(seed)
    a, c = rng.uniform(-np.pi, np.pi, n), rng.uniform(-np.pi, np.pi, n)
    b = np.arccos(rng.uniform(-1, 1, n))
    return rz(a) @ ry(b) @ rz(c)


def test_from_angles_is_the_product_of_elementary_rotations():
    rng = np.random.default_rng(1)
    A = rng.uniform(-np.pi, np.pi, (10_000, 3))
    for kind, hand in HAND.items():
        assert np.abs(rotation.convert_from(A, kind) - hand(A)).max() < 1e-15, kind
    # Problem 2.1 written out: r11 = c_phi c_psi - s_phi c_theta s_psi.
    R = rotation.from_zxz(A)
    p, t, s = A.T
    assert np.abs(R[:, 0, 0] - (np.cos(p) * np.cos(s) - np.sin(p) * np.cos(t) * np.sin(s))).max() < 1e-15


@pytest.mark.parametrize("kind", ["zyz", "zxz", "rpy"])
def test_both_euler_solutions_reproduce_10000_random_rotations(kind):
    R = random_rotations(10_000)
    first, second = rotation.convert_to(R, kind), rotation.convert_to(R, kind, second=True)
    assert first.shape == (10_000, 3)
    for A in (first, second):
        assert np.abs(HAND[kind](A) - R).max() < 1e-14
        assert np.all(np.abs(A) <= np.pi)
    if kind == "rpy":
        assert np.all(np.abs(first[:, 1]) <= np.pi / 2) and np.all(np.abs(second[:, 1]) >= np.pi / 2)
    else:
        assert np.all(first[:, 1] >= 0) and np.all(second[:, 1] <= 0)


def test_angles_come_back_where_they_are_in_range():
    rng = np.random.default_rng(2)
    A = np.column_stack([rng.uniform(-3.1, 3.1, 1000), rng.uniform(0.01, 3.13, 1000), rng.uniform(-3.1, 3.1, 1000)])
    for kind in ("zyz", "zxz"):
        assert np.abs(rotation.convert_to(HAND[kind](A), kind) - A).max() < 1e-12
    B = A - [0.0, np.pi / 2, 0.0]
    assert np.abs(rotation.to_rpy(HAND["rpy"](B)) - B).max() < 1e-12


def test_singular_sets_phi_zero_and_the_matrix_reproduced():
    rng = np.random.default_rng(3)
    phi, psi = rng.uniform(-np.pi, np.pi, 500), rng.uniform(-np.pi, np.pi, 500)
    for kind, thetas in (("zyz", (0.0, np.pi)), ("zxz", (0.0, np.pi)), ("rpy", (np.pi / 2, -np.pi / 2))):
        for theta in thetas:
            R = HAND[kind](np.column_stack([phi, np.full(500, theta), psi]))
            A = rotation.convert_to(R, kind)
            assert np.all(A[:, 0] == 0.0), (kind, theta)
            assert np.abs(HAND[kind](A) - R).max() < 1e-14


def test_axis_angle_and_quaternion_round_trip():
    R = random_rotations(10_000, seed=5)
    X = rotation.to_axis_angle(R)
    assert X.shape == (10_000, 4)
    assert np.all((X[:, 0] >= 0) & (X[:, 0] <= np.pi))
    assert np.abs(np.linalg.norm(X[:, 1:], axis=1) - 1).max() < 1e-15
    assert np.abs(rodrigues(X) - R).max() < 1e-14
    assert np.abs(rotation.from_axis_angle(X) - R).max() < 1e-14
    Q = rotation.to_quaternion(R)
    assert np.all(Q[:, 0] >= 0)
    # eta = cos(theta/2), epsilon = sin(theta/2) r, (2.30)-(2.31).
    assert np.abs(Q[:, 0] - np.cos(X[:, 0] / 2)).max() < 1e-12
    assert np.abs(Q[:, 1:] - np.sin(X[:, 0] / 2)[:, None] * X[:, 1:]).max() < 1e-12
    assert np.abs(rotation.from_quaternion(Q) - R).max() < 1e-14
    # -q is the same rotation, and the rows are normalized.
    assert np.abs(rotation.from_quaternion(-3 * Q) - R).max() < 1e-14
    # theta = 0 and pi.
    assert np.allclose(rotation.to_axis_angle(np.eye(3)), [0, 0, 0, 1])
    half = rotation.to_axis_angle(rodrigues(np.array([np.pi, 0.0, 3.0, -4.0])))
    assert abs(half[0] - np.pi) < 1e-15
    assert min(np.abs(half[1:] - [0.0, 0.6, -0.8]).max(), np.abs(half[1:] + [0.0, 0.6, -0.8]).max()) < 1e-15


def test_one_matrix_out_and_the_command_line(cli):
    R = rotation.from_zyz(np.radians([30.0, 45.0, 60.0]))
    assert R.shape == (3, 3)
    theirs = cli("rotation", "--from", "zyz:30,45,60", "--format", "json")
    assert np.abs(R - np.array(theirs["matrix"])).max() < 1e-15
    for kind in ("zyz", "zxz", "rpy"):
        ours = np.array([rotation.convert_to(R, kind), rotation.convert_to(R, kind, second=True)])
        assert np.abs(ours - np.array(theirs[kind]["solutions"])).max() < 1e-15, kind
    q = rotation.to_quaternion(R)
    assert np.abs(q - [theirs["quaternion"]["eta"], *theirs["quaternion"]["epsilon"]]).max() < 1e-15
    Rs = random_rotations(100)
    out = np.empty((100, 4))
    assert rotation.to_quaternion(Rs, out=out) is out
    assert np.abs(out - rotation.to_quaternion(Rs)).max() == 0.0
    back = np.empty((100, 3, 3))
    assert rotation.from_quaternion(out, out=back) is back


def test_bad_input_raises_value_error_naming_the_row():
    R = random_rotations(3)
    R[1, 0, 0] += 1e-3
    with pytest.raises(ValueError, match=r"R\[1\] is not a rotation matrix"):
        rotation.to_zyz(R)
    with pytest.raises(ValueError, match="reflection"):
        rotation.to_rpy(-np.eye(3))
    with pytest.raises(ValueError, match="non-finite"):
        rotation.to_zyz(np.full((2, 3, 3), np.nan))
    with pytest.raises(ValueError, match="shape"):
        rotation.to_zyz(np.zeros((2, 3, 4)))
    with pytest.raises(ValueError, match=r"X\[1\] has a zero quaternion"):
        rotation.from_quaternion([[1, 0, 0, 0], [0, 0, 0, 0]])
    with pytest.raises(ValueError, match="zero axis"):
        rotation.from_axis_angle([1.0, 0, 0, 0])
    with pytest.raises(ValueError, match="shape"):
        rotation.from_zyz(np.zeros((4, 4)))
    with pytest.raises(ValueError, match="unknown representation"):
        rotation.convert_to(np.eye(3), "xyz")
    with pytest.raises(ValueError, match="out must have shape"):
        rotation.to_zyz(random_rotations(2), out=np.empty((3, 3)))
