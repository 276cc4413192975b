"""Type stubs of ``armlab._core``, the Rust extension module behind :mod:`armlab`.

Use the :mod:`armlab` package's API (``armlab.Robot`` and friends); this module is its engine.
Arrays are float64; joint values in rad or m, lengths in m, poses (4, 4) row-major.
"""

from typing import Any, Dict, List, Optional, Tuple

import numpy as np
import numpy.typing as npt

__version__: str

class ArmlabError(Exception):
    """Base class of armlab's errors (the Rust library's typed errors, same messages)."""

class ModelError(ArmlabError):
    """A model that cannot be loaded; the message names the file, line and field."""

class KinematicsError(ArmlabError):
    """Forward kinematics or a Jacobian refused its input."""

class IkError(ArmlabError):
    """Inverse kinematics refused its input (no closed form, a target it cannot take)."""

class WorkspaceError(ArmlabError):
    """A workspace computation or point query this arm does not support."""

class FigureError(ArmlabError):
    """A figure could not be drawn (e.g. no graphics adapter)."""

class CalibrationError(ArmlabError):
    """A calibration that could not run; the message names the file and line."""

class CollisionError(ArmlabError):
    """A scene the collision checker cannot use; the message names the file, line and obstacle."""

F64 = npt.NDArray[np.float64]

class CoreRobot:
    """One robot and its closed-form solver, detected once."""

    @staticmethod
    def load(spec: str) -> "CoreRobot":
        """A built-in name or a path to a .toml model file or a .urdf."""
    @staticmethod
    def builtins() -> List[Tuple[str, str]]:
        """(name, summary) of every built-in model."""
    @property
    def name(self) -> str: ...
    @property
    def spec(self) -> str: ...
    @property
    def dof(self) -> int: ...
    def joints(self) -> List[Tuple[str, str, float, float]]:
        """(name, kind, lower, upper) per joint variable."""
    def end_effectors(self) -> List[str]: ...
    def closed_form(self) -> Optional[str]: ...
    def no_closed_form_reason(self) -> Optional[str]: ...
    def configs(self) -> List[Tuple[str, List[float]]]: ...
    def frame_names(self) -> List[str]: ...
    def fk(self, q: F64, ee: int) -> F64:
        """(4, 4) world_from_tool."""
    def fk_frames(self, q: F64) -> F64:
        """(frames, 4, 4) world_from_frame_j."""
    def jacobian(self, q: F64, ee: int) -> F64:
        """(6, dof) geometric Jacobian, world frame."""
    def manipulability(self, q: F64, ee: int) -> Tuple[float, List[int]]:
        """(manipulability, task rows)."""
    def ik(
        self,
        target: F64,
        ee: int = 0,
        seed: Optional[F64] = None,
        solver: str = "auto",
        scene_path: Optional[str] = None,
        scene_text: Optional[str] = None,
    ) -> Tuple[
        Tuple[str, Optional[float], str, List[Tuple[List[float], str, bool, float, float, List[Tuple[int, str]], str, str, str]]],
        List[str],
    ]:
        """((status, distance, solver, [(q, posture, within_limits, position_error,
        orientation_error, free joints, posture fields JSON, collision report JSON, collision
        summary)]), the collision checker's warnings)."""
    def ik_numerical(
        self,
        target: F64,
        q0: F64,
        ee: int = 0,
        method: str = "lm",
        tolerance: float = 1e-10,
        max_iterations: int = 100,
        restarts: int = 50,
        seed: int = 0x5EED,
    ) -> str:
        """The numerical solver's report as JSON."""

def reachability(
    robot: CoreRobot,
    voxel: float = 0.05,
    directions: int = 200,
    rolls: int = 8,
    ee: int = 0,
    seeds: int = 4,
    force: bool = False,
    scene_path: Optional[str] = None,
    scene_text: Optional[str] = None,
) -> Dict[str, Any]:
    """The reachability map as a dict with the keys of `armlab reachability`'s .npz file."""

def fk_batch(
    robot: CoreRobot, qs: F64, ee: int = 0, frames: bool = False, out: Optional[F64] = None
) -> F64:
    """(N, 4, 4) or (N, frames, 4, 4); every core, the GIL released."""

def collisions(
    robot: CoreRobot, q: F64, scene_path: Optional[str] = None, scene_text: Optional[str] = None
) -> Tuple[str, List[str]]:
    """(the report as JSON, or a list of them for (N, dof), the checker's warnings)."""

def ik_batch(
    robot: CoreRobot, ts: F64
) -> Tuple[F64, npt.NDArray[np.bool_], npt.NDArray[np.bool_], npt.NDArray[np.int32], List[Tuple[int, str]]]:
    """(q (N, k, dof), valid (N, k), within_limits (N, k), posture codes (N, k), labels)."""

def ik_batch_numerical(
    robot: CoreRobot,
    ts: F64,
    seeds: Optional[F64] = None,
    ee: int = 0,
    tolerance: float = 1e-10,
    max_iterations: int = 100,
    restarts: int = 50,
) -> Tuple[F64, npt.NDArray[np.bool_], npt.NDArray[np.bool_], npt.NDArray[np.int32], List[Tuple[int, str]], F64, F64]:
    """(q (N, 1, dof), converged (N, 1), within_limits (N, 1), codes (N, 1), labels,
    position errors (N,), orientation errors (N,))."""

def render(
    robot: CoreRobot,
    q: F64,
    view: str = "iso",
    width: int = 800,
    height: int = 600,
    frames: bool = False,
    theme: str = "light",
) -> Tuple[bytes, str]:
    """(png, svg) of the arm at q."""

def workspace(
    robot: CoreRobot,
    view: Optional[str] = None,
    point: str = "wrist-centre",
    color_by: str = "posture",
    samples: int = 200_000,
    seed: int = 1,
    width: int = 1200,
    height: int = 900,
    theme: str = "light",
) -> Tuple[str, bytes, str]:
    """(statistics JSON, png, svg)."""

def reach(
    robot: CoreRobot, points: F64, point: str = "wrist-centre"
) -> Tuple[List[bool], List[float], List[List[str]], bool, int]:
    """(reachable, distance, postures, exact, dimension)."""

def self_motion(
    robot: CoreRobot,
    target: F64,
    samples: int = 360,
    lock: Optional[int] = None,
    branch: Optional[str] = None,
    ee: int = 0,
    figure: bool = False,
) -> Tuple[str, Optional[Tuple[bytes, str]]]:
    """(JSON, (png, svg) or None)."""

def symbolic(robot: CoreRobot, numbers: bool = False, ee: int = 0) -> Tuple[str, str, str]:
    """(text, latex, markdown)."""

def calibrate(
    robot: CoreRobot, *, measurements: Optional[str] = None,
    measurements_text: Optional[str] = None, setup: Optional[str] = None,
    validate: Optional[str] = None, simulate: bool = False, poses: int = 50,
    select: str = "random", tolerance_mm: float = 1.0, tolerance_deg: float = 0.5,
    noise_mm: float = 0.05, noise_mrad: float = 0.1, position_only: bool = False, seed: int = 1,
    groups: int = 3, distance_mm: float = 300.0, sphere_radius_mm: Optional[float] = None,
    with_base: bool = False, with_tool: bool = False, with_compliance: bool = False,
    fix: List[str] = ..., hayati: str = "auto", unidentifiable: str = "nominal",
    correct_targets: Optional[str] = None,
) -> Tuple[str, str]:
    """One calibration in the library (the experiment built from these keywords, run once):
    (the report's JSON, its text)."""

def run_cli(args: List[str], error: str = "armlab") -> str:
    """``armlab ARGS...`` in process; what it printed."""

def svg_to_pdf(svg: str) -> bytes:
    """A PDF of an SVG figure."""

def textbook_figure(name: str, width: int = 1200, height: int = 900, theme: str = "light") -> Tuple[bytes, str]:
    """(png, svg) of a figure of the excerpt."""

def rotation_to(rs: F64, to: str, second: bool = False, out: Optional[F64] = None) -> F64:
    """Rotation matrices (N, 3, 3) in representation ``to`` ("zyz", "zxz", "rpy": (N, 3) rad;
    "axis_angle": (N, 4) (theta, rx, ry, rz); "quaternion": (N, 4) (eta, ex, ey, ez), eta >= 0);
    ``second``: the other Euler solution. Each matrix orthonormal to 1e-6 with det +1."""

def rotation_from(xs: F64, kind: str, out: Optional[F64] = None) -> F64:
    """Rotation matrices (N, 3, 3) of rows (N, 3) or (N, 4) in representation ``kind``."""
