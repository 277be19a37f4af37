#!/usr/bin/env bash
# `make run`: opens the studio on the bundled sample, or, with no display, runs the headless pipeline on it.
set -euo pipefail
build_dir=${1:-build}
cli="$build_dir/app/plenopath"
studio="$build_dir/app/plenopath-studio"
sample_project="resources/samples/office/office.plenopath"

"$cli" --version
if [[ -f "$sample_project" ]]; then
  "$cli" info "$sample_project"
fi

if [[ -n "${DISPLAY:-}" ]] && command -v xdpyinfo >/dev/null && xdpyinfo >/dev/null 2>&1; then
  echo "Opening the studio…"
  exec "$studio" ${sample_project:+$( [[ -f "$sample_project" ]] && echo "$sample_project")}
else
  echo "No display: the headless demo above ran instead. Start the studio on a desktop with: make run"
fi
