"""Shared fixtures: the repository, the `armlab` command line (the Rust library's own answers,
to compare with), and the reference data computed with the Robotics Toolbox."""

import json
import os
import subprocess
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]


def _binary() -> Path:
    env = os.environ.get("ARMLAB_BIN")
    candidates = [Path(env)] if env else [ROOT / "target/debug/armlab", ROOT / "target/release/armlab"]
    for c in candidates:
        if c.is_file():
            return c
    raise RuntimeError(
        "the armlab command line is needed to compare with the Rust library: build it with "
        "`cargo build --bin armlab` (python/test.sh does) or set ARMLAB_BIN"
    )


@pytest.fixture(scope="session")
def root() -> Path:
    return ROOT


@pytest.fixture(scope="session")
def cli():
    """Runs `armlab ARGS...` and returns its standard output (JSON parsed with json=True)."""
    binary = _binary()

    def run(*args, json_out=True, check=True):
        p = subprocess.run([str(binary), *map(str, args)], capture_output=True, text=True, cwd=ROOT)
        if check and p.returncode != 0:
            raise AssertionError(f"armlab {' '.join(map(str, args))} failed: {p.stderr}")
        if not check:
            return p
        return json.loads(p.stdout) if json_out else p.stdout

    return run


@pytest.fixture(scope="session")
def reference():
    """The reference data of tests/data/reference by model name."""

    def load(name):
        return json.loads((ROOT / "tests/data/reference" / name).read_text())

    return load
