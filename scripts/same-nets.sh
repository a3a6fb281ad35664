#!/usr/bin/env bash
# Proves that a change kept papernet's nets: records what `papernet unfold` writes for a set of
# meshes (the net JSON without its `seconds`, the SVG and PDF page counts, the exit code and the
# summary line without timings), and compares two such records.
#
#   scripts/same-nets.sh record PAPERNET DIR   run every mesh with every strategy, seed 1
#   scripts/same-nets.sh compare DIR_A DIR_B   exit 0 when the records are identical
#
# The meshes: every file in tests/data, and ../shared/data/bench at 400 and 2,000 faces (when
# present; set SHARED_DATA to another folder, or BENCH_SIZES="" to leave it out).
set -euo pipefail
cd "$(dirname "$0")/.."

STRATEGIES=${STRATEGIES:-"QQ SEMP SEQ TU"}
SHARED_DATA=${SHARED_DATA:-../shared/data}
BENCH_SIZES=${BENCH_SIZES-"400 2000"}
JOBS=${JOBS:-$(nproc)}
# Long enough that no run of these meshes ends by the clock: a net cut short by time is not
# reproducible, so it proves nothing.
TIME_LIMIT=${TIME_LIMIT:-600}
export TIME_LIMIT

meshes() {
  find tests/data -maxdepth 2 -type f \( -name '*.obj' -o -name '*.stl' -o -name '*.ply' \
    -o -name '*.glb' -o -name '*.gltf' -o -name '*.off' -o -name '*.drc' \) | sort
  for n in $BENCH_SIZES; do
    if [ -d "$SHARED_DATA/bench/$n" ]; then
      find "$SHARED_DATA/bench/$n" -name '*.obj' | sort
    else
      echo "same-nets: $SHARED_DATA/bench/$n is absent; those meshes are not compared" >&2
    fi
  done
}

# One run: papernet unfold MESH --strategy S --seed 1 with JSON, SVG and PDF outputs.
record_one() {
  local bin=$1 dir=$2 mesh=$3 strategy=$4
  local name
  name=$(echo "$mesh" | sed 's|^\.\./shared/data/||; s|/|_|g')__$strategy
  local work="$dir/work/$name"
  mkdir -p "$work"
  local code=0
  "$bin" unfold "$mesh" --strategy "$strategy" --seed 1 --time-limit "$TIME_LIMIT" \
    -o "$work/net.json" \
    -o "$work/net.svg" -o "$work/net.pdf" >"$work/stdout" 2>"$work/stderr" || code=$?
  {
    echo "exit=$code"
    # The summary line without what depends on the clock.
    sed -E 's/ seconds=[^ ]+//' "$work/stdout"
    if [ -f "$work/net.pdf" ]; then
      echo "pdf_pages=$(pdfinfo "$work/net.pdf" | awk '/^Pages:/ {print $2}')"
    fi
    echo "svg_pages=$(find "$work" -name 'net*.svg' | wc -l)"
  } >"$dir/$name.txt"
  # Timings, not compared: where the time went.
  grep -oE 'seconds=[^ ]+' "$work/stdout" | head -1 | sed "s|^|$name |" >>"$dir/seconds.log" || true
  if [ -f "$work/net.json" ]; then
    sed -E 's/"seconds":[-0-9.eE+]+/"seconds":0/' "$work/net.json" >"$dir/$name.json"
  fi
  rm -rf "$work"
}
export -f record_one

case "${1:-}" in
  record)
    [ $# -eq 3 ] || { echo "usage: $0 record PAPERNET DIR" >&2; exit 2; }
    bin=$(realpath "$2")
    dir=$3
    rm -rf "$dir" && mkdir -p "$dir"
    start=$(date +%s)
    for mesh in $(meshes); do
      for s in $STRATEGIES; do echo "$mesh $s"; done
    done | xargs -P "$JOBS" -n 2 bash -c 'record_one "$0" "$1" "$2" "$3"' "$bin" "$dir"
    rmdir "$dir/work" 2>/dev/null || true
    echo "same-nets: recorded $(find "$dir" -name '*.txt' | wc -l) runs in $dir" \
      "($(($(date +%s) - start)) s)"
    ;;
  compare)
    [ $# -eq 3 ] || { echo "usage: $0 compare DIR_A DIR_B" >&2; exit 2; }
    runs=$(find "$2" -name '*.txt' | wc -l)
    nets=$(find "$2" -name '*.json' | wc -l)
    if diff -r -q -x seconds.log "$2" "$3"; then
      echo "same-nets: identical: $runs runs, $nets net JSON documents, page counts and exit codes"
    else
      echo "same-nets: DIFFERENT (files listed above)" >&2
      exit 1
    fi
    ;;
  *)
    echo "usage: $0 record PAPERNET DIR | compare DIR_A DIR_B" >&2
    exit 2
    ;;
esac
