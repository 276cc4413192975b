#!/usr/bin/env bash
# The web build's test (run by .ci/run): builds the static folder and drives it in headless
# Chromium through chromedriver (web/test_page.py). Fails, never skips, without a browser.
set -euo pipefail
cd "$(dirname "$0")/.."
# The `web-test` profile (Cargo.toml: the shipped one without fat LTO) without the wasm-opt pass,
# unless ARMLAB_WEB_PROFILE=web asks for the shipped build.
export ARMLAB_WEB_PROFILE="${ARMLAB_WEB_PROFILE:-web-test}"
if [ "$ARMLAB_WEB_PROFILE" = web-test ]; then
  export ARMLAB_WASM_OPT="${ARMLAB_WASM_OPT:-0}"
fi
web/build.sh web/dist
python3 web/test_page.py web/dist
# the live class: the class server (target/debug/armlab) serving web/dist, a teacher's page and
# two students' pages
python3 web/test_class.py web/dist
