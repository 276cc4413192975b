#!/usr/bin/env bash
# Builds the user guide (docs/book): its pictures made anew by armlab (docs/pictures.sh), the
# book by mdBook (installed from crates.io if missing), and its internal links and pictures
# checked (docs/check_links.py). Part of the README's test command.
set -euo pipefail
cd "$(dirname "$0")/.."
docs/pictures.sh ${ARMLAB:+"$ARMLAB"}
if ! command -v mdbook >/dev/null 2>&1; then
  # The book builder only (no `serve` or `watch`, whose web server and file watcher are most
  # of its build), at opt-level 1: a tool, not the product.
  echo "installing mdbook from crates.io"
  CARGO_PROFILE_RELEASE_OPT_LEVEL=1 CARGO_PROFILE_RELEASE_LTO=false \
    CARGO_PROFILE_RELEASE_CODEGEN_UNITS=16 CARGO_PROFILE_RELEASE_DEBUG=false \
    cargo install mdbook --version "^0.4" --locked --quiet --no-default-features --features search
fi
mdbook build docs
python3 docs/check_links.py
echo "guide built: docs/book/index.html"
