#!/usr/bin/env bash
# The long libFuzzer run of the DXF importer (`make fuzz`): BUILD_DIR [SECONDS, default 600].
# New inputs go to BUILD_DIR/fuzz-corpus/dxf (the seeds in tests/data/dxf are never written to);
# crashes are saved under BUILD_DIR/fuzz-artifacts/.
set -euo pipefail
build=${1:?usage: run-long.sh BUILD_DIR [SECONDS]}
seconds=${2:-600}
here=$(cd "$(dirname "$0")" && pwd)
exe="$build/tests/fuzz/fuzz_dxf_import"
[[ -x "$exe" ]] || { echo "run-long.sh: $exe not built (configure with -DPLENOPATH_BUILD_FUZZ=ON and clang)"; exit 1; }
corpus="$build/fuzz-corpus/dxf"
artifacts="$build/fuzz-artifacts/"
mkdir -p "$corpus" "$artifacts"
"$exe" "$corpus" "$here/../data/dxf" "$here/../data/dxf-ezdxf" -max_total_time="$seconds" -max_len=65536 -timeout=10 -rss_limit_mb=2048 \
  -artifact_prefix="$artifacts" -print_final_stats=1
