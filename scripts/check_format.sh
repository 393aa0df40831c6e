#!/usr/bin/env bash
# Check that every C++ file is formatted by clang-format 14 with the
# project's .clang-format (installs clang-format-14 from Debian if missing).
#   bash scripts/check_format.sh         report and fail on any difference
#   bash scripts/check_format.sh --fix   format the files in place
set -euo pipefail
cd "$(dirname "$0")/.."
if ! command -v clang-format-14 >/dev/null; then
  echo "Installing: clang-format-14"
  apt-get update -qq
  DEBIAN_FRONTEND=noninteractive apt-get install -y -qq clang-format-14 >/dev/null
fi
mapfile -t files < <(git ls-files '*.h' '*.cc')
if [ "${1:-}" = "--fix" ]; then
  clang-format-14 -i "${files[@]}"
  exit 0
fi
if ! clang-format-14 --dry-run --Werror "${files[@]}" 2>/tmp/format-check.$$; then
  grep "error:" /tmp/format-check.$$ | sed 's/:[0-9]*: error:.*//' | sort -u \
    | sed 's/^/not formatted: /' >&2
  rm -f /tmp/format-check.$$
  echo "Run: bash scripts/check_format.sh --fix" >&2
  exit 1
fi
rm -f /tmp/format-check.$$
echo "format: ${#files[@]} files formatted as .clang-format asks"
