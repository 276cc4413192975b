"""armlab.rotation: rotation matrices and the minimal representations of Sect. 2.4, in batches.

Stacks of rotation matrices ``R`` of shape (N, 3, 3) (or one (3, 3) matrix) convert to

- Euler angles ZYZ ``R = Rz(phi) Ry(theta) Rz(psi)`` (2.18), ZXZ ``Rz(phi) Rx(theta) Rz(psi)``
  (Problem 2.1) and roll-pitch-yaw ``Rz(phi) Ry(theta) Rx(psi)`` (2.21): (N, 3) rows
  ``(phi, theta, psi)`` in rad; the first solution has theta in [0, pi] (ZYZ, ZXZ) or
  [-pi/2, pi/2] (RPY), ``second=True`` gives the other one; at a singular case phi = 0;
- angle and axis (2.27)-(2.28): (N, 4) rows ``(theta, rx, ry, rz)``, theta in [0, pi], r a unit
  vector (z where theta = 0, where any axis serves);
- the unit quaternion (2.34)-(2.35): (N, 4) rows ``(eta, ex, ey, ez)`` with eta >= 0;

and back. The work is armlab's Rust library (each conversion a few tens of nanoseconds); a batch
releases the GIL and uses every core. Every ``to_*`` and ``from_*`` takes ``out=`` to write into
an array of the result's shape instead of a new one.

>>> import numpy as np
>>> from armlab import rotation
>>> R = rotation.from_zyz(np.radians([30.0, 45.0, 60.0]))
>>> np.degrees(rotation.to_zyz(R)).round(6)
array([30., 45., 60.])
>>> rotation.to_quaternion(np.eye(3))
array([1., 0., 0., 0.])

A matrix that is not orthonormal to 1e-6 (or a reflection), a NaN, a zero axis or quaternion, or
a wrong shape raises ``ValueError`` naming the argument and the row.
"""

from __future__ import annotations

from typing import Any, Optional

import numpy as np

from . import _core

__all__ = [
    "to_zyz",
    "to_zxz",
    "to_rpy",
    "to_axis_angle",
    "to_quaternion",
    "from_zyz",
    "from_zxz",
    "from_rpy",
    "from_axis_angle",
    "from_quaternion",
    "convert_to",
    "convert_from",
    "KINDS",
]

#: The representations, as ``convert_to`` and ``convert_from`` name them.
KINDS = ("zyz", "zxz", "rpy", "axis_angle", "quaternion")

_WIDTH = {"zyz": 3, "zxz": 3, "rpy": 3, "axis_angle": 4, "quaternion": 4}


def _floats(x: Any, name: str) -> np.ndarray:
    """``x`` as a C-contiguous float64 array, or ValueError."""
    try:
        a = np.asarray(x)
    except Exception as e:  # ragged lists and the like
        raise ValueError(f"{name} must be an array of real numbers: {e}") from None
    if a.dtype.kind not in "iuf":
        raise ValueError(f"{name} must hold real numbers; got dtype {a.dtype}")
    return np.ascontiguousarray(a, dtype=np.float64)


def convert_to(R: Any, kind: str, second: bool = False, out: Optional[np.ndarray] = None) -> np.ndarray:
    """Rotation matrices ``R`` (N, 3, 3), or one (3, 3), in representation ``kind`` (one of
    :data:`KINDS`): (N, 3) or (N, 4), or one row for one matrix."""
    if kind not in _WIDTH:
        raise ValueError(f"unknown representation {kind!r}: use one of {', '.join(KINDS)}")
    r = _floats(R, "R")
    one = r.ndim == 2
    if one:
        r = r.reshape(1, *r.shape)
        if out is not None:
            out = out.reshape(1, -1)
    result = _core.rotation_to(r, kind, bool(second), out)
    return result[0] if one else result


def convert_from(X: Any, kind: str, out: Optional[np.ndarray] = None) -> np.ndarray:
    """Rows ``X`` (N, 3) or (N, 4) of representation ``kind`` (one of :data:`KINDS`), or one row,
    as rotation matrices (N, 3, 3), or one (3, 3)."""
    if kind not in _WIDTH:
        raise ValueError(f"unknown representation {kind!r}: use one of {', '.join(KINDS)}")
    x = _floats(X, "X")
    one = x.ndim == 1
    if one:
        x = x.reshape(1, -1)
        if out is not None:
            out = out.reshape(1, 3, 3)
    result = _core.rotation_from(x, kind, out)
    return result[0] if one else result


def to_zyz(R: Any, second: bool = False, out: Optional[np.ndarray] = None) -> np.ndarray:
    """ZYZ Euler angles (phi, theta, psi) in rad, (2.19)-(2.20): theta in [0, pi], or in [-pi, 0]
    with ``second``; phi = 0 where sin(theta) = 0 (only phi +- psi is determined there)."""
    return convert_to(R, "zyz", second, out)


def to_zxz(R: Any, second: bool = False, out: Optional[np.ndarray] = None) -> np.ndarray:
    """ZXZ Euler angles (phi, theta, psi) in rad (Problem 2.1), theta in [0, pi] or, with
    ``second``, in [-pi, 0]."""
    return convert_to(R, "zxz", second, out)


def to_rpy(R: Any, second: bool = False, out: Optional[np.ndarray] = None) -> np.ndarray:
    """Roll-pitch-yaw angles (phi, theta, psi) in rad of ``R = Rz(phi) Ry(theta) Rx(psi)``
    (2.22)-(2.23): theta in [-pi/2, pi/2], or with ``second`` in (pi/2, 3pi/2) wrapped to
    (-pi, pi]."""
    return convert_to(R, "rpy", second, out)


def to_axis_angle(R: Any, out: Optional[np.ndarray] = None) -> np.ndarray:
    """Rows (theta, rx, ry, rz), (2.27)-(2.28): theta in [0, pi] (rad), r a unit vector; at
    theta = 0 (any axis serves) r = z; at theta = pi, r and -r are the same rotation."""
    return convert_to(R, "axis_angle", False, out)


def to_quaternion(R: Any, out: Optional[np.ndarray] = None) -> np.ndarray:
    """Rows (eta, ex, ey, ez) of the unit quaternion, (2.34)-(2.35), eta >= 0."""
    return convert_to(R, "quaternion", False, out)


def from_zyz(A: Any, out: Optional[np.ndarray] = None) -> np.ndarray:
    """``Rz(phi) Ry(theta) Rz(psi)`` (2.18) of rows (phi, theta, psi) in rad."""
    return convert_from(A, "zyz", out)


def from_zxz(A: Any, out: Optional[np.ndarray] = None) -> np.ndarray:
    """``Rz(phi) Rx(theta) Rz(psi)`` (Problem 2.1) of rows (phi, theta, psi) in rad."""
    return convert_from(A, "zxz", out)


def from_rpy(A: Any, out: Optional[np.ndarray] = None) -> np.ndarray:
    """``Rz(phi) Ry(theta) Rx(psi)`` (2.21) of rows (phi, theta, psi) in rad."""
    return convert_from(A, "rpy", out)


def from_axis_angle(X: Any, out: Optional[np.ndarray] = None) -> np.ndarray:
    """``R(theta, r)`` (2.25) of rows (theta, rx, ry, rz), theta in rad; r is normalized."""
    return convert_from(X, "axis_angle", out)


def from_quaternion(Q: Any, out: Optional[np.ndarray] = None) -> np.ndarray:
    """``R(eta, epsilon)`` (2.33) of rows (eta, ex, ey, ez); each row is normalized."""
    return convert_from(Q, "quaternion", out)
