#!/usr/bin/env bash
# Fails (exit 1) when a C++ file of the project differs from .clang-format, naming each such file.
# `make format` fixes them. Used by .ci/run before the tests.
set -euo pipefail
cd "$(dirname "$0")/.."
command -v clang-format >/dev/null || { echo "check-format: clang-format is not installed" >&2; exit 1; }
bad=()
while IFS= read -r -d '' f; do
  clang-format --dry-run -Werror "$f" >/dev/null 2>&1 || bad+=("$f")
done < <(git ls-files -z -- 'app/*.cpp' 'app/*.h' 'widgets/*.cpp' 'widgets/*.h' 'model/*.cpp' 'model/*.h' \
           'processing/*.cpp' 'processing/*.h' 'rig/*.cpp' 'rig/*.h' 'tests/*.cpp' 'tests/*.h')
if [[ ${#bad[@]} -gt 0 ]]; then
  echo "check-format: ${#bad[@]} file(s) differ from .clang-format (run 'make format'):" >&2
  printf '  %s\n' "${bad[@]}" >&2
  exit 1
fi
echo "check-format: every C++ file follows .clang-format"
