"""Collisions from Python: ``robot.collisions(q, scene=...)`` and the collision fields of
``robot.ik``, checked against distances computed here from ``fk`` (a sphere on the tool point
must collide, one far away must not, and the clearance to a sphere ahead of the tool is the
distance computed by hand, within the size of the links' bodies) and against the command line."""


import numpy as np
import pytest

import armlab

Q = np.array([0.3, -0.8, 1.9, 0.2, 0.5, 0.1])
KEYS = {"in_collision", "pairs", "clearance_m", "closest"}
# The stick figure's bodies around a frame origin: capsules of the link radius (1.8 % of the
# arm's size, 16 mm for the Puma) and joint cylinders of 1.9 link radii; three link radii bound
# how far the arm's surface lies beyond the tool point towards a sphere ahead of it.
BODY_TOLERANCE_M = 0.05


@pytest.fixture(scope="module")
def puma():
    return armlab.Robot.builtin("puma560")


def sphere(name, radius, centre):
    x, y, z = (repr(float(c)) for c in centre)
    return (
        f'[[obstacle]]\nname = "{name}"\nshape = "sphere"\nsize = [{float(radius)!r}]\n'
        f"xyz = [{x}, {y}, {z}]\n"
    )


@pytest.fixture(scope="module")
def puma_without_self_checks(tmp_path_factory, cli):
    """The Puma as a TOML model file with every pair of its links disabled (written here), so
    that only obstacles are checked."""
    path = tmp_path_factory.mktemp("model") / "puma.toml"
    cli("export", "puma560", "--toml", path, json_out=False)
    links = ["base"] + [f"link{i}" for i in range(1, 7)]
    tables = "".join(
        f'\n[[disable_collisions]]\nlink1 = "{a}"\nlink2 = "{b}"\nreason = "User"\n'
        for i, a in enumerate(links)
        for b in links[i + 1:]
    )
    path.write_text(path.read_text() + tables)
    return armlab.Robot.load(path)


def test_a_sphere_on_the_tool_point_collides_and_one_far_away_does_not(puma):
    p = puma.fk(Q)[:3, 3]
    r = puma.collisions(Q, scene=sphere("ball", 0.05, p))
    assert set(r) == KEYS
    assert r["in_collision"] is True and r["clearance_m"] == 0.0
    hits = [c for c in r["pairs"] if c["b"] == "ball"]
    assert hits, r
    # The tool point is on the last link: the sphere's centre is inside the arm, so separating
    # them takes at least the sphere's radius.
    assert max(c["depth_m"] for c in hits) >= 0.05
    for c in r["pairs"]:
        assert {"a", "b", "depth_m"} <= set(c) <= {"a", "b", "depth_m", "at"}
    far = puma.collisions(Q, scene=sphere("ball", 0.05, p + [0.0, 0.0, 5.0]))
    assert set(far) == KEYS
    assert not any(c["b"] == "ball" for c in far["pairs"]), far


def test_the_clearance_to_a_sphere_ahead_of_the_tool_is_the_distance_by_hand(
    puma, puma_without_self_checks
):
    robot = puma_without_self_checks
    T = robot.fk(Q)
    assert np.abs(T - puma.fk(Q)).max() < 1e-12
    p, approach = T[:3, 3], T[:3, 2]
    radius, ahead = 0.05, 0.3
    centre = p + ahead * approach
    r = robot.collisions(Q, scene=sphere("ball", radius, centre))
    assert r["in_collision"] is False and r["closest"]["b"] == "ball", r
    by_hand = np.linalg.norm(centre - p) - radius
    # The tool point is on the arm: the clearance is at most the distance from it; the arm's
    # bodies around it are at most a few link radii thick.
    assert r["clearance_m"] <= by_hand + 1e-9
    assert r["clearance_m"] >= by_hand - BODY_TOLERANCE_M


def test_a_scene_file_and_its_text_give_the_same_report_and_batches_give_lists(puma, tmp_path):
    p = puma.fk(Q)[:3, 3]
    text = sphere("ball", 0.05, p)
    path = tmp_path / "cell.toml"
    path.write_text(text)
    one = puma.collisions(Q, scene=path)
    assert one == puma.collisions(Q, scene=str(path)) == puma.collisions(Q, scene=text)
    both = puma.collisions(np.stack([Q, Q + [np.pi, 0, 0, 0, 0, 0]]), scene=path)
    assert isinstance(both, list) and len(both) == 2 and both[0] == one
    assert not any(c["b"] == "ball" for c in both[1]["pairs"])
    # Without a scene: the arm's own links only.
    alone = puma.collisions(Q)
    assert set(alone) == KEYS
    assert all(c["b"] != "ball" for c in alone["pairs"])


def test_the_same_report_as_the_command_line(puma, cli, tmp_path):
    path = tmp_path / "cell.toml"
    path.write_text(sphere("ball", 0.08, puma.fk(Q)[:3, 3]))
    q = ",".join(repr(float(v)) for v in Q)
    theirs = cli("collisions", "puma560", "--q", q, "--scene", path, "--format", "json")
    assert puma.collisions(Q, scene=path) == theirs


def test_ik_solutions_carry_the_command_lines_collision_fields(puma, cli, tmp_path):
    T = puma.fk(Q)
    path = tmp_path / "cell.toml"
    path.write_text(sphere("ball", 0.08, T[:3, 3]))
    sols = puma.ik(T, all=True, scene=path)
    assert len(sols) == 8
    pose = ",".join(repr(float(v)) for v in T.reshape(-1))
    theirs = cli("ik", "puma560", "--pose", pose, "--all", "--scene", path, "--format", "json")[0]
    for mine, other in zip(sols, theirs["solutions"]):
        assert np.array_equal(mine.q, np.array(other["q"]))
        assert mine.collision == other["collision"]
        assert mine.clearance_m == other["clearance_m"]
    # Every solution reaches the same tool point, where the sphere is: every one hits it.
    for s in sols:
        assert s.collision and any(c["b"] == "ball" for c in s.collision), s
        assert "hits ball" in s.collision_summary and "COLLIDES" in repr(s)
    # Without a scene: the arm's own links, still reported.
    free = puma.ik(T, all=True)
    assert all(s.clearance_m is not None for s in free)
    assert [s.collision for s in free] == [
        o["collision"]
        for o in cli("ik", "puma560", "--pose", pose, "--all", "--format", "json")[0]["solutions"]
    ]


def test_a_bad_scene_raises_collision_error_naming_file_line_and_obstacle(puma, tmp_path):
    path = tmp_path / "bad.toml"
    path.write_text('# a cell\n[[obstacle]]\nname = "slab"\nshape = "box"\nsize = [1, 0, 1]\n')
    with pytest.raises(armlab.CollisionError) as e:
        puma.collisions(Q, scene=path)
    message = str(e.value)
    assert "bad.toml:2" in message and '"slab"' in message and "degenerate" in message
    assert isinstance(e.value, armlab.ArmlabError)
    with pytest.raises(armlab.CollisionError, match="link9"):
        puma.ik(puma.fk(Q), scene='[[obstacle]]\nname = "t"\nshape = "sphere"\nsize = [0.1]\nframe = "link9"\n')
    with pytest.raises(armlab.CollisionError, match="cannot read"):
        puma.collisions(Q, scene=tmp_path / "missing.toml")
    with pytest.raises(TypeError):
        puma.collisions(Q, scene=3)
    with pytest.raises(ValueError):
        puma.collisions([0.1] * 5)
    with pytest.raises(ValueError, match="single target"):
        puma.ik(puma.fk(np.stack([Q, Q])), scene=path)
