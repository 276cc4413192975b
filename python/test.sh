#!/usr/bin/env bash
# The Python package's checks: lint its Rust crate, build and install the package into a virtual
# environment under target/ (`pip install ./python[test]`: maturin and NumPy from PyPI, the
# extension built in release into target/ with the rest of the workspace), then its pytest suite
# (python/tests), which compares with the command line and executes python/examples/tour.ipynb.
# Needs python3 with venv and pip, a Rust toolchain, and for the figures a graphics adapter
# (Mesa's lavapipe without a GPU: mesa-vulkan-drivers libvulkan1).
set -euo pipefail
cd "$(dirname "$0")/.."
start=$SECONDS

cargo clippy -p armlab-python --all-targets -- -D warnings
# The command line the tests compare with (already built by `cargo test`).
cargo build --bin armlab
export ARMLAB_BIN="$PWD/target/debug/armlab"

venv=target/python-venv
if [ ! -x "$venv/bin/python" ]; then
  python3 -m venv "$venv"
fi
"$venv/bin/python" -m pip install --quiet --disable-pip-version-check "./python[test]"
"$venv/bin/python" -m pytest -q python/tests
echo "python/test.sh: $((SECONDS - start)) s"
