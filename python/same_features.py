"""Checks that `cargo test` and the Python extension's build enable the same features in every
crate they share, so that python/test.sh reuses cargo test's build instead of building the
dependency stack again (cargo unifies features per build). Exits 1 naming each crate whose
features differ, and the line of Cargo.toml that aligns them."""
import re
import subprocess
import sys


def features(*args: str) -> dict:
    out = subprocess.run(
        ["cargo", "tree", "--prefix", "none", "-f", "{p} [{f}]", *args],
        check=True, capture_output=True, text=True,
    ).stdout
    found: dict = {}
    for line in out.splitlines():
        m = re.match(r"(\S+ v\S+)(?: \(.*?\))? \[(.*)\]", line.strip())
        if m:
            found.setdefault(m.group(1), set()).add(m.group(2))
    return found


def main() -> int:
    tests = features("-p", "armlab", "-e", "normal,build,dev")
    python = features("-p", "armlab-python", "-e", "normal,build")
    differ = sorted(k for k in set(tests) & set(python) if tests[k] != python[k])
    for k in differ:
        print(f"python/same_features.py: {k}: cargo test builds it with {sorted(tests[k])}, "
              f"the Python extension with {sorted(python[k])}; add the missing features to "
              "armlab's [dev-dependencies] (or [build-dependencies] for proc-macro crates) in "
              "Cargo.toml", file=sys.stderr)
    return 1 if differ else 0


if __name__ == "__main__":
    sys.exit(main())
