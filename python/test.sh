#!/usr/bin/env bash
# The Python package's checks: lint its Rust crate, build and install the package into a virtual
# environment in cargo's build folder (`pip install ./python[test]`: maturin and NumPy from PyPI),
# then its pytest suite (python/tests), which compares with the command line and executes
# python/examples/tour.ipynb. The build folder is cargo's own (`cargo metadata`: `target/`, or
# CARGO_TARGET_DIR where it is set), and the extension is built there in the dev profile, as
# `cargo test` built the crate, so that its dependencies are not built a third time (a user's
# `pip install ./python` builds in release).
# Needs python3 with venv and pip, a Rust toolchain, and for the figures a graphics adapter
# (Mesa's lavapipe without a GPU: mesa-vulkan-drivers libvulkan1).
set -euo pipefail
cd "$(dirname "$0")/.."
start=$SECONDS

target_dir=$(cargo metadata --format-version 1 --no-deps \
  | python3 -c 'import json, sys; print(json.load(sys.stdin)["target_directory"])')
# cargo test and this build share their dependencies only with the same features (see the script).
python3 python/same_features.py
cargo clippy -p armlab-python --all-targets -- -D warnings
# The command line the tests compare with (already built by `cargo test`).
cargo build --bin armlab
export ARMLAB_BIN="$target_dir/debug/armlab"
[ -x "$ARMLAB_BIN" ] || { echo "python/test.sh: no $ARMLAB_BIN after cargo build" >&2; exit 1; }

venv="$target_dir/python-venv"
if [ ! -x "$venv/bin/python" ]; then
  python3 -m venv "$venv"
fi
MATURIN_PEP517_ARGS="--profile dev" \
  "$venv/bin/python" -m pip install --quiet --disable-pip-version-check "./python[test]"
"$venv/bin/python" -m pytest -q python/tests
echo "python/test.sh: $((SECONDS - start)) s"
