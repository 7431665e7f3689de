#!/usr/bin/env bash
# The viewer's tests (ctest's viewer.browser): installs the pinned npm packages when
# node_modules lacks them (`npm ci`, from package-lock.json), then runs node's test runner on
# the capture reader and on the page in headless Chromium. Needs PROXIMA_CLI (the built
# proxima executable; ctest sets it) and /usr/bin/chromium (or $CHROMIUM).
set -euo pipefail
cd "$(dirname "$0")/.."
if [ ! -f node_modules/three/build/three.module.js ] || [ ! -d node_modules/playwright-core ]; then
  npm ci --no-audit --no-fund
fi
exec node --test test/capture.test.mjs test/browser.test.mjs
