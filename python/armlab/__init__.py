"""armlab: robot-manipulator kinematics for notebooks.

After chapter 2 of Siciliano, Sciavicco, Villani, Oriolo, *Robotics: Modelling, Planning and
Control*. The computing is armlab's Rust library; this package is its Python face: NumPy arrays
in and out, SI units (m) and radians, poses as (4, 4) homogeneous transforms ``world_from_tool``.

>>> import armlab
>>> r = armlab.Robot.builtin("puma560")
>>> T = r.fk([0.1] * 6)                       # (4, 4)
>>> sols = r.ik(T, all=True)                  # every closed-form solution, labelled
>>> len(sols), sols[0].posture
(8, 'shoulder right, elbow up, wrist no flip')

Batch calls take stacks: ``r.fk(Q)`` with Q of shape (N, dof) gives (N, 4, 4), ``r.ik(Ts)`` with
Ts of shape (N, 4, 4) gives an :class:`IkBatch`; both release the GIL and use every core.
Rotations in batches (matrices to Euler, RPY, angle-axis and quaternions, and back) are in
:mod:`armlab.rotation`. Figures (:meth:`Robot.figure`, :meth:`Robot.workspace`,
:meth:`Robot.self_motion`, :func:`textbook_figure`) show inline in Jupyter and save as PNG, SVG
or PDF.

Collisions: :meth:`Robot.collisions` says what a configuration hits (the arm's own links and the
obstacles of a scene file), and every solution of :meth:`Robot.ik` carries its ``collision`` and
``clearance_m``.

Reachability maps: :meth:`Robot.reachability` returns the arrays of ``armlab reachability``'s
``.npz`` file (where the tool reaches, in which orientations, with which postures).

Errors are armlab's own, with the library's messages: :class:`ModelError` (a model that cannot
be loaded: file, line and field named), :class:`IkError`, :class:`KinematicsError`,
:class:`WorkspaceError`, :class:`FigureError`, :class:`CalibrationError`,
:class:`CollisionError` (a scene that cannot be used: file, line and obstacle named), all
subclasses of :class:`ArmlabError`. A bad array (wrong shape or dtype, NaN) raises ``ValueError``.
"""

from __future__ import annotations

import io
import json
import os
import struct
import warnings
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any, Dict, List, Optional, Sequence, Tuple, Union

import numpy as np

from . import _core
from ._core import (
    ArmlabError,
    CalibrationError,
    CollisionError,
    FigureError,
    IkError,
    KinematicsError,
    ModelError,
    WorkspaceError,
)
from . import rotation

__version__: str = _core.__version__

__all__ = [
    "Robot",
    "DhRow",
    "DhTable",
    "IkSolution",
    "IkSolutions",
    "IkBatch",
    "NumericalReport",
    "Reach",
    "Workspace",
    "SelfMotion",
    "Symbolic",
    "Figure",
    "CalibrationReport",
    "calibrate",
    "textbook_figure",
    "posture_label",
    "rotation",
    "ArmlabError",
    "ModelError",
    "KinematicsError",
    "IkError",
    "WorkspaceError",
    "FigureError",
    "CalibrationError",
    "CollisionError",
]

PathLike = Union[str, "os.PathLike[str]"]


def _floats(x: Any, name: str) -> np.ndarray:
    """``x`` as a float64 array, or ValueError for anything that is not real numbers."""
    if isinstance(x, np.ndarray) and x.dtype == np.float64:
        return x
    try:
        a = np.asarray(x)
    except Exception as e:  # ragged lists and the like
        raise ValueError(f"{name} must be an array of real numbers: {e}") from None
    if a.dtype.kind not in "iuf":
        raise ValueError(
            f"{name} must hold real numbers (integers or floats); got dtype {a.dtype}"
        )
    return a.astype(np.float64)


# ---------------------------------------------------------------------------------------------
# Figures


def _scene_args(scene: Any) -> Tuple[Optional[str], Optional[str]]:
    """A scene as (path, text): a path (str or os.PathLike) to a scene file, or the TOML text
    of one (a str holding a newline or ``[[``); None for no obstacles."""
    if scene is None:
        return None, None
    if isinstance(scene, os.PathLike):
        return os.fspath(scene), None
    if isinstance(scene, str):
        if "\n" in scene or "[[" in scene:
            return None, scene
        return scene, None
    raise TypeError(f"scene must be a path to a scene file or its TOML text; got {type(scene).__name__}")


def _warn(messages: Sequence[str]) -> None:
    """The checker's warnings (each naming its link, obstacle or file) as Python warnings."""
    for m in messages:
        warnings.warn(m, stacklevel=3)


def _png_size(png: bytes) -> Tuple[int, int]:
    """Width and height (px) from a PNG's IHDR chunk."""
    w, h = struct.unpack(">II", png[16:24])
    return int(w), int(h)


class Figure:
    """A figure drawn by armlab's renderer: PNG pixels and the SVG of the same drawing.

    Jupyter shows it inline (``_repr_png_``, ``_repr_svg_``); :meth:`save` writes ``.png``,
    ``.svg`` or ``.pdf`` (vectors: exact arcs, text as text, fonts embedded) by the extension.
    """

    def __init__(self, png: bytes, svg: str, title: str = "") -> None:
        #: The PNG file's bytes.
        self.png: bytes = bytes(png)
        #: The SVG document.
        self.svg: str = svg
        #: What the figure shows.
        self.title: str = title

    @property
    def size(self) -> Tuple[int, int]:
        """(width, height) in pixels."""
        return _png_size(self.png)

    def _repr_png_(self) -> bytes:
        return self.png

    def _repr_svg_(self) -> str:
        return self.svg

    def save(self, path: PathLike) -> Path:
        """Writes the figure to ``path``: PNG, SVG or PDF by its extension. Returns the path."""
        p = Path(path)
        ext = p.suffix.lower()
        if ext == ".png":
            p.write_bytes(self.png)
        elif ext == ".svg":
            p.write_text(self.svg, encoding="utf-8")
        elif ext == ".pdf":
            p.write_bytes(_core.svg_to_pdf(self.svg))
        else:
            raise ValueError(f"{p}: give a .png, .svg or .pdf file name")
        return p

    def __repr__(self) -> str:
        w, h = self.size
        return f"<armlab.Figure {self.title!r} {w}x{h}>"


def textbook_figure(
    name: str, size: Tuple[int, int] = (1200, 900), theme: str = "light"
) -> Figure:
    """Figure ``name`` of the excerpt ("2.29", "2.30", "2.31", "2.32", "2.33", "problem-2.17"),
    as ``armlab figure NAME`` draws it."""
    png, svg = _core.textbook_figure(str(name), int(size[0]), int(size[1]), theme)
    return Figure(png, svg, f"Fig. {name}")


# ---------------------------------------------------------------------------------------------
# Results


@dataclass(frozen=True)
class DhRow:
    """One row of a DH table (Sect. 2.8.2): lengths in m, angles in rad."""

    name: str
    kind: str
    a: float
    alpha: float
    d: float
    theta: float
    offset: float
    limits: Tuple[float, float]


class DhTable(tuple):
    """The DH table of an arm, row by row (a tuple of :class:`DhRow`), with its convention and
    the constant transforms before and after it."""

    convention: str
    world_from_base: np.ndarray
    flange_from_tool: np.ndarray

    def __new__(cls, rows: Sequence[DhRow], convention: str, base: Any, tool: Any) -> "DhTable":
        t = super().__new__(cls, rows)
        t.convention = convention
        t.world_from_base = np.asarray(base, dtype=float)
        t.flange_from_tool = np.asarray(tool, dtype=float)
        return t

    def to_array(self) -> np.ndarray:
        """(n, 4) array of a, alpha, d, theta per row (m, rad)."""
        return np.array([[r.a, r.alpha, r.d, r.theta] for r in self], dtype=float).reshape(-1, 4)

    def __repr__(self) -> str:
        lines = [f"DH table ({self.convention} convention)",
                 f"{'joint':<10}{'type':<11}{'a [m]':>10}{'alpha [deg]':>13}{'d [m]':>10}{'theta [deg]':>13}"]
        for r in self:
            lines.append(
                f"{r.name:<10}{r.kind:<11}{r.a:>10.4f}{np.degrees(r.alpha):>13.2f}"
                f"{r.d:>10.4f}{np.degrees(r.theta):>13.2f}"
            )
        return "\n".join(lines)

    def _repr_markdown_(self) -> str:
        rows = ["| joint | type | a (m) | alpha (deg) | d (m) | theta (deg) |", "|---|---|---|---|---|---|"]
        for r in self:
            rows.append(
                f"| {r.name} | {r.kind} | {r.a:.4f} | {np.degrees(r.alpha):.2f} | {r.d:.4f} | "
                f"{np.degrees(r.theta):.2f} |"
            )
        return f"DH table ({self.convention} convention)\n\n" + "\n".join(rows)


@dataclass
class IkSolution:
    """One inverse-kinematics solution."""

    #: Joint vector (rad or m), angles wrapped into the limits where a 2 pi shift allows.
    q: np.ndarray
    #: Posture label, e.g. "shoulder right, elbow up, wrist no flip"; "numerical" otherwise.
    posture: str
    #: Whether q lies inside the joint limits.
    within_limits: bool
    #: |p(FK(q)) - p_target| (m), from the robot's own forward kinematics.
    position_error: float
    #: Rotation angle between FK(q) and the target (rad).
    orientation_error: float
    #: Joints the closed form cannot determine here: (index, why), a representative value chosen.
    free_joints: List[Tuple[int, str]] = field(default_factory=list)
    #: The posture's fields as JSON text (read by :attr:`parts`).
    _parts_json: str = field(default="", repr=False)
    #: What it hits: None when free, else the contacts, each ``{"a", "b", "depth_m", "at"}``
    #: (a link and a link or obstacle, the depth in m, where in the world frame), deepest first;
    #: the ``collision`` of ``armlab ik --format json``.
    collision: Optional[List[Dict[str, Any]]] = None
    #: The smallest distance between the bodies checked (m; 0 in collision; None when nothing is
    #: checked): the arm's own links and, with a scene, its obstacles.
    clearance_m: Optional[float] = None
    #: The same in words: "forearm hits table, 12 mm" or "free, 45 mm clear".
    collision_summary: str = ""

    @property
    def parts(self) -> Dict[str, Any]:
        """The posture as data, the ``posture_parts`` of ``armlab ik --format json``:
        ``{"solver": "closed_form", "shoulder": "right", "elbow": "up", "extension": None,
        "wrist": "no_flip", "branch": None, "reversed": False, "free": [...]}``, or
        ``{"solver": "numerical", "converged": True}``. Read these instead of parsing
        :attr:`posture`, the label."""
        return json.loads(self._parts_json) if self._parts_json else {}

    def __repr__(self) -> str:
        q = np.array2string(np.asarray(self.q), precision=4, suppress_small=True, floatmode="fixed")
        flag = "" if self.within_limits else "  OUTSIDE the limits"
        hits = f"  COLLIDES: {self.collision_summary}" if self.collision else ""
        return f"{self.posture:<44} q = {q}{flag}{hits}"


class IkSolutions(list):
    """Every solution of one target (a list of :class:`IkSolution`), with the status, the
    solver that answered and, when unreachable, the distance to the workspace (m)."""

    status: str
    solver: str
    distance: Optional[float]

    def __init__(self, items: Sequence[IkSolution], status: str, solver: str, distance: Optional[float]):
        super().__init__(items)
        self.status = status
        self.solver = solver
        self.distance = distance

    def posture(self, label: str) -> IkSolution:
        """The solution with this posture label; KeyError if there is none."""
        for s in self:
            if s.posture == label:
                return s
        raise KeyError(f"no solution with posture {label!r}; postures: {[s.posture for s in self]}")

    def __repr__(self) -> str:
        head = f"{len(self)} solution(s) by the {self.solver}, status {self.status}"
        if self.distance is not None:
            head += f", {self.distance:.6g} from the workspace"
        return "\n".join([head] + [f"  {s!r}" for s in self])


@dataclass
class IkBatch:
    """All closed-form solutions of N poses at once.

    Slot j of pose i is its j-th solution; ``valid[i, j]`` says whether the slot holds one
    (unused slots hold NaN). ``posture[i, j]`` is an integer code (:func:`posture_label` or
    ``labels`` turns it into the label).
    """

    #: (N, k, dof) joint vectors, angles wrapped into the limits where a 2 pi shift allows.
    q: np.ndarray
    #: (N, k) whether slot j holds a solution.
    valid: np.ndarray
    #: (N, k) whether that solution lies inside the joint limits.
    within_limits: np.ndarray
    #: (N, k) posture codes (-1 for an empty slot).
    posture: np.ndarray
    #: code -> label for every code in ``posture``.
    labels: Dict[int, str]
    #: (N,) position errors (m) of the numerical solver's answers (None for the closed form,
    #: whose solutions are exact).
    position_error: Optional[np.ndarray] = None
    #: (N,) orientation errors (rad) of the numerical solver's answers.
    orientation_error: Optional[np.ndarray] = None

    def counts(self) -> np.ndarray:
        """(N,) number of solutions per pose."""
        return self.valid.sum(axis=1)

    def __len__(self) -> int:
        return int(self.q.shape[0])

    def __repr__(self) -> str:
        n, k, dof = self.q.shape
        return (
            f"<armlab.IkBatch {n} poses x {k} slots x {dof} joints, "
            f"{int(self.valid.sum())} solutions, {len(self.labels)} postures>"
        )


_SHOULDER = ["", "shoulder right", "shoulder left", "shoulder on axis", "shoulder boundary"]
_ELBOW = ["", "elbow up", "elbow down", "elbow stretched", "elbow folded"]
_EXTENSION = ["", "extension forward", "extension reversed", "extension zero"]
_WRIST = ["", "wrist no flip", "wrist flip", "wrist singular", "wrist up", "wrist down"]


def posture_label(code: int) -> str:
    """A short description of posture code ``code`` (from :class:`IkBatch`): shoulder + 5 elbow
    + 25 extension + 100 wrist + 1000 branch. :attr:`IkBatch.labels` has the library's exact
    labels."""
    code = int(code)
    if code < 0:
        return "no solution"
    b, rest = divmod(code, 1000)
    w, rest = divmod(rest, 100)
    x, rest = divmod(rest, 25)
    e, s = divmod(rest, 5)
    parts = [p for p in (_SHOULDER[s], _ELBOW[e], _EXTENSION[x], _WRIST[w]) if p]
    if b:
        parts.append(f"branch {b}")
    return ", ".join(parts) or "the solution"


@dataclass
class NumericalReport:
    """What the numerical solver did (:meth:`Robot.ik_numerical`)."""

    #: Final joint vector (the best found when not converged).
    q: np.ndarray
    #: Whether both errors are below the tolerance.
    converged: bool
    #: Iterations over all attempts.
    iterations: int
    #: Random restarts used.
    restarts: int
    #: Position error (m).
    position_error: float
    #: Orientation error (rad).
    orientation_error: float


@dataclass
class Reach:
    """Point queries against the exact workspace (:meth:`Robot.reach`)."""

    #: (N,) reached with some posture inside the joint limits.
    reachable: np.ndarray
    #: (N,) distance to the workspace boundary (m): positive inside, negative outside.
    distance: np.ndarray
    #: Per point, the posture classes that reach it.
    postures: List[List[str]]
    #: Whether the distances are exact (planar arms) or bracketed by a search.
    exact: bool


@dataclass
class Workspace:
    """A workspace figure and its statistics (:meth:`Robot.workspace`), as ``armlab workspace
    --format json`` reports them."""

    #: Area (m^2, planar views) or volume (m^3), whichever applies.
    area: Optional[float]
    volume: Optional[float]
    #: Reach from the base (m), and whether it is exact.
    min_reach: float
    max_reach: float
    reach_exact: bool
    #: Bounding box (m): {"min": [x, y, z], "max": [...]}.
    bbox: Dict[str, List[float]]
    #: How the measure was computed, in words.
    measure_method: str
    #: The tracked point: "wrist centre" or "flange".
    point: str
    #: Every posture class with the measure it reaches ("with") and reaches alone ("only").
    classes: List[Dict[str, Any]]
    #: The whole JSON.
    stats: Dict[str, Any]
    #: The figure.
    figure: Figure

    def _repr_png_(self) -> bytes:
        return self.figure.png

    def _repr_svg_(self) -> str:
        return self.figure.svg

    def save(self, path: PathLike) -> Path:
        """Writes the figure (PNG, SVG or PDF by the extension)."""
        return self.figure.save(path)

    def __repr__(self) -> str:
        m = f"area {self.area:.6f} m^2" if self.area is not None else (
            f"volume {self.volume:.6f} m^3" if self.volume is not None else "no measure")
        exact = "exact" if self.reach_exact else "from cells"
        return (f"<armlab.Workspace of the {self.point}: {m}, reach {self.min_reach:.4f}-"
                f"{self.max_reach:.4f} m ({exact}); {self.measure_method}>")


@dataclass
class SelfMotion:
    """The self-motion of a redundant arm holding its hand still (:meth:`Robot.self_motion`)."""

    #: The parameter's name ("psi", "q7", "q3 (locked)", "arc length", ...).
    parameter: str
    #: What the parameter is, in a sentence.
    meaning: str
    #: Exact (closed-form branches) or walked numerically.
    exact: bool
    #: (S,) parameter values (rad).
    values: np.ndarray
    #: Branch name -> (S, dof) joint vectors (NaN where the branch has no solution).
    q: Dict[str, np.ndarray]
    #: Branch name -> (S,) whether inside the joint limits.
    within_limits: Dict[str, np.ndarray]
    #: Branch name -> feasible intervals of the parameter inside the limits (rad).
    feasible: Dict[str, List[Tuple[float, float]]]
    #: Disjoint self-motion curves inside the limits.
    manifolds: int
    #: An algorithmic singularity of the parameterisation.
    singular: bool
    #: The figure of every joint over the parameter (when asked for).
    figure: Optional[Figure] = None

    @property
    def branches(self) -> List[str]:
        """The branch names."""
        return list(self.q)

    def _repr_png_(self) -> Optional[bytes]:
        return self.figure.png if self.figure is not None else None

    def _repr_svg_(self) -> Optional[str]:
        return self.figure.svg if self.figure is not None else None

    def __repr__(self) -> str:
        kind = "exact" if self.exact else "walked numerically"
        lines = [f"<armlab.SelfMotion over {self.parameter} ({kind}), {len(self.values)} samples, "
                 f"{self.manifolds} curve(s) inside the limits>"]
        for name, iv in self.feasible.items():
            ivs = " ".join(f"[{np.degrees(a):.3f}, {np.degrees(b):.3f}]" for a, b in iv)
            lines.append(f"  {name}: feasible {ivs or 'nowhere'} (deg)")
        return "\n".join(lines)


@dataclass
class Symbolic:
    """The direct kinematics in the textbook's symbols (c1, s23, a2, d4, ...): each A_i^{i-1}(q_i)
    and T_n^0, as ``armlab symbolic`` prints them. Shows as LaTeX in Jupyter."""

    text: str
    latex: str
    markdown: str

    def __str__(self) -> str:
        return self.text

    def __repr__(self) -> str:
        return self.text

    def _repr_markdown_(self) -> str:
        return self.markdown


@dataclass
class CalibrationReport:
    """A calibration's report (``armlab calibrate --format json``), with the summary in words
    (what the setup cannot see, which parameters are not identifiable and why, the fit before and
    after) as ``armlab calibrate`` prints it."""

    #: The whole JSON report.
    data: Dict[str, Any]
    #: The report in words.
    summary: str

    @property
    def converged(self) -> bool:
        """Whether the iterations converged."""
        return bool(self.data["converged"])

    @property
    def parameters(self) -> List[Dict[str, Any]]:
        """Per parameter: name, kind, nominal, estimate, std, identifiable, fixed (SI units)."""
        return list(self.data["parameters"])

    @property
    def estimate(self) -> np.ndarray:
        """The estimated parameters (m, rad), in the order of :attr:`parameters`."""
        return np.array([p["estimate"] for p in self.data["parameters"]], dtype=float)

    @property
    def unidentifiable(self) -> List[Any]:
        """What the data cannot identify (empty when everything is)."""
        return list(self.data["unidentifiable"])

    @property
    def rank(self) -> int:
        """Numerical rank of the identification Jacobian."""
        return int(self.data["rank"])

    @property
    def fit(self) -> Dict[str, Any]:
        """RMS and maximum errors before and after (m, rad)."""
        return dict(self.data["fit"])

    def __getitem__(self, key: str) -> Any:
        return self.data[key]

    def __repr__(self) -> str:
        return self.summary


def _solution(row: Tuple[Any, ...]) -> IkSolution:
    """One solution of ``_core.CoreRobot.ik`` as an :class:`IkSolution`."""
    q, posture, within, pe, oe, free, parts, report, summary = row
    r = json.loads(report)
    return IkSolution(np.array(q, dtype=float), posture, within, pe, oe, list(free), parts,
                      r["pairs"] if r["in_collision"] else None, r["clearance_m"], summary)


# ---------------------------------------------------------------------------------------------
# The robot


class Robot:
    """A robot: a built-in model (:meth:`builtin`) or a TOML model file or URDF (:meth:`load`).

    Joint vectors are in rad (revolute) and m (prismatic); poses are (4, 4) ``world_from_tool``
    arrays in m.
    """

    def __init__(self, core: "_core.CoreRobot") -> None:
        self._core = core
        self._info: Optional[Dict[str, Any]] = None

    # -- construction -----------------------------------------------------------------------

    @classmethod
    def builtin(cls, name: str) -> "Robot":
        """A built-in model by name (:meth:`builtins` lists them), e.g. ``"puma560"``."""
        name = str(name)
        if name not in cls.builtins():
            raise ModelError(
                f"unknown built-in model {name!r}; built-in models: {', '.join(cls.builtins())}"
                + (" (for a file, use Robot.load)" if Path(name).suffix else "")
            )
        return cls(_core.CoreRobot.load(name))

    @classmethod
    def load(cls, path: PathLike) -> "Robot":
        """A robot from a TOML model file (``.toml``) or a URDF (``.urdf``). A file that cannot be
        read raises :class:`ModelError` naming the file, line and field."""
        p = os.fspath(path)
        if Path(p).suffix.lower() not in (".toml", ".urdf", ".xacro"):
            raise ModelError(f"{p}: not a model file (give a .toml model file or a .urdf)")
        return cls(_core.CoreRobot.load(p))

    @staticmethod
    def builtins() -> Dict[str, str]:
        """The built-in models: name -> one-line summary."""
        return dict(_core.CoreRobot.builtins())

    # -- description -------------------------------------------------------------------------

    @property
    def name(self) -> str:
        """The model's name."""
        return self._core.name

    @property
    def dof(self) -> int:
        """Number of joint variables."""
        return self._core.dof

    @property
    def joint_names(self) -> List[str]:
        """The joint variables' names."""
        return [j[0] for j in self._core.joints()]

    @property
    def joint_kinds(self) -> List[str]:
        """"revolute" or "prismatic" per joint variable."""
        return [j[1] for j in self._core.joints()]

    @property
    def limits(self) -> np.ndarray:
        """(dof, 2) lower and upper joint limits (rad or m; +-inf where a joint has none)."""
        return np.array([[j[2], j[3]] for j in self._core.joints()], dtype=float).reshape(-1, 2)

    @property
    def end_effectors(self) -> List[str]:
        """The end-effectors' names (index 0 is the default ``ee``)."""
        return list(self._core.end_effectors())

    @property
    def closed_form(self) -> Optional[str]:
        """The closed-form IK family detected from the joint axes, or None."""
        return self._core.closed_form()

    @property
    def closed_form_reason(self) -> Optional[str]:
        """Why there is no closed form (None when there is one)."""
        return self._core.no_closed_form_reason()

    @property
    def configs(self) -> Dict[str, np.ndarray]:
        """Named configurations ("ready", ...)."""
        return {n: np.array(q, dtype=float) for n, q in self._core.configs()}

    @property
    def frame_names(self) -> List[str]:
        """Names of the frames ``fk(q, frames=True)`` returns, in order."""
        return list(self._core.frame_names())

    def info(self) -> Dict[str, Any]:
        """What ``armlab info MODEL --format json`` says: pose, Euler angles, Jacobian analysis,
        and per end-effector its chain, DH table, closed form and redundancy."""
        if self._info is None:
            self._info = json.loads(_core.run_cli(["info", self._core.spec, "--format", "json"], "model"))
        return self._info

    @property
    def dh(self) -> Optional[DhTable]:
        """The DH table of the first end-effector's arm (derived from the joint axes for a URDF),
        or None when the chain has none (``info()`` says why)."""
        dh = self.info()["end_effectors"][0].get("dh")
        if dh is None:
            return None
        rows = [
            DhRow(r["name"], r["type"], r["a"], r["alpha"], r["d"], r["theta"], r["offset"],
                  (float(r["limits"][0]), float(r["limits"][1])))
            for r in dh["rows"]
        ]
        return DhTable(rows, dh["convention"], dh["world_from_base"], dh["flange_from_tool"])

    def __repr__(self) -> str:
        cf = f", closed form: {self.closed_form}" if self.closed_form else ""
        return f"<armlab.Robot {self.name!r}, {self.dof} joints{cf}>"

    # -- kinematics --------------------------------------------------------------------------

    def fk(
        self, q: Any, ee: int = 0, frames: bool = False, out: Optional[np.ndarray] = None
    ) -> np.ndarray:
        """Forward kinematics (2.50): ``world_from_tool`` of end-effector ``ee``.

        ``q`` of shape (dof,) gives (4, 4); Q of shape (N, dof) gives (N, 4, 4) (computed on
        every core, the GIL released). With ``frames=True`` every joint frame instead:
        (frames, 4, 4) or (N, frames, 4, 4), in the order of :attr:`frame_names`. A batch may be
        written into ``out`` (a C-contiguous float64 array of that shape), which is returned.
        """
        a = _floats(q, "q")
        if a.ndim == 1:
            if out is not None:
                raise ValueError("out is for batches: give Q of shape (N, dof)")
            return self._core.fk_frames(a) if frames else self._core.fk(a, ee)
        if a.ndim == 2:
            return _core.fk_batch(self._core, a, ee, frames, out)
        raise ValueError(f"q must have shape ({self.dof},) or (N, {self.dof}); got shape {a.shape}")

    def jacobian(self, q: Any, ee: int = 0) -> np.ndarray:
        """The geometric Jacobian (6, dof) at ``q`` (Sect. 3.1): rows v (m/s) then omega
        (rad/s), in the world frame."""
        return self._core.jacobian(_floats(q, "q"), ee)

    def manipulability(self, q: Any, ee: int = 0) -> float:
        """Yoshikawa's manipulability sqrt(det(J J^T)) over the task rows the arm controls
        (v_x, v_y for a two-link planar arm; all six rows for a six-joint arm)."""
        return float(self._core.manipulability(_floats(q, "q"), ee)[0])

    def ik(
        self,
        T: Any,
        all: bool = False,
        seed: Any = None,
        posture: Optional[str] = None,
        ee: int = 0,
        solver: str = "auto",
        scene: Any = None,
    ) -> Union[IkSolutions, IkSolution, IkBatch, None]:
        """Inverse kinematics of a pose (4, 4) or a position (3,).

        With ``all=True`` every solution (an :class:`IkSolutions`): the closed form's, each
        labelled with its posture, where the arm's structure has one; the numerical solver's
        otherwise. Without it, the one with ``posture``, or the one closest to ``seed`` (default
        the first); None when the target is unreachable.

        ``Ts`` of shape (N, 4, 4) solves every pose at once and returns an :class:`IkBatch`
        (every core, the GIL released): every closed-form solution, or, for an arm without a
        closed form (or ``solver="numerical"``), the numerical solver's answer from ``seed``
        (one q, or one row per pose; default "ready"), ``valid`` where it converged.

        Each solution of a single target says what it hits (``collision``, ``clearance_m``,
        ``collision_summary``): the arm's own links and, with ``scene`` (a scene file's path, or
        its TOML text), the scene's obstacles. A batch carries no collision fields.
        """
        a = _floats(T, "T")
        s = None if seed is None else _floats(seed, "seed")
        if a.ndim == 3:
            if scene is not None:
                raise ValueError("scene is for a single target: a batch carries no collision fields")
            numerical = solver == "numerical" or (solver == "auto" and self.closed_form is None)
            if not numerical:
                q, valid, within, codes, labels = _core.ik_batch(self._core, a)
                return IkBatch(q, valid, within, codes, dict(labels))
            q, valid, within, codes, labels, pe, oe = _core.ik_batch_numerical(self._core, a, s, ee)
            return IkBatch(q, valid, within, codes, dict(labels), pe, oe)
        path, text = _scene_args(scene)
        (status, distance, used, found), said = self._core.ik(a, ee, s, solver, path, text)
        _warn(said)
        sols = IkSolutions([_solution(row) for row in found], status, used, distance)
        if all:
            return sols
        if posture is not None:
            return sols.posture(posture)
        if not sols or status == "unreachable":
            return None
        if s is None:
            return sols[0]
        return min(sols, key=lambda x: float(np.linalg.norm(_wrapped(x.q - s, self.joint_kinds))))

    def collisions(self, q: Any, scene: Any = None) -> Union[Dict[str, Any], List[Dict[str, Any]]]:
        """What configuration ``q`` (dof,) hits, as ``armlab collisions --format json`` says it:
        ``{"in_collision": bool, "pairs": [{"a", "b", "depth_m", "at"}], "clearance_m": m or
        None, "closest": {"a", "b"} or None}``. Pairs are a link and a link or obstacle, deepest
        first, with the depth (m) and where (world frame, m); ``clearance_m`` is the smallest
        distance between the bodies checked (0 in collision) and ``closest`` their names.

        The arm's own links are checked (adjacent links and the pairs the model's matrix
        disables are not); ``scene`` adds the obstacles of a scene file (its path, or its TOML
        text). Q of shape (N, dof) gives a list of reports. A scene that cannot be used raises
        :class:`CollisionError` naming the file, line and obstacle; what the checker lets pass
        with a remark (a link checked with its visual) is a warning."""
        a = _floats(q, "q")
        if a.ndim not in (1, 2):
            raise ValueError(f"q must have shape ({self.dof},) or (N, {self.dof}); got shape {a.shape}")
        path, text = _scene_args(scene)
        report, said = _core.collisions(self._core, a, path, text)
        _warn(said)
        return json.loads(report)

    def ik_numerical(
        self,
        T: Any,
        q0: Any = None,
        ee: int = 0,
        method: str = "lm",
        tolerance: float = 1e-10,
        max_iterations: int = 100,
        restarts: int = 50,
        seed: int = 0x5EED,
    ) -> NumericalReport:
        """The numerical solver alone from ``q0`` (default the "ready" configuration, else zero):
        ``method`` "lm" (Levenberg-Marquardt), "dls", "pinv" or "transpose" (Sect. 3.7)."""
        if q0 is None:
            q0 = self.configs.get("ready", np.zeros(self.dof))
        r = json.loads(
            self._core.ik_numerical(_floats(T, "T"), _floats(q0, "q0"), ee, method,
                                    float(tolerance), int(max_iterations), int(restarts), int(seed))
        )
        return NumericalReport(np.array(r["q"], dtype=float), r["converged"], r["iterations"],
                               r["restarts"], r["position_error"], r["orientation_error"])

    # -- workspace, redundancy, symbols, figures ---------------------------------------------

    def reach(self, points: Any, point: str = "wrist-centre") -> Reach:
        """Whether each point (N, 3), or (N, 2) in the plane of a planar arm, is in the exact
        workspace of the wrist centre or the flange, with the postures that reach it and the
        distance to the boundary."""
        a = _floats(points, "points")
        if a.ndim == 1:
            a = a.reshape(1, -1)
        reachable, distance, postures, exact, _ = _core.reach(self._core, a, point)
        return Reach(np.array(reachable, dtype=bool), np.array(distance, dtype=float),
                     [list(p) for p in postures], bool(exact))

    def reachability(
        self,
        voxel: float = 0.05,
        directions: int = 200,
        rolls: int = 8,
        ee: Union[int, str, None] = None,
        scene: Any = None,
        seeds: int = 4,
        force: bool = False,
    ) -> Dict[str, Any]:
        """The six-dimensional reachability map (``armlab reachability``): for every voxel
        centre of a grid over the arm's reach (``voxel`` m), every approach direction of a
        Fibonacci sphere of ``directions`` points and every roll 2 pi j / ``rolls`` about it,
        whether some IK solution within the joint limits reaches the pose, and which postures do.

        Returns a dict with the keys of the ``.npz`` file ``armlab reachability --out`` writes:
        ``reachable`` (nx, ny, nz, N, R) bool, ``postures`` (nx, ny, nz, N, R) uint16 (bit p set
        when posture ``posture_names[p]`` reaches the sample), ``posture_names`` (str array),
        ``index`` (nx, ny, nz) float64 (the fraction of each voxel's samples reached),
        ``origin`` (3,) (the centre of voxel (0, 0, 0); voxel (i, j, k) is centred at
        ``origin + voxel * (i, j, k)``, m, world frame), ``voxel`` (m), ``size`` (3,) (m),
        ``directions`` (N, 3), ``rolls`` (R,) (rad), ``end_effector``, ``model``, ``version``,
        ``solver`` (str: the closed form, or the numerical solver from ``seeds`` starts per
        sample for arms without one), ``collisions`` (bool), ``reach_centre`` (3,) and ``reach`` (m):
        voxels farther than ``reach`` from ``reach_centre`` were not solved.

        ``ee`` is an end-effector's index or name (default the first); ``scene`` (a scene file's
        path, or its TOML text) counts a solution only when it hits neither the arm itself nor
        the scene. Bad options (a zero voxel, no directions or rolls, over 1e9 samples without
        ``force``) raise ``ValueError`` before any work. The map is computed on every core with
        the GIL released; Ctrl+C does not interrupt it.
        """
        if ee is None:
            index = 0
        elif isinstance(ee, str):
            if ee not in self.end_effectors:
                raise ValueError(f"ee = {ee!r}: the end-effectors are {', '.join(self.end_effectors)}")
            index = self.end_effectors.index(ee)
        else:
            index = int(ee)
        counts = {"directions": int(directions), "rolls": int(rolls), "seeds": int(seeds), "ee": index}
        for name, value in counts.items():
            if value < 0:
                raise ValueError(f"{name} must not be negative, got {value}")
        path, text = _scene_args(scene)
        m = _core.reachability(self._core, float(voxel), counts["directions"], counts["rolls"],
                               index, counts["seeds"], bool(force), path, text)
        m["posture_names"] = np.array(m["posture_names"], dtype=str)
        return m

    def workspace(
        self,
        view: Optional[str] = None,
        size: Tuple[int, int] = (1200, 900),
        point: str = "wrist-centre",
        color_by: str = "posture",
        samples: int = 200_000,
        seed: int = 1,
        theme: str = "light",
    ) -> Workspace:
        """The workspace figure and its statistics, as ``armlab workspace`` makes them: ``view``
        "plane" (planar arms), "top", "side", "3d" or "joint-space"; exact regions where the
        structure allows (the subtitle and ``measure_method`` say how)."""
        stats, png, svg = _core.workspace(self._core, view, point, color_by, int(samples),
                                          int(seed), int(size[0]), int(size[1]), theme)
        s = json.loads(stats)
        return Workspace(s.get("area"), s.get("volume"), s["min_reach"], s["max_reach"],
                         s["reach_exact"], s["bbox"], s["measure_method"], s["point"],
                         s["classes"], s, Figure(png, svg, f"workspace of the {self.name}"))

    def self_motion(
        self,
        T: Any,
        samples: int = 360,
        lock: Optional[int] = None,
        branch: Optional[str] = None,
        ee: int = 0,
        figure: bool = True,
    ) -> SelfMotion:
        """The self-motion of a redundant arm holding pose ``T`` (4, 4): every branch over the
        parameter (the arm angle of an SRS arm, q7 of the Panda, a locked joint otherwise;
        ``lock`` = 1..7 picks the joint), the feasible intervals inside the limits and, with
        ``figure``, the figure of every joint over the parameter."""
        js, drawn = _core.self_motion(self._core, _floats(T, "T"), int(samples), lock, branch,
                                      ee, figure)
        m = json.loads(js)
        values = np.array([s["value"] for s in m["samples"]], dtype=float)
        names = list(m["branch_names"])
        q = {n: np.full((len(values), self.dof if ee == 0 else 0), np.nan) for n in names}
        within = {n: np.zeros(len(values), dtype=bool) for n in names}
        for i, s in enumerate(m["samples"]):
            for b in s["branches"]:
                row = np.asarray(b["q"], dtype=float)
                if q[b["name"]].shape[1] != row.size:
                    q[b["name"]] = np.full((len(values), row.size), np.nan)
                q[b["name"]][i] = row
                within[b["name"]][i] = b["within_limits"]
        feasible = {n: [(float(a), float(b)) for a, b in iv] for n, iv in m["feasible"].items()}
        fig = Figure(drawn[0], drawn[1], f"self-motion of the {self.name}") if drawn else None
        return SelfMotion(m["parameter"], m["parameter_meaning"], m["exact"], values, q, within,
                          feasible, m["manifolds"], m["singular"], fig)

    def symbolic(self, numbers: bool = False, ee: int = 0) -> Symbolic:
        """The direct kinematics in the textbook's symbols (each A_i^{i-1} and T_n^0);
        ``numbers`` substitutes the constant lengths by their values."""
        text, latex, md = _core.symbolic(self._core, bool(numbers), ee)
        return Symbolic(text, latex, md)

    def figure(
        self,
        q: Any = None,
        view: str = "iso",
        size: Tuple[int, int] = (800, 600),
        frames: bool = False,
        theme: str = "light",
    ) -> Figure:
        """The arm at ``q`` (default its "ready" configuration, else zero) from ``view`` ("iso",
        "front", "side", "top"), with its DH frames when ``frames``."""
        if q is None:
            q = self.configs.get("ready", np.zeros(self.dof))
        png, svg = _core.render(self._core, _floats(q, "q"), view, int(size[0]), int(size[1]),
                                bool(frames), theme)
        return Figure(png, svg, self.name)


def _wrapped(dq: np.ndarray, kinds: Sequence[str]) -> np.ndarray:
    """Joint differences with revolute ones wrapped into (-pi, pi]."""
    out = np.array(dq, dtype=float)
    for k, kind in enumerate(kinds):
        if kind == "revolute":
            out[k] = (out[k] + np.pi) % (2 * np.pi) - np.pi
    return out


# ---------------------------------------------------------------------------------------------
# Calibration


def calibrate(
    robot: Robot,
    measurements: Union[PathLike, Tuple[Any, Any], None] = None,
    *,
    setup: Optional[str] = None,
    validate: Optional[PathLike] = None,
    simulate: bool = False,
    poses: int = 50,
    select: str = "random",
    tolerance_mm: float = 1.0,
    tolerance_deg: float = 0.5,
    noise_mm: float = 0.05,
    noise_mrad: float = 0.1,
    position_only: bool = False,
    seed: int = 1,
    groups: int = 3,
    distance_mm: float = 300.0,
    sphere_radius_mm: Optional[float] = None,
    with_base: bool = False,
    with_tool: bool = False,
    with_compliance: bool = False,
    fix: Optional[Sequence[str]] = None,
    hayati: str = "auto",
    unidentifiable: str = "nominal",
    correct_targets: Optional[PathLike] = None,
) -> CalibrationReport:
    """Calibrates ``robot``'s DH parameters from measurements, as ``armlab calibrate`` does, in
    the library (one computation per call; no command line, no temporary file).

    ``measurements`` is a file (a headered CSV with units, robot_cal_tools' YAML, FIGAROH's CSV,
    or armlab's plain file; ``setup`` = "pose", "position", "tracker", "distance", "pivot",
    "plane" or "sphere"), or a pair of arrays ``(Q, Y)``: Q (N, dof) joint values and Y (N, 3)
    measured tool positions or (N, 4, 4) poses (m). ``validate`` is a held-out file of the same
    format.

    ``simulate=True`` makes a "real" arm (the model plus deviations within ``tolerance_mm`` and
    ``tolerance_deg``) and ``poses`` measurements of it (as many again held out), chosen by
    ``select`` ("random", "o1" or "o4"), ``position_only`` or full poses, from ``seed``;
    ``groups``, ``distance_mm`` and ``sphere_radius_mm`` shape the pivot, plane, sphere and
    distance setups. ``noise_mm`` / ``noise_mrad`` are the measurement noise (the weights).

    The model: ``with_base``, ``with_tool``, ``with_compliance`` add parameters; ``fix`` keeps
    parameters at their nominal values by name ("d1", "theta6"); ``hayati`` is "auto" (beta on
    parallel axes) or "off"; ``unidentifiable`` is "nominal" or "minimum-norm".
    ``correct_targets`` is a file of desired tool poses, corrected in every posture.

    Returns the report, identifiability in words included. Raises ``CalibrationError`` naming the
    file and line of bad data, ``ValueError`` naming a bad keyword.
    """
    path: Optional[str] = None
    text: Optional[str] = None
    if isinstance(measurements, tuple):
        text = _measurement_text(robot, *measurements)
    elif measurements is not None:
        path = os.fspath(measurements)
    elif not simulate:
        raise ValueError("give measurements (a file or (Q, Y) arrays), or simulate=True")

    def fspath(p: Optional[PathLike]) -> Optional[str]:
        return None if p is None else os.fspath(p)

    data, summary = _core.calibrate(
        robot._core, measurements=path, measurements_text=text, setup=setup,
        validate=fspath(validate), simulate=simulate, poses=poses, select=select,
        tolerance_mm=tolerance_mm, tolerance_deg=tolerance_deg, noise_mm=noise_mm,
        noise_mrad=noise_mrad, position_only=position_only, seed=seed, groups=groups,
        distance_mm=distance_mm, sphere_radius_mm=sphere_radius_mm, with_base=with_base,
        with_tool=with_tool, with_compliance=with_compliance, fix=list(fix or []),
        hayati=hayati, unidentifiable=unidentifiable,
        correct_targets=fspath(correct_targets),
    )
    return CalibrationReport(json.loads(data), summary)


def _measurement_text(robot: Robot, Q: Any, Y: Any) -> str:
    """(Q, Y) arrays as the text of armlab's plain measurement file."""
    q = _floats(Q, "Q")
    y = _floats(Y, "Y")
    if q.ndim != 2 or q.shape[1] != robot.dof:
        raise ValueError(f"Q must have shape (N, {robot.dof}); got shape {q.shape}")
    if y.shape not in ((q.shape[0], 3), (q.shape[0], 4, 4)):
        raise ValueError(f"Y must have shape ({q.shape[0]}, 3) or ({q.shape[0]}, 4, 4); got shape {y.shape}")
    for name, a in (("Q", q), ("Y", y)):
        bad = np.argwhere(~np.isfinite(a))
        if bad.size:
            raise ValueError(f"{name} contains a non-finite number at index {tuple(int(i) for i in bad[0])}")
    rows = np.hstack([q, y.reshape(q.shape[0], -1)])
    f = io.StringIO()
    f.write("# armlab measurements (SI units: rad, m), written by armlab.calibrate\n")
    np.savetxt(f, rows, delimiter=",", fmt="%.17g")
    return f.getvalue()
