#!/usr/bin/env bash
# Regenerates docs/inputs.md: what `papernet unfold` makes of every model of the test collection
# in ../shared/data/meshes (gltf/, draco/, classic/, thingi-like/, bad/): a net (its pieces and
# repairs), a refusal (its reason) or a failure (a crash, a timeout, no net).
#   scripts/inputs.sh                 builds papernet and papernet-inputs (Release) and runs them
#   MESHES=dir BUILD=build JOBS=2 TIME_LIMIT=60 PAPERNET=other/papernet scripts/inputs.sh
# About 15 minutes on 2 idle cores. Exits 3 when a file failed.
set -euo pipefail
cd "$(dirname "$0")/.."
MESHES=${MESHES:-../shared/data/meshes}
BUILD=${BUILD:-build}
JOBS=${JOBS:-$(nproc)}
TIME_LIMIT=${TIME_LIMIT:-60}
OUT=${OUT:-docs/inputs.md}
if [ ! -d "$MESHES" ]; then
  echo "error: no test collection at $MESHES (set MESHES=...; see ../shared/data/README)" >&2
  exit 1
fi
cmake -S . -B "$BUILD" -DCMAKE_BUILD_TYPE=Release >/dev/null
cmake --build "$BUILD" -j "$JOBS" --target papernet papernet-inputs
papernet=${PAPERNET:-$BUILD/bin/papernet}
commit=$(git rev-parse --short HEAD 2>/dev/null || echo unknown)
if ! git diff --quiet HEAD 2>/dev/null; then commit="$commit + local changes"; fi
table=$(mktemp)
status=0
"$BUILD/bin/papernet-inputs" "$MESHES" --papernet "$papernet" --time-limit "$TIME_LIMIT" \
  --jobs "$JOBS" --command scripts/inputs.sh --markdown "$table" >/dev/null || status=$?
{
  echo "# Inputs: what papernet makes of real models"
  echo
  echo "Every model file of the test collection (\`../shared/data/meshes\`: third-party glTF, Draco,"
  echo "classic scans, Thingi10K-like parts, and a folder of *bad* inputs) through"
  echo "\`papernet unfold FILE -o net.json --time-limit $TIME_LIMIT --tab-room-budget 0\` with every"
  echo "other option at its default: repair on, every part its own piece. *net*: a net was written"
  echo "(it passed the net checker: the command checks every piece before it writes); *refused*:"
  echo "exit 2 with the reason; *failed*: a crash, a timeout or no net (exit 1)."
  echo "Repairs, and the result's warnings (\`warning CODE COUNT\`), are listed by code and count (core/mesh/repair.h; \`skipped_on_load\`: what the"
  echo "loader left out, such as point or line primitives)."
  echo
  echo "Made by \`scripts/inputs.sh\` from commit $commit on $(date -u +%Y-%m-%d)."
  echo
  cat "$table"
} >"$OUT"
rm -f "$table"
echo "scripts/inputs.sh: wrote $OUT" >&2
exit $status
