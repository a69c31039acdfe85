#!/usr/bin/env bash
# Builds the WebAssembly decoder (scripts/build_web.sh) and checks it under Node.js: the whole
# conformance suite through the runner's command-line contract (web/tools/m4d_decode.mjs,
# streams pushed in 4 KB chunks as a page receives them), type-checks a TypeScript use of the
# API against its declarations, then the JavaScript API's tests and
# the player's tests in headless Chromium (web/test/; puppeteer-core, which scripts/setup.sh
# installs from web/package-lock.json). Needs the native build (scripts/build.sh) for the
# player's reference images.
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/build_web.sh >/dev/null
scripts/conformance_run.sh --layers-flag --layers node web/tools/m4d_decode.mjs --chunk 4096 |
  tail -1 | sed 's/^/WebAssembly /'
(cd web && npx --no-install tsc -p tsconfig.json)  # the TypeScript declarations, m4d.d.mts
node --test web/test/
