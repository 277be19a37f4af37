#!/usr/bin/env bash
# `make run`: renders the office sample's capture once (cached under resources/samples/office/capture/,
# git-ignored), then opens the studio on the sample project when there is a display, or, when there is
# none, runs the pipeline headless on it: summary, path recovery scored against ground truth, visibility.
set -euo pipefail
build_dir=${1:-build}
cli="$build_dir/app/plenopath"
studio="$build_dir/app/plenopath-studio"
sample_dir="resources/samples/office"
project="$sample_dir/office.plenopath"
capture="$sample_dir/capture"
stamp="$capture/.rendered-with"
render_args=(render --plan "$sample_dir/office.dxf" --path "$sample_dir/office_path.json" --size 1024x512 --depth
             --out "$capture")

"$cli" --version
if [[ ! -f "$project" || ! -f "$sample_dir/office.dxf" || ! -f "$sample_dir/office_path.json" ]]; then
  echo "Writing the office sample (plan, path, project)…"
  "$cli" make-sample --out "$sample_dir"
fi

# The capture is up to date when it was rendered by this version with these arguments after the inputs
# last changed.
wanted="$("$cli" --version) ${render_args[*]}"
if [[ -f "$stamp" && "$(cat "$stamp")" == "$wanted" && -f "$capture/groundtruth.json" &&
      "$stamp" -nt "$sample_dir/office.dxf" && "$stamp" -nt "$sample_dir/office_path.json" ]]; then
  echo "Sample capture up to date: $capture"
else
  echo "Rendering the sample capture once (300 panoramas of 1024x512 with depth)…"
  rm -rf "$capture"
  "$cli" "${render_args[@]}"
  echo "$wanted" > "$stamp"
fi

if [[ -n "${DISPLAY:-}" && -x "$studio" ]] && command -v xdpyinfo >/dev/null && xdpyinfo >/dev/null 2>&1; then
  echo "Opening the studio on $project…"
  exec "$studio" "$project"
fi
echo
"$cli" info "$project"
echo
"$cli" capture-info "$capture/frames" --depth "$capture/depth" || true

# The pipeline on the sample, headless: recover the path from the panoramas alone, score it against the
# renderer's ground truth, and cut the walk into visibility cells.
out="$build_dir/sample-run"
mkdir -p "$out"
echo
echo "Tracking the camera path from the panoramas alone…"
if "$cli" track --capture "$capture/frames" --camera-height 1.6 --out "$out/tracked_path.json" --quiet; then
  "$cli" eval-path --estimate "$out/tracked_path.json" --truth "$capture/groundtruth.json"
fi
echo
echo "Visibility events and cells along the walk:"
"$cli" visibility --plan "$sample_dir/office.dxf" --path "$sample_dir/office_path.json" | head -n 3 || true
echo
echo "Keyframes at 30x fewer images, uniform against visibility-driven (what each loses):"
for method in uniform visibility; do
  "$cli" sample --project "$project" --method "$method" --ratio 30 --photometric-frames 0 | head -n 3 || true
done
echo
echo "No display: this was the headless run. On a desktop, \`make run\` opens the studio on $project."
