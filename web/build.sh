#!/usr/bin/env bash
# Builds the app for the browser into a folder of static files (default web/dist): index.html,
# armlab.js (the glue), armlab_bg.wasm and worker.js (the web worker for heavy computations). Serve the folder with any static file server, e.g.
#   python3 -m http.server 8765 --bind 127.0.0.1 --directory web/dist
#
# Toolchain, whichever is here:
# * rustup with the target (`rustup target add wasm32-unknown-unknown`): used as is;
# * else Debian's rustc-web (packages rustc-web cargo-web rust-web-src rust-web-llvm lld-22): its
#   standard library is built from source for wasm32 (-Zbuild-std, allowed by RUSTC_BOOTSTRAP=1).
# and wasm-bindgen-cli at the version of the wasm-bindgen in Cargo.lock (installed if missing).
set -euo pipefail
cd "$(dirname "$0")/.."
out="${1:-web/dist}"
target=wasm32-unknown-unknown
export CARGO_TARGET_DIR="${CARGO_TARGET_DIR:-$PWD/target}/web"
args=(rustc --lib --crate-type cdylib --profile web --target "$target" --no-default-features --features gui)

if rustup target list --installed 2>/dev/null | grep -qx "$target"; then
  cargo "${args[@]}" -- -D warnings
elif [ -x /usr/bin/rustc ] && /usr/bin/rustc --print target-list | grep -qx "$target" \
  && [ -d /usr/lib/rustlib/src/rust/library ]; then
  PATH="/usr/bin:$PATH" RUSTC=/usr/bin/rustc RUSTC_BOOTSTRAP=1 \
    /usr/bin/cargo "${args[@]}" -Zbuild-std=std,panic_abort -- -D warnings
else
  echo "web/build.sh: no Rust toolchain for $target here. Either" >&2
  echo "  rustup target add $target" >&2
  echo "or (Debian 12) apt-get install rustc-web cargo-web rust-web-src rust-web-llvm lld-22" >&2
  exit 1
fi

want=$(grep -A1 '^name = "wasm-bindgen"$' Cargo.lock | sed -n 's/^version = "\(.*\)"/\1/p')
have=$(wasm-bindgen --version 2>/dev/null | awk '{print $2}' || true)
if [ "$have" != "$want" ]; then
  echo "installing wasm-bindgen-cli $want (have: ${have:-none}; about 6 min on two cores)"
  cargo install -q wasm-bindgen-cli --version "$want"
fi

rm -rf "$out"
mkdir -p "$out"
wasm-bindgen --target web --no-typescript --out-dir "$out" --out-name armlab \
  "$CARGO_TARGET_DIR/$target/web/armlab.wasm"
cp web/index.html web/worker.js "$out/"
# the shipped lessons, for ?lesson=lessons/NAME.toml
mkdir -p "$out/lessons" && cp assets/lessons/*.toml "$out/lessons/"
wasm=$(stat -c %s "$out/armlab_bg.wasm")
gz=$(gzip -9 -c "$out/armlab_bg.wasm" | wc -c)
echo "web build in $out: armlab_bg.wasm $((wasm / 1024)) KiB, $((gz / 1024)) KiB gzipped"
