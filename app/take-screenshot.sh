#!/usr/bin/env bash
# `make screenshot`: the studio on the bundled office sample, grabbed to a PNG for the README.
# Usage: app/take-screenshot.sh BUILD_DIR OUTPUT.png [PROJECT.plenopath]
# Runs under a virtual X server when there is no display. The studio opens the project, computes visibility
# (Process ▸ Compute visibility) when the project has none, samples keyframes when it has none, goes to a
# frame in the middle of the walk, waits for the panorama to show it, saves the window and exits.
set -euo pipefail
build_dir=${1:?usage: take-screenshot.sh BUILD_DIR OUTPUT.png [PROJECT]}
output=${2:?usage: take-screenshot.sh BUILD_DIR OUTPUT.png [PROJECT]}
project=${3:-resources/samples/office/office.plenopath}
studio="$build_dir/app/plenopath-studio"

if [[ ! -x "$studio" ]]; then
  echo "take-screenshot: $studio not found; build first (make build)" >&2
  exit 1
fi
if [[ -z "${3:-}" ]]; then
  # The bundled sample: write it and render its capture if needed (cached), without opening the studio.
  DISPLAY= bash app/run-sample.sh "$build_dir" > /dev/null
fi
if [[ ! -f "$project" ]]; then
  echo "take-screenshot: $project not found" >&2
  exit 1
fi
mkdir -p "$(dirname "$output")"

run=()
if [[ -z "${DISPLAY:-}" ]]; then
  run=(xvfb-run -a -s "-screen 0 1600x1000x24")
fi
# A throwaway settings folder: the screenshot must not depend on (or change) the user's window layout.
settings=$(mktemp -d)
trap 'rm -rf "$settings"' EXIT
XDG_CONFIG_HOME="$settings" XDG_DATA_HOME="$settings" "${run[@]}" "$studio" "$project" \
  --screenshot "$output" --size 1600x1000 --frame "${SCREENSHOT_FRAME:-middle}" --look "${SCREENSHOT_LOOK:-0}" \
  --compute-visibility --resample
echo "wrote $output"
