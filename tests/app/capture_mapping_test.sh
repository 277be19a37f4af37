#!/usr/bin/env bash
# The Capture alone maps a frame's index to its source position and time (issue 17, ARCHITECTURE.md):
# Capture::frame_index_of_kept / kept_of_frame_index / frame_time_s / time_at_index_s in model/capture.cpp.
# Fails naming file:line wherever app/, widgets/, processing/ or model/ redo that arithmetic
# (first_frame + k * stride, index - first_frame, ... / max(1, stride), walking by += stride) outside the
# whitelist below. Usage: capture_mapping_test.sh CLI DATA SOURCE_DIR
set -uo pipefail
src=${3:?source dir}
cd "$src" || exit 2

# What looks like the mapping: an offset by first_frame, a product or a walk by stride, a division by it.
pattern='first_frame[[:space:]]*\+|-[[:space:]]*([A-Za-z_]+(\.|->))*first_frame\b|\*[[:space:]]*([A-Za-z_()]+(\.|->))*stride\b|/[[:space:]]*std::max\(1,[^)]*stride\)|\+=[[:space:]]*([A-Za-z_]+(\.|->))+stride\b'

# FILE-REGEX ## LINE-REGEX ## reason. Matched by content, not by line number, so edits around them do not matter.
whitelist=(
  'model/capture\.cpp ## . ## the one place the mapping lives'
  'model/capture\.h ## ^[[:space:]]*// ## comments describing the mapping'
  'processing/capture/frame_source_folder\.cpp ## for \(int p = options\.first_frame; p <= last; p \+= options\.stride\) ## choosing the files of a folder from the raw sorted list, before any Capture exists'
  'processing/capture/frame_source_video\.cpp ## for \(long long raw = options\.first_frame; raw <= last; raw \+= options\.stride\) ## walking the raw video to index the frames it keeps, before any Capture exists'
  'processing/capture/multi_head_capture\.cpp ## for \(int i = options\.first_frame; i <= last; i \+= options\.stride\) ## choosing the matched frames of a rig from the raw list, before any Capture exists'
  'processing/egomotion/klt_tracks\.(h|cpp) ## s\.first_frame ## a KLT track'"'"'s own first frame, not a capture'"'"'s'
  'processing/sampling/depth_section\.cpp ## u \* stride ## a pixel stride across a depth image, not frames'
)

fail=0
while IFS= read -r hit; do
  file=${hit%%:*}; rest=${hit#*:}; line=${rest%%:*}; text=${rest#*:}
  allowed=0
  for w in "${whitelist[@]}"; do
    wfile=${w%% ## *}; wrest=${w#* ## }; wre=${wrest%% ## *}
    if [[ $file =~ ^${wfile}$ ]] && [[ $text =~ $wre ]]; then allowed=1; break; fi
  done
  if [[ $allowed -eq 0 ]]; then
    echo "capture_mapping: $file:$line re-derives the Capture's frame mapping (use Capture::frame_index_of_kept / kept_of_frame_index / frame_time_s): $text" >&2
    fail=1
  fi
done < <(grep -rnE "$pattern" app widgets processing model --include='*.cpp' --include='*.h')

# The whitelist's own entries must still match something (a stale entry would hide nothing and mislead).
all_hits=$(grep -rnE "$pattern" app widgets processing model --include='*.cpp' --include='*.h')
for w in "${whitelist[@]}"; do
  wfile=${w%% ## *}; wrest=${w#* ## }; wre=${wrest%% ## *}
  found=0
  while IFS= read -r hit; do
    file=${hit%%:*}; rest=${hit#*:}; text=${rest#*:}
    if [[ $file =~ ^${wfile}$ ]] && [[ $text =~ $wre ]]; then found=1; break; fi
  done <<< "$all_hits"
  [[ $found -eq 1 ]] || { echo "capture_mapping: whitelist entry matches nothing: $w" >&2; fail=1; }
done

[[ $fail -eq 0 ]] && echo "capture_mapping: ok (the Capture alone maps frame index <-> source position <-> time)"
exit $fail
