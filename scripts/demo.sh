#!/usr/bin/env bash
# Installs the dependencies, builds Proxima (release) and runs the main job: `proxima demo`.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/install-deps.sh
cmake --preset release >/dev/null
cmake --build --preset release --target proxima_cli
./build/release/tools/proxima demo "$@"
