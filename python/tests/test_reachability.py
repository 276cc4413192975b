"""Reachability maps from Python: ``robot.reachability(...)`` (issue 49).

Checked against computations written here: the shapes and dtypes of the ``.npz`` file's
arrays; the directions, rolls and index from the issue's formulas; every posture bit set on
sampled entries is a solution of the package's IK with that posture label, within the limits,
that the package's FK puts on the sample pose rebuilt here from the issue's formulas; a box
takes out every sample whose tool point is inside it; and the arrays equal those of
``armlab reachability ... --out map.npz`` read with ``numpy.load``, key by key."""

import numpy as np
import pytest

import armlab

VOXEL, N, R = 0.2, 20, 2
KEYS = {
    "reachable", "postures", "posture_names", "index", "origin", "voxel", "size", "directions",
    "rolls", "end_effector", "model", "version", "solver", "collisions", "reach_centre", "reach",
}


@pytest.fixture(scope="module")
def puma():
    return armlab.Robot.builtin("puma560")


@pytest.fixture(scope="module")
def small_map(puma):
    return puma.reachability(voxel=VOXEL, directions=N, rolls=R)


def fibonacci(n):
    """The issue's Fibonacci sphere: z_i = 1 - (2i + 1)/n, rho_i = sqrt(1 - z_i^2),
    phi_i = i pi (3 - sqrt 5), d_i = (rho_i cos phi_i, rho_i sin phi_i, z_i)."""
    i = np.arange(n)
    z = 1 - (2 * i + 1) / n
    rho = np.sqrt(1 - z * z)
    phi = i * np.pi * (3 - np.sqrt(5))
    return np.stack([rho * np.cos(phi), rho * np.sin(phi), z], axis=1)


def sample_pose(m, i, j, k, d, r):
    """The tool pose of sample (i, j, k, d, r), from the issue's words: z = d_k; x = the unit
    vector of e - (e . d) d turned by r_j about d (e = world x, or world y when |d . x| > 0.9);
    the tool point at the voxel centre origin + voxel (i, j, k)."""
    z = fibonacci(m["directions"].shape[0])[d]
    e = np.array([0.0, 1.0, 0.0]) if abs(z[0]) > 0.9 else np.array([1.0, 0.0, 0.0])
    x0 = e - e.dot(z) * z
    x0 /= np.linalg.norm(x0)
    roll = 2 * np.pi * r / m["rolls"].shape[0]
    # Rodrigues about z (x0 is perpendicular to it).
    x = x0 * np.cos(roll) + np.cross(z, x0) * np.sin(roll)
    T = np.eye(4)
    T[:3, 0], T[:3, 1], T[:3, 2] = x, np.cross(z, x), z
    T[:3, 3] = m["origin"] + m["voxel"] * np.array([i, j, k])
    return T


def test_the_arrays_have_the_files_keys_shapes_and_dtypes(puma, small_map):
    m = small_map
    assert set(m) == KEYS
    nx, ny, nz = m["index"].shape
    assert m["reachable"].shape == (nx, ny, nz, N, R) and m["reachable"].dtype == np.bool_
    assert m["postures"].shape == (nx, ny, nz, N, R) and m["postures"].dtype == np.uint16
    assert m["index"].dtype == np.float64
    assert m["posture_names"].dtype.kind == "U" and len(m["posture_names"]) == 8
    assert m["origin"].shape == (3,) and m["directions"].shape == (N, 3) and m["rolls"].shape == (R,)
    assert isinstance(m["voxel"], float) and m["voxel"] == VOXEL
    np.testing.assert_allclose(m["size"], VOXEL * np.array([nx, ny, nz]), rtol=1e-15)
    np.testing.assert_allclose(m["directions"], fibonacci(N), atol=1e-14)
    np.testing.assert_allclose(m["rolls"], 2 * np.pi * np.arange(R) / R, atol=1e-15)
    # The index is the fraction of each voxel's N x R samples reached.
    np.testing.assert_array_equal(m["index"], m["reachable"].mean(axis=(3, 4)))
    # In closed form a sample is reached exactly when some posture reaches it.
    np.testing.assert_array_equal(m["reachable"], m["postures"] != 0)
    assert m["postures"].max() < 1 << 8
    assert m["model"] == puma.name and m["end_effector"] == puma.end_effectors[0]
    assert m["version"] == armlab.__version__
    assert m["solver"].startswith("closed form") and m["collisions"] is False
    assert m["reach_centre"].shape == (3,)
    assert m["reach"] > 0.8 and 0.05 < m["index"].mean() < 0.9


def test_every_posture_bit_set_is_a_solution_on_the_sample_pose(puma, small_map):
    m = small_map
    names = list(m["posture_names"])
    reached = np.argwhere(m["reachable"])
    rng = np.random.default_rng(49)
    checked = 0
    for i, j, k, d, r in reached[rng.choice(len(reached), size=80, replace=False)]:
        T = sample_pose(m, i, j, k, d, r)
        bits = int(m["postures"][i, j, k, d, r])
        sols = [s for s in puma.ik(T, all=True) if s.within_limits]
        labels = {s.posture for s in sols}
        for b in range(16):
            if bits >> b & 1:
                mine = [s for s in sols if s.posture == names[b]]
                assert mine, f"sample {(i, j, k, d, r)}: bit {names[b]!r} set, the IK has {labels}"
                for s in mine:
                    assert np.abs(puma.fk(s.q) - T).max() < 1e-9
                checked += 1
        # And no posture the IK finds within the limits is missing from the bits.
        for s in sols:
            if s.posture in names:
                assert bits >> names.index(s.posture) & 1, f"{s.posture} missing at {(i, j, k, d, r)}"
    assert checked >= 80


def test_a_box_takes_out_every_sample_with_the_tool_inside_it(puma):
    lo, hi = np.array([0.4, -1.5, 0.0]), np.array([1.0, 1.5, 0.6])
    centre, size = (lo + hi) / 2, hi - lo
    numbers = lambda v: ", ".join(repr(float(x)) for x in v)  # noqa: E731
    scene = (
        f'[[obstacle]]\nname = "block"\nshape = "box"\nsize = [{numbers(size)}]\n'
        f"xyz = [{numbers(centre)}]\n"
    )
    free = puma.reachability(voxel=VOXEL, directions=8, rolls=1)
    m = puma.reachability(voxel=VOXEL, directions=8, rolls=1, scene=scene)
    assert m["collisions"] is True and free["collisions"] is False
    assert m["reachable"].shape == free["reachable"].shape
    np.testing.assert_array_equal(m["origin"], free["origin"])
    # Collisions only take samples out.
    assert not (m["reachable"] & ~free["reachable"]).any()
    # The tool point is on the last link: with it inside the block, the link is in it.
    nx, ny, nz = m["index"].shape
    ijk = np.stack(np.meshgrid(np.arange(nx), np.arange(ny), np.arange(nz), indexing="ij"), -1)
    c = m["origin"] + VOXEL * ijk
    inside = np.all((c > lo + 0.01) & (c < hi - 0.01), axis=-1)
    assert free["reachable"][inside].any(), "the map without the block reaches into it"
    assert not m["reachable"][inside].any()
    assert m["reachable"][~inside].any()


def test_bad_options_are_refused_before_any_work(puma):
    with pytest.raises(ValueError, match="voxel edge must be a positive length"):
        puma.reachability(voxel=0.0)
    with pytest.raises(ValueError, match="directions must be at least 1"):
        puma.reachability(directions=0)
    with pytest.raises(ValueError, match="over the limit"):
        puma.reachability(voxel=0.002)
    with pytest.raises(ValueError, match="must not be negative"):
        puma.reachability(rolls=-1)
    with pytest.raises(ValueError, match="end-effectors are"):
        puma.reachability(ee="no such link")


def test_the_arrays_equal_the_command_lines_npz(cli, tmp_path, small_map):
    out = tmp_path / "map.npz"
    cli("reachability", "puma560", "--voxel", VOXEL, "--directions", N, "--rolls", R, "--out", out,
        json_out=False)
    with np.load(out) as f:
        assert set(f.files) == set(small_map)
        for key in f.files:
            theirs, mine = f[key], small_map[key]
            if key == "posture_names":
                assert list(theirs) == list(mine)
            elif theirs.dtype.kind == "U":
                assert theirs.shape == () and str(theirs) == mine, key
            else:
                mine = np.asarray(mine)
                assert theirs.dtype == mine.dtype and theirs.shape == mine.shape, key
                np.testing.assert_array_equal(theirs, mine, err_msg=key)
