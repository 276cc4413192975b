#!/usr/bin/env bash
# Builds the user guide (docs/book): its pictures made anew by armlab (docs/pictures.sh), the
# book by mdBook (installed from crates.io if missing), and its internal links and pictures
# checked (docs/check_links.py). Part of the README's test command.
set -euo pipefail
cd "$(dirname "$0")/.."
docs/pictures.sh ${ARMLAB:+"$ARMLAB"}
if ! command -v mdbook >/dev/null 2>&1; then
  echo "installing mdbook from crates.io"
  cargo install mdbook --version "^0.4" --locked --quiet
fi
mdbook build docs
python3 docs/check_links.py
echo "guide built: docs/book/index.html"
