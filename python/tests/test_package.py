"""The package's surface: every name of the extension module has a stub, every public name a
docstring; position targets; the version."""

import ast
import inspect
from pathlib import Path

import numpy as np

import armlab
from armlab import _core

STUB = Path(armlab.__file__).with_name("_core.pyi")


def test_every_name_of_the_extension_has_a_stub_and_no_stub_is_stale():
    tree = ast.parse(STUB.read_text())
    stubbed = {n.name for n in tree.body if isinstance(n, (ast.FunctionDef, ast.ClassDef))}
    stubbed |= {t.id for n in tree.body if isinstance(n, (ast.AnnAssign,)) for t in [n.target]}
    stubbed |= {t.id for n in tree.body if isinstance(n, ast.Assign) for t in n.targets}
    public = {n for n in dir(_core) if not n.startswith("_")} | {"__version__"}
    assert public - stubbed == set(), "names without a stub"
    assert (stubbed - {"F64"}) - public == set(), "stubs of names that do not exist"
    methods = {n.name for c in tree.body if isinstance(c, ast.ClassDef) and c.name == "CoreRobot"
               for n in c.body if isinstance(n, ast.FunctionDef)}
    real = {n for n in dir(_core.CoreRobot) if not n.startswith("_")}
    assert methods == real


def test_every_public_name_has_a_docstring():
    for name in armlab.__all__:
        obj = getattr(armlab, name)
        assert inspect.getdoc(obj), name
        if inspect.isclass(obj):
            for m, f in vars(obj).items():
                if not m.startswith("_") and callable(f):
                    assert inspect.getdoc(f), f"{name}.{m}"


def test_position_targets_and_the_version():
    r = armlab.Robot.builtin("anthropomorphic3r")
    p = r.fk([0.3, 0.6, -0.9])[:3, 3]
    sols = r.ik(p, all=True)
    assert len(sols) == 4
    for s in sols:
        assert np.abs(r.fk(s.q)[:3, 3] - p).max() < 1e-12
    assert armlab.__version__ == "0.1.0"
