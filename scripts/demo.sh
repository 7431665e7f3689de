#!/usr/bin/env bash
# Installs the dependencies, builds Proxima (release) and runs the main job: `proxima demo`
# (the billiard break), then `proxima demo-tunnelling` (discrete against continuous detection)
# and `proxima demo-platformer` (the 2D world), whose pictures go next to the billiards one:
# PATH.svg gives PATH.png, PATH-tunnelling.svg and .png, and PATH-platformer.svg and .png
# (proxima-demo.svg and .png, proxima-demo-tunnelling.svg and .png, proxima-demo-platformer.svg
# and .png by default). The arguments go to `proxima demo`; of them the other demos follow
# --svg ('' : no pictures) and --quiet.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/install-deps.sh
cmake --preset release >/dev/null
cmake --build --preset release --target proxima_cli proxima_python

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
platformer=(--svg)
if [ -n "$svg" ]; then tunnelling+=("${svg%.svg}-tunnelling.svg" --png "${svg%.svg}-tunnelling.png"); else tunnelling+=("" --png ""); fi
if [ -n "$svg" ]; then platformer+=("${svg%.svg}-platformer.svg" --png "${svg%.svg}-platformer.png"); else platformer+=("" --png ""); fi

# The billiards PNG goes beside its SVG too, unless the arguments name it.
billiards_png=()
if [[ " ${args[*]} " != *" --png"* ]]; then
  if [ -n "$svg" ]; then billiards_png=(--png "${svg%.svg}.png"); else billiards_png=(--png ""); fi
fi
./build/release/tools/proxima demo "$@" "${billiards_png[@]}"
./build/release/tools/proxima demo-tunnelling "${tunnelling[@]}" "${quiet[@]}"
./build/release/tools/proxima demo-platformer "${platformer[@]}" "${quiet[@]}"
