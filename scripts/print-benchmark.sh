#!/usr/bin/env bash
# Regenerates the table of docs/print.md, "Against Blender's exporter" (make print-benchmark):
# every mesh of ../shared/data/bench at 400 and 1,000 faces, printed at 200 mm on A4 with
# detail=full, by papernet (bench/print_main.cpp) and by Blender's bundled "Export Paper Model"
# add-on run headless with "limit island size" on (blender_print_peer.py, from
# ../shared/tools). Installs Blender (Debian's `blender`) when it is missing.
#
# About 5 minutes on the 2-core reference machine, idle (4 min 53 s on 2026-11-26).
#
# Environment (all optional):
#   DATA=../shared/data  BUILD=build  RES=400,1000  SIZE_MM=200
#   MARGIN_MM=10  page margins of both tools (papernet's default; Blender's own is 5 mm)
#   PEER=../shared/tools/blender_print_peer.py
#   FROM_TSV=file.tsv  an earlier Blender run's TSV instead of running Blender again
set -euo pipefail
cd "$(dirname "$0")/.."

DATA=${DATA:-../shared/data}
BUILD=${BUILD:-build}
RES=${RES:-400,1000}
SIZE_MM=${SIZE_MM:-200}
MARGIN_MM=${MARGIN_MM:-10}
PEER=${PEER:-../shared/tools/blender_print_peer.py}
OUT=$BUILD/print-bench
DOC=docs/print.md
BEGIN='<!-- print-benchmark: begin (scripts/print-benchmark.sh writes what follows) -->'
END='<!-- print-benchmark: end -->'

[ -d "$DATA/bench" ] || { echo "error: no $DATA/bench (the benchmark meshes)" >&2; exit 1; }
grep -qF "$BEGIN" "$DOC" || { echo "error: $DOC has no line '$BEGIN'" >&2; exit 1; }
mkdir -p "$OUT"
cmake -S . -B "$BUILD" -DCMAKE_BUILD_TYPE=Release >/dev/null
cmake --build "$BUILD" -j "$(nproc)" --target papernet-print-bench >/dev/null

tsv=${FROM_TSV:-$OUT/blender.tsv}
if [ -z "${FROM_TSV:-}" ]; then
  [ -f "$PEER" ] || { echo "error: no $PEER (the Blender peer script)" >&2; exit 1; }
  bash scripts/install-deps.sh blender
  echo "Blender's exporter on $DATA/bench ($RES faces, $SIZE_MM mm, A4, $MARGIN_MM mm margins): $OUT/blender.log"
  PEER_MARGIN_M=$(awk -v mm="$MARGIN_MM" 'BEGIN { print mm / 1000 }') \
    blender -b --factory-startup --python "$PEER" -- "$DATA/bench" "$tsv" "$RES" "$SIZE_MM" \
    >"$OUT/blender.log" 2>&1
fi
echo "papernet on the same meshes: $OUT/table.md"
"$BUILD/bin/papernet-print-bench" --bench "$DATA/bench" --res "$RES" --size-mm "$SIZE_MM" \
  --detail full --margin-mm "$MARGIN_MM" --blender "$tsv" | tee "$OUT/table.md"

{
  sed -n "1,/^$(printf '%s' "$BEGIN" | sed 's/[][\/.*^$]/\\&/g')\$/p" "$DOC"
  echo
  echo "Commit $(git rev-parse --short HEAD), $(date -u +%Y-%m-%d); Blender $(blender --version 2>/dev/null | head -1 | sed 's/^Blender //')."
  echo
  cat "$OUT/table.md"
  sed -n "/^$(printf '%s' "$END" | sed 's/[][\/.*^$]/\\&/g')\$/,\$p" "$DOC"
} >"$OUT/print.md"
mv "$OUT/print.md" "$DOC"
echo "wrote $DOC"
