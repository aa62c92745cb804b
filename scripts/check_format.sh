#!/usr/bin/env bash
# Fails, listing the files, when a tracked C++ file is not formatted as .clang-format says.
# Apply the style with: git ls-files '*.cpp' '*.h' | xargs clang-format -i
set -euo pipefail
cd "$(dirname "$0")/.."
if ! command -v clang-format >/dev/null; then
  echo "check_format.sh: clang-format is not installed (Debian: clang-format)" >&2
  exit 1
fi
mapfile -t files < <(git ls-files '*.cpp' '*.h')
# clang-format runs on batches of files, one batch per core at a time (one run per file took 30 s
# of the CI job on 2 cores); each file that differs is named in a diagnostic of its own.
log=$(mktemp)
trap 'rm -f "$log"' EXIT
status=0
printf '%s\0' "${files[@]}" | xargs -0 -P "$(nproc)" -n 32 clang-format --dry-run --Werror >/dev/null 2>"$log" || status=$?
mapfile -t bad < <(grep -oE '^[^:]+:[0-9]+:[0-9]+: error: code should be clang-formatted' "$log" | cut -d: -f1 | sort -u)
if [ "$status" -ne 0 ] && [ "${#bad[@]}" -eq 0 ]; then
  cat "$log" >&2
  echo "check_format.sh: clang-format failed (exit status $status)" >&2
  exit 1
fi
if [ "${#bad[@]}" -gt 0 ]; then
  echo "check_format.sh: ${#bad[@]} file(s) differ from .clang-format (clang-format $(clang-format --version | grep -o '[0-9][0-9.]*' | head -1)):" >&2
  printf '  %s\n' "${bad[@]}" >&2
  exit 1
fi
echo "check_format.sh: ${#files[@]} files formatted"
