"""Timing of the Python package's hot paths (plain timing, medians over repeats).

    python python/bench/bench.py            # after `pip install ./python`

Prints one Markdown row per measurement, for the README's performance table. With the Robotics
Toolbox for Python importable (``pip install roboticstoolbox-python``), its fastest FK path
(``ETS.eval`` on the same 100,000 Puma configurations) is timed in the same run, side by side.
Set RAYON_NUM_THREADS to pin the number of threads of the batch calls (default: every core).
"""

from __future__ import annotations

import os
import statistics
import sys
import time
import timeit

import numpy as np

import armlab


def per_call(stmt, number: int, repeat: int = 7) -> float:
    """Median seconds per call over `repeat` runs of `number` calls."""
    return statistics.median(t / number for t in timeit.repeat(stmt, number=number, repeat=repeat))


def per_batch(stmt, repeat: int = 9) -> float:
    """Median seconds of one call."""
    times = []
    for _ in range(repeat):
        t = time.perf_counter()
        stmt()
        times.append(time.perf_counter() - t)
    return statistics.median(times)


def rotations(rng) -> list:
    """armlab.rotation on 1,000,000 rotation matrices (issue 47: >= 20 M/s on two cores)."""
    from armlab import rotation

    n = 1_000_000
    R = rotation.from_zyz(rng.uniform(-np.pi, np.pi, (n, 3)))
    rows = []
    for kind in ("zyz", "zxz", "rpy", "axis_angle", "quaternion"):
        out = np.empty((n, 3 if kind in ("zyz", "zxz", "rpy") else 4))
        t = per_batch(lambda: rotation.convert_to(R, kind, out=out), repeat=5)
        rows.append((f"`armlab.rotation`: 1,000,000 matrices to {kind} into `out=`", f"{n / t / 1e6:.1f} M/s"))
        X = out.copy()
        back = np.empty((n, 3, 3))
        t = per_batch(lambda: rotation.convert_from(X, kind, out=back), repeat=5)
        rows.append((f"`armlab.rotation`: 1,000,000 {kind} rows to matrices into `out=`", f"{n / t / 1e6:.1f} M/s"))
    t = per_batch(lambda: rotation.to_zyz(R), repeat=5)
    rows.append(("`armlab.rotation`: 1,000,000 matrices to zyz (a new (N, 3) array)", f"{n / t / 1e6:.1f} M/s"))
    return rows


def main() -> None:
    cores = os.cpu_count()
    threads = os.environ.get("RAYON_NUM_THREADS", str(cores))
    print(f"# armlab {armlab.__version__}, Python {sys.version.split()[0]}, NumPy {np.__version__}, "
          f"{cores} cores, {threads} threads for the batch calls")
    puma = armlab.Robot.builtin("puma560")
    rng = np.random.default_rng(1)
    lo, hi = puma.limits[:, 0], puma.limits[:, 1]
    q = rng.uniform(lo, hi)
    q_list = [float(v) for v in q]
    rows = []

    t = per_call(lambda: puma.fk(q), 100_000)
    rows.append(("`fk(q)`, Puma 560, q a NumPy array (one call, Python overhead included)", f"{t * 1e6:.2f} µs"))
    t = per_call(lambda: puma.fk(q_list), 100_000)
    rows.append(("`fk(q)`, Puma 560, q a list of floats", f"{t * 1e6:.2f} µs"))

    Q = rng.uniform(lo, hi, (100_000, 6))
    t = per_batch(lambda: puma.fk(Q))
    rows.append(("batch FK, Puma 560, 100,000 configurations (a new (N, 4, 4) array)", f"{len(Q) / t / 1e6:.1f} M poses/s"))
    Q1 = rng.uniform(lo, hi, (1_000_000, 6))
    out = np.empty((len(Q1), 4, 4))
    t = per_batch(lambda: puma.fk(Q1, out=out), repeat=5)
    rows.append(("batch FK, Puma 560, 1,000,000 configurations into `out=`", f"{len(Q1) / t / 1e6:.1f} M poses/s"))
    t = per_batch(lambda: puma.fk(Q1), repeat=5)
    rows.append(("batch FK, Puma 560, 1,000,000 configurations (a new 128 MB array)", f"{len(Q1) / t / 1e6:.1f} M poses/s"))

    Ts = puma.fk(Q)
    t = per_batch(lambda: puma.ik(Ts))
    rows.append(("batch closed-form IK, Puma 560, all 8 solutions of 100,000 poses (`ik(Ts)`)", f"{len(Ts) / t / 1e6:.2f} M poses/s"))
    T = Ts[0]
    t = per_call(lambda: puma.ik(T, all=True), 5_000)
    rows.append(("`ik(T, all=True)`, Puma 560: 8 labelled, FK-checked solutions (one call)", f"{t * 1e6:.1f} µs"))

    rows.extend(rotations(rng))

    try:
        import roboticstoolbox as rtb  # the peer, when installed

        ets = rtb.models.DH.Puma560().ets()
        ets.eval(Q[:10])
        t = per_batch(lambda: ets.eval(Q), repeat=5)
        rows.append((f"peer: Robotics Toolbox {rtb.__version__} `ETS.eval`, the same 100,000 configurations",
                     f"{len(Q) / t / 1e6:.2f} M poses/s"))
    except ImportError:
        rows.append(("peer: Robotics Toolbox `ETS.eval`", "not installed (pip install roboticstoolbox-python)"))

    print("| what | median |")
    print("|---|---|")
    for what, value in rows:
        print(f"| {what} | {value} |")


if __name__ == "__main__":
    main()
