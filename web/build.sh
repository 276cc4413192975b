#!/usr/bin/env bash
# Builds the app for the browser into a folder of static files (default web/dist): index.html,
# armlab.js (the glue), armlab_bg.wasm and worker.js (the web worker for heavy computations). Serve the folder with any static file server, e.g.
#   python3 -m http.server 8765 --bind 127.0.0.1 --directory web/dist
#
# Toolchain, whichever is here:
# * rustup with the target (`rustup target add wasm32-unknown-unknown`): used as is;
# * else Debian's rustc-web (packages rustc-web cargo-web rust-web-src rust-web-llvm lld-22): its
#   standard library is built from source for wasm32 (-Zbuild-std, allowed by RUSTC_BOOTSTRAP=1).
# and wasm-bindgen-cli at the version of the wasm-bindgen in Cargo.lock (installed if missing),
# then wasm-opt from binaryen (the npm registry's package, pinned; installed under the target
# folder if missing) on the module wasm-bindgen writes. ARMLAB_WASM_OPT=0 skips it.
set -euo pipefail
cd "$(dirname "$0")/.."
out="${1:-web/dist}"
target=wasm32-unknown-unknown
BINARYEN_VERSION=132.0.0
# Its own folder inside cargo's build folder (`target/`, or CARGO_TARGET_DIR where it is set).
target_dir=$(cargo metadata --format-version 1 --no-deps \
  | python3 -c 'import json, sys; print(json.load(sys.stdin)["target_directory"])')
export CARGO_TARGET_DIR="$target_dir/web"
# The cargo profile: `web` (fat LTO, one codegen unit: the smallest download) unless
# ARMLAB_WEB_PROFILE names another (web/test.sh builds `web-test`, see Cargo.toml).
profile="${ARMLAB_WEB_PROFILE:-web}"
args=(rustc --lib --crate-type cdylib --profile "$profile" --target "$target" --no-default-features --features gui)

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
  # A tool, not the product: built at opt-level 1 without LTO, and without its default TLS
  # stack (rustls and ring, for its test runner's downloads, which armlab does not use); it
  # still runs in seconds on armlab's module.
  echo "installing wasm-bindgen-cli $want (have: ${have:-none}; about 3 min on two cores)"
  CARGO_PROFILE_RELEASE_OPT_LEVEL=1 CARGO_PROFILE_RELEASE_LTO=false \
    CARGO_PROFILE_RELEASE_CODEGEN_UNITS=16 CARGO_PROFILE_RELEASE_DEBUG=false \
    cargo install -q wasm-bindgen-cli --version "$want" --no-default-features
fi

rm -rf "$out"
mkdir -p "$out"
wasm-bindgen --target web --no-typescript --out-dir "$out" --out-name armlab \
  "$CARGO_TARGET_DIR/$target/$profile/armlab.wasm"
if [ "${ARMLAB_WASM_OPT:-1}" != 0 ]; then
  binaryen="$CARGO_TARGET_DIR/binaryen-$BINARYEN_VERSION"
  if [ ! -x "$binaryen/node_modules/.bin/wasm-opt" ]; then
    command -v npm >/dev/null || { echo "web/build.sh: npm is needed for wasm-opt (apt-get install npm, or ARMLAB_WASM_OPT=0)" >&2; exit 1; }
    echo "installing binaryen $BINARYEN_VERSION (wasm-opt) from the npm registry"
    npm install --silent --no-audit --no-fund --prefix "$binaryen" "binaryen@$BINARYEN_VERSION"
  fi
  before=$(stat -c %s "$out/armlab_bg.wasm")
  # -O2 for speed (the workspace is computed in the page); the features are those rustc's
  # wasm32 target enables by default.
  "$binaryen/node_modules/.bin/wasm-opt" -O2 --strip-debug --strip-producers \
    --enable-bulk-memory --enable-nontrapping-float-to-int --enable-sign-ext \
    --enable-mutable-globals --enable-reference-types --enable-multivalue \
    "$out/armlab_bg.wasm" -o "$out/armlab_bg.opt.wasm"
  mv "$out/armlab_bg.opt.wasm" "$out/armlab_bg.wasm"
  echo "wasm-opt -O2: $((before / 1024)) KiB -> $(( $(stat -c %s "$out/armlab_bg.wasm") / 1024 )) KiB"
fi
cp web/index.html web/worker.js "$out/"
# the shipped lessons, for ?lesson=lessons/NAME.toml
mkdir -p "$out/lessons" && cp assets/lessons/*.toml "$out/lessons/"
wasm=$(stat -c %s "$out/armlab_bg.wasm")
gz=$(gzip -9 -c "$out/armlab_bg.wasm" | wc -c)
echo "web build in $out: armlab_bg.wasm $((wasm / 1024)) KiB, $((gz / 1024)) KiB gzipped"
