"""Figures (PNG, SVG, PDF; the same pixels as the command line) and calibration (the same report
as `armlab calibrate`)."""

import numpy as np
import pytest

import armlab


def test_robot_figure_png_svg_pdf(tmp_path, cli):
    r = armlab.Robot.builtin("puma560")
    f = r.figure(size=(640, 480))
    assert f.png[:8] == b"\x89PNG\r\n\x1a\n" and f.size == (640, 480)
    assert "<svg" in f.svg[:400]
    assert f._repr_png_() == f.png and f._repr_svg_() == f.svg
    pdf = f.save(tmp_path / "arm.pdf").read_bytes()
    assert pdf.startswith(b"%PDF")
    assert f.save(tmp_path / "arm.svg").read_text().startswith(f.svg[:50])
    with pytest.raises(ValueError, match=".png, .svg or .pdf"):
        f.save(tmp_path / "arm.jpg")
    # The same pixels as `armlab render` at the same configuration.
    cli("render", "puma560", "--config", "ready", "--size", "640x480", "--out", tmp_path / "cli.png",
        json_out=False)
    assert f.png == (tmp_path / "cli.png").read_bytes()


def test_textbook_figure_equals_the_command_line(tmp_path, cli):
    f = armlab.textbook_figure("2.30", size=(600, 450))
    cli("figure", "2.30", "--size", "600x450", "--out", tmp_path / "f.png", json_out=False)
    assert f.png == (tmp_path / "f.png").read_bytes()


def test_self_motion_figure():
    r = armlab.Robot.builtin("dlr")
    T = r.fk(np.array([0.3, 0.5, -0.2, 1.1, 0.4, -0.6, 0.2]))
    m = r.self_motion(T, samples=60, branch=None)
    assert m.figure is not None and m.figure.size[0] > 100
    assert len(m.branches) == 8


def test_calibrate_simulated_equals_the_command_line(cli):
    puma = armlab.Robot.builtin("puma560")
    rep = armlab.calibrate(puma, simulate=True, poses=40, seed=3)
    theirs = cli("calibrate", "puma560", "--simulate", "--poses", "40", "--seed", "3", "--format", "json")
    assert rep.data == theirs
    assert rep.converged and rep.rank == 24
    assert "identifiability" in rep.summary
    assert rep.estimate.shape == (len(rep.parameters),)


def test_calibrate_computes_once_in_the_library(monkeypatch):
    """One call of the library's experiment per calibration, no command line run in-process:
    the JSON-like data and the summary come from the same report."""
    calls = []
    library = armlab._core.calibrate

    def once(*args, **kwargs):
        calls.append(args)
        return library(*args, **kwargs)

    def no_cli(*args, **kwargs):
        raise AssertionError(f"calibrate ran the command line: {args}")

    monkeypatch.setattr(armlab._core, "calibrate", once)
    monkeypatch.setattr(armlab._core, "run_cli", no_cli)
    puma = armlab.Robot.builtin("puma560")
    rep = armlab.calibrate(puma, simulate=True, poses=20, seed=2)
    Q = np.random.default_rng(4).uniform(-1.5, 1.5, (30, 6))
    arrays = armlab.calibrate(puma, (Q, puma.fk(Q)), noise_mm=0.01)
    assert len(calls) == 2
    assert f"rank {rep.rank} of {rep.data['parameter_count']}" in rep.summary
    assert arrays.data["setup"] == "pose" and arrays.converged


def test_every_keyword_means_what_its_flag_means(cli, tmp_path):
    """The typed keywords build the same experiment as the command line's flags: a simulated
    position-only run with the tool, a fixed parameter, plain DH, O1 selection, other noise and
    tolerances, and target correction, compared key by key with `armlab calibrate --format json`."""
    puma = armlab.Robot.builtin("puma560")
    targets = tmp_path / "targets.txt"
    Q = np.random.default_rng(8).uniform(-1.0, 1.0, (3, 6))
    np.savetxt(targets, puma.fk(Q).reshape(3, 16), fmt="%.17g", delimiter=",")
    rep = armlab.calibrate(
        puma, simulate=True, poses=25, seed=9, select="o1", tolerance_mm=0.5, tolerance_deg=0.2,
        noise_mm=0.02, noise_mrad=0.05, position_only=True, with_tool=True, fix=["d1", "theta6"],
        hayati="off", unidentifiable="minimum-norm", correct_targets=targets)
    theirs = cli("calibrate", "puma560", "--simulate", "--poses", "25", "--seed", "9",
                 "--select", "o1", "--tolerance-mm", "0.5", "--tolerance-deg", "0.2",
                 "--noise-mm", "0.02", "--noise-mrad", "0.05", "--position-only", "--with-tool",
                 "--fix", "d1,theta6", "--hayati", "off", "--unidentifiable", "minimum-norm",
                 "--correct-targets", str(targets), "--format", "json")
    assert rep.data == theirs
    assert rep.data["setup"] == "position"
    fixed = {p["name"] for p in rep.parameters if p["fixed"]}
    assert {"d1", "theta6"} <= fixed
    # A pivot setup's scene keywords too.
    rep = armlab.calibrate(puma, simulate=True, setup="sphere", poses=60, groups=4,
                           sphere_radius_mm=30.0, seed=4)
    theirs = cli("calibrate", "puma560", "--simulate", "--setup", "sphere", "--poses", "60",
                 "--groups", "4", "--sphere-radius-mm", "30", "--seed", "4", "--format", "json")
    assert rep.data == theirs


def test_bad_keywords_and_files_are_named(tmp_path):
    puma = armlab.Robot.builtin("puma560")
    for kwargs, name in [({"setup": "laser"}, "setup"), ({"select": "best"}, "select"),
                         ({"hayati": "on"}, "hayati"), ({"unidentifiable": "drop"}, "unidentifiable"),
                         ({"noise_mm": -1.0}, "noise_mm"), ({"poses": 0}, "poses"),
                         ({"sphere_radius_mm": 0.0}, "sphere_radius_mm")]:
        with pytest.raises(ValueError, match=name):
            armlab.calibrate(puma, simulate=True, **kwargs)
    with pytest.raises(armlab.CalibrationError, match="missing.csv"):
        armlab.calibrate(puma, tmp_path / "missing.csv")
    bad = tmp_path / "targets.txt"
    bad.write_text("1 2 3\n")
    with pytest.raises(armlab.CalibrationError, match="targets.txt"):
        armlab.calibrate(puma, simulate=True, poses=10, correct_targets=bad)


def test_calibrate_from_a_cell_file_and_from_arrays(root):
    puma = armlab.Robot.builtin("puma560")
    rep = armlab.calibrate(puma, root / "tests/data/calibration/cell_puma_fit.csv",
                           validate=root / "tests/data/calibration/cell_puma_check.csv")
    assert rep.converged and rep["validation"]["after"]["position_rms"] < 1e-4
    assert any("note" in w for w in rep["warnings"])
    # Perfect positions of the nominal arm: the estimate stays nominal; a position-only setup
    # cannot see everything, and the report says what.
    Q = np.random.default_rng(2).uniform(-1.5, 1.5, (60, 6))
    Y = puma.fk(Q)[:, :3, 3]
    rep = armlab.calibrate(puma, (Q, Y), setup="position", noise_mm=0.01)
    nominal = np.array([p["nominal"] for p in rep.parameters])
    assert np.abs(rep.estimate - nominal).max() < 1e-6
    assert rep.data["setup_cannot_see"]
