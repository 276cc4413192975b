"""Bad input raises a clear exception and never crashes: ValueError for arrays of the wrong
shape or dtype or with NaN, armlab's own exceptions (same messages as the Rust library's) for
models, IK and calibration."""

import threading
import time

import numpy as np
import pytest

import armlab


@pytest.fixture(scope="module")
def puma():
    return armlab.Robot.builtin("puma560")


@pytest.mark.parametrize(
    "q, words",
    [
        ([0.1] * 5, "shape (6)"),
        (np.zeros((2, 3, 6)), "shape"),
        (np.zeros((4, 5)), "shape (N, 6)"),
        (["a"] * 6, "real numbers"),
        (np.array([1j] * 6), "real numbers"),
        (np.array([True] * 6), "real numbers"),
        ([[0.1] * 6, [0.2] * 5], "real numbers"),
        (None, "real numbers"),
    ],
)
def test_fk_rejects_bad_arrays(puma, q, words):
    with pytest.raises(ValueError) as e:
        puma.fk(q)
    assert words in str(e.value)


def test_nan_is_named_with_its_index(puma):
    q = np.zeros(6)
    q[3] = np.nan
    with pytest.raises(ValueError, match=r"non-finite number \(NaN\) at index \[3\]"):
        puma.fk(q)
    Q = np.zeros((10, 6))
    Q[7, 2] = np.inf
    with pytest.raises(ValueError, match=r"at index \[7, 2\]"):
        puma.fk(Q)
    with pytest.raises(ValueError, match="non-finite"):
        puma.jacobian(q)
    T = np.eye(4)
    T[0, 3] = np.nan
    with pytest.raises(ValueError, match="T contains a non-finite"):
        puma.ik(T, all=True)


def test_batch_ik_names_the_pose_that_is_not_rigid(puma):
    Ts = puma.fk(np.zeros((5, 6)))
    Ts[3, 0, 0] = 2.0
    with pytest.raises(ValueError, match=r"Ts\[3\] is not a homogeneous transform"):
        puma.ik(Ts)
    with pytest.raises(ValueError, match=r"shape \(N, 4, 4\)"):
        puma.ik(np.zeros((5, 3, 4)))


def test_out_of_the_wrong_shape_or_layout(puma):
    Q = np.zeros((4, 6))
    with pytest.raises(ValueError, match="out must have shape"):
        puma.fk(Q, out=np.empty((3, 4, 4)))
    with pytest.raises(ValueError, match="C-contiguous"):
        puma.fk(Q, out=np.empty((4, 4, 8))[:, :, ::2])
    with pytest.raises(ValueError, match="out is for batches"):
        puma.fk(np.zeros(6), out=np.empty((4, 4)))


def test_models_that_cannot_be_loaded_raise_model_error_with_the_library_message(root, cli):
    bad = root / "tests/data/bad_models/bad_angle_string.toml"
    with pytest.raises(armlab.ModelError) as e:
        armlab.Robot.load(bad)
    message = cli("info", bad, check=False).stderr.strip().removeprefix("armlab: error: ")
    assert str(e.value) == message
    assert "bad_angle_string.toml:9:9" in str(e.value) and "joints[1].alpha" in str(e.value)
    for path in sorted((root / "tests/data/bad_models").glob("*.toml")):
        with pytest.raises(armlab.ModelError):
            armlab.Robot.load(path)
    with pytest.raises(armlab.ModelError, match="no_such_file.urdf"):
        armlab.Robot.load(root / "no_such_file.urdf")
    with pytest.raises(armlab.ModelError, match="unknown built-in model 'puma'"):
        armlab.Robot.builtin("puma")
    with pytest.raises(armlab.ModelError, match="not a model file"):
        armlab.Robot.load("robot.txt")
    assert issubclass(armlab.ModelError, armlab.ArmlabError)


def test_ik_errors(puma):
    panda = armlab.Robot.builtin("panda")
    with pytest.raises(armlab.IkError, match="no batch closed form"):
        panda.ik(panda.fk(np.zeros((2, 7))), solver="closed-form")
    with pytest.raises(armlab.IkError):
        panda.ik(panda.fk(np.zeros(7)), all=True, solver="closed-form")
    with pytest.raises(ValueError, match="solver"):
        puma.ik(np.eye(4), solver="magic")
    with pytest.raises(ValueError, match="ee = 3"):
        puma.fk(np.zeros(6), ee=3)
    far = np.eye(4)
    far[0, 3] = 10.0
    sols = puma.ik(far, all=True)
    assert sols.status == "unreachable" and len(sols) == 0 and sols.distance > 8
    assert puma.ik(far) is None


def test_calibration_errors_name_the_file(root, tmp_path):
    bad = tmp_path / "broken.csv"
    bad.write_text("0.1, 0.2, oops\n")
    with pytest.raises(armlab.CalibrationError, match="broken.csv"):
        armlab.calibrate(puma := armlab.Robot.builtin("puma560"), bad)
    with pytest.raises(ValueError, match="Y must have shape"):
        armlab.calibrate(puma, (np.zeros((3, 6)), np.zeros((3, 2))))
    with pytest.raises(ValueError, match="give measurements"):
        armlab.calibrate(puma)


def test_batch_calls_release_the_gil(puma):
    """While a long batch runs in a thread, the main thread keeps running Python."""
    Q = np.random.default_rng(1).uniform(-2, 2, (2_000_000, 6))
    done = []
    t = threading.Thread(target=lambda: done.append(puma.fk(Q)))
    start = time.perf_counter()
    t.start()
    ticks = 0
    while t.is_alive():
        ticks += 1
    elapsed = time.perf_counter() - start
    t.join()
    assert done and done[0].shape == (2_000_000, 4, 4)
    # A held GIL would give the main thread at most a few switch intervals (5 ms each).
    assert elapsed > 0.05 and ticks > 1000, (elapsed, ticks)
