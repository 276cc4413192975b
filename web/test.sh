#!/usr/bin/env bash
# The web build's test (run by .ci/run): builds the static folder and drives it in headless
# Chromium through chromedriver (web/test_page.py). Fails, never skips, without a browser.
set -euo pipefail
cd "$(dirname "$0")/.."
web/build.sh web/dist
python3 web/test_page.py web/dist
