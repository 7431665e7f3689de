#!/usr/bin/env bash
# Installs the dependencies, builds Proxima (release) and runs the main job: `proxima demo`
# (the billiard break), then `proxima demo-tunnelling` (discrete against continuous detection),
# whose picture goes next to the billiards one: PATH.svg gives PATH-tunnelling.svg
# (proxima-demo.svg and proxima-demo-tunnelling.svg by default). The arguments go to
# `proxima demo`; of them the tunnelling demo follows --svg ('' : no pictures) and --quiet.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/install-deps.sh
cmake --preset release >/dev/null
cmake --build --preset release --target proxima_cli

svg=proxima-demo.svg
tunnelling=(--svg)
quiet=()
args=("$@")
for ((i = 0; i < ${#args[@]}; i++)); do
  case "${args[i]}" in
    --svg) svg="${args[i + 1]-}" ;;
    --svg=*) svg="${args[i]#--svg=}" ;;
    --quiet | -q) quiet=(--quiet) ;;
    --help | -h) exec ./build/release/tools/proxima demo "$@" ;;
  esac
done
if [ -n "$svg" ]; then tunnelling+=("${svg%.svg}-tunnelling.svg"); else tunnelling+=(""); fi

./build/release/tools/proxima demo "$@"
./build/release/tools/proxima demo-tunnelling "${tunnelling[@]}" "${quiet[@]}"
