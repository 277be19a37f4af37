#!/usr/bin/env bash
# The long libFuzzer runs (`make fuzz`): BUILD_DIR [SECONDS per target, default 600] [TARGET ...].
# Each target's new inputs go to BUILD_DIR/fuzz-corpus/<target> (the seeds in tests/data are never written
# to); crashes are saved under BUILD_DIR/fuzz-artifacts/<target>-. A summary line per target (executions,
# seconds, crashes) goes to BUILD_DIR/fuzz-summary.txt.
set -uo pipefail
build=${1:?usage: run-long.sh BUILD_DIR [SECONDS] [TARGET ...]}
seconds=${2:-600}
shift $(( $# >= 2 ? 2 : 1 ))
here=$(cd "$(dirname "$0")" && pwd)
data="$here/../data"
declare -A seeds=([dxf_import]="$data/dxf $data/dxf-ezdxf" [gps_track]="$data/fuzz/gps" [image_header]="$data/fuzz/image"
                  [project]="$data/fuzz/project $data/projects" [path]="$data/fuzz/path" [path_points]="$data/fuzz/points" [anchors]="$data/fuzz/anchors"
                  [rig]="$data/fuzz/rig" [tour_json]="$data/fuzz/tour" [spherical_video]="$data/fuzz/spherical")
declare -A dicts=([dxf_import]=dxf [gps_track]=gps [image_header]=image [project]=json [path]=json [path_points]=json [anchors]=json [rig]=json [tour_json]=json [spherical_video]=mp4)
targets=("$@")
[[ ${#targets[@]} -gt 0 ]] || targets=(dxf_import gps_track image_header project path path_points anchors rig tour_json spherical_video)
summary="$build/fuzz-summary.txt"
status=0
for t in "${targets[@]}"; do
  exe="$build/tests/fuzz/fuzz_$t"
  [[ -x "$exe" ]] || { echo "run-long.sh: $exe not built (configure with -DPLENOPATH_BUILD_FUZZ=ON and clang)"; exit 1; }
  corpus="$build/fuzz-corpus/$t"
  mkdir -p "$corpus" "$build/fuzz-artifacts"
  log="$build/fuzz-$t.log"
  # shellcheck disable=SC2086
  "$exe" "$corpus" ${seeds[$t]} -dict="$here/dict/${dicts[$t]}.dict" -max_total_time="$seconds" -max_len=65536 \
    -timeout=10 -rss_limit_mb=2048 -artifact_prefix="$build/fuzz-artifacts/$t-" -print_final_stats=1 > "$log" 2>&1
  rc=$?
  runs=$(grep -o 'stat::number_of_executed_units: *[0-9]*' "$log" | grep -o '[0-9]*$')
  crashes=$(ls "$build/fuzz-artifacts/" 2> /dev/null | grep -c "^$t-" || true)
  line="$t: exit $rc, ${runs:-?} executions in $seconds s, $crashes artifacts"
  echo "$line" | tee -a "$summary"
  [[ $rc -eq 0 ]] || status=1
done
exit $status
