#!/usr/bin/env bash
# Makes the guide's pictures with armlab itself: one line of docs/pictures.txt per picture,
# "NAME.png<TAB>armlab ARGS...", run in docs/src/pictures with the given armlab binary.
# Usage: docs/pictures.sh [ARMLAB_BINARY]   (default: armlab in cargo's build folder, built if missing)
set -euo pipefail
cd "$(dirname "$0")/.."
# cargo's build folder (`target/`, or CARGO_TARGET_DIR where it is set).
target_dir=$(cargo metadata --format-version 1 --no-deps \
  | python3 -c 'import json, sys; print(json.load(sys.stdin)["target_directory"])')
bin=${1:-$target_dir/debug/armlab}
if [ ! -x "$bin" ]; then
  cargo build --bin armlab
  bin=$target_dir/debug/armlab
fi
bin=$(realpath "$bin")
mkdir -p docs/src/pictures
cd docs/src/pictures
while IFS=$'\t' read -r name command; do
  case "$name" in ''|'#'*) continue ;; esac
  read -r -a words <<<"$command"
  [ "${words[0]}" = armlab ] || { echo "docs/pictures.txt: $name: the command must start with armlab" >&2; exit 1; }
  "$bin" "${words[@]:1}" >/dev/null
  [ -s "$name" ] || { echo "docs/pictures.txt: $name: the command wrote no $name" >&2; exit 1; }
  echo "picture $name"
done < ../../pictures.txt
