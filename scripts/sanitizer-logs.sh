#!/usr/bin/env bash
# Fails (and prints them) when a sanitizer wrote reports into DIR: `make sanitize` points every
# process's log_path there, the papernet processes the tests start included.
#   scripts/sanitizer-logs.sh DIR
set -euo pipefail
dir="${1:?usage: $0 DIR}"
shopt -s nullglob
reports=("$dir"/*)
[ ${#reports[@]} -eq 0 ] && exit 0
for r in "${reports[@]}"; do
  echo "=== sanitizer report $r"
  cat "$r"
done
echo "error: ${#reports[@]} sanitizer report(s) in $dir" >&2
exit 1
