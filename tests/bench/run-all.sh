#!/usr/bin/env bash
# Runs every benchmark executable and prints their JSON figures as one JSON array (also saved to
# BUILD_DIR/bench.json). Benchmarks, never timed unit tests, check speed and accuracy targets.
set -euo pipefail
build_dir=${1:-build}
out="$build_dir/bench.json"
benches=$(find "$build_dir/tests/bench" -maxdepth 1 -type f -name 'bench_*' -perm -u+x | sort)
if [[ -z "$benches" ]]; then echo "[]" | tee "$out"; exit 0; fi
{
  echo "["
  first=1
  for b in $benches; do
    echo "bench: running $(basename "$b")" >&2
    result=$("$b")
    [[ $first -eq 1 ]] || echo ","
    first=0
    echo "$result"
  done
  echo "]"
} > "$out"
cat "$out"
