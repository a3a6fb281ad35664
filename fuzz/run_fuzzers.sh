#!/usr/bin/env bash
# Runs every fuzz target (or those named) of a PAPERNET_FUZZ build for SECONDS each, FUZZ_JOBS
# (default: one per core) at a time, from fresh seeds (make_corpus.sh) plus the corpus earlier
# runs kept in BUILD/fuzz-corpus/<target>. Prints executions and corpus size per target; exits 1
# when a target found a crash, leaving the input in BUILD/fuzz-artifacts/ (make it a tests/ case).
#   fuzz/run_fuzzers.sh BUILD SECONDS [TARGET...]
# FUZZ_FLAGS adds libFuzzer flags: FUZZ_FLAGS=-max_len=4096 mutates small inputs only, which
# runs the slow targets (whole glTF and Draco models, 5-40 executions a second under ASan with
# the collection's seeds) hundreds of times faster.
set -euo pipefail
root="$(cd "$(dirname "$0")/.." && pwd)"
build="${1:?usage: $0 BUILD SECONDS [TARGET...]}"
seconds="${2:?usage: $0 BUILD SECONDS [TARGET...]}"
shift 2
targets=("$@")
[ ${#targets[@]} -gt 0 ] ||
  targets=(glb gltf gltf_external draco obj off ply stl image options upload)

seeds="$build/fuzz-corpus/seeds"
"$root/fuzz/make_corpus.sh" "$seeds"
mkdir -p "$build/fuzz-artifacts" "$build/fuzz-logs"
# The malloc limit catches a loader that trusts a declared count: the service's limits allow
# nothing near 1 GiB for inputs of this size.
export ASAN_OPTIONS="${ASAN_OPTIONS:-detect_leaks=1:allocator_may_return_null=0}"
export UBSAN_OPTIONS="${UBSAN_OPTIONS:-print_stacktrace=1:halt_on_error=1}"
# One target per core at a time (FUZZ_JOBS, default nproc): each is single-threaded, and CI's
# smoke run of eleven targets took 11 x 20 s one after the other.
jobs="${FUZZ_JOBS:-$(nproc)}"
run_target() {
  local t="$1" corpus="$build/fuzz-corpus/$1" log="$build/fuzz-logs/$1.log"
  mkdir -p "$corpus"
  local status=ok
  if ! "$build/fuzz/fuzz_$t" -max_total_time="$seconds" -timeout=30 -rss_limit_mb=2560 \
    -malloc_limit_mb=1024 -print_final_stats=1 ${FUZZ_FLAGS:-} -artifact_prefix="$build/fuzz-artifacts/$t-" \
    "$corpus" "$seeds/$t" >"$log" 2>&1; then
    status=CRASH
  fi
  echo "$status" >"$build/fuzz-logs/$t.status"
}
running=0
for t in "${targets[@]}"; do
  rm -f "$build/fuzz-logs/$t.status"
  if [ "$running" -ge "$jobs" ]; then
    wait -n || true
    running=$((running - 1))
  fi
  run_target "$t" &
  running=$((running + 1))
done
wait
failed=()
printf '%-14s %10s %8s %8s %6s\n' target executions exec/s corpus result
for t in "${targets[@]}"; do
  log="$build/fuzz-logs/$t.log"
  corpus="$build/fuzz-corpus/$t"
  status=$(cat "$build/fuzz-logs/$t.status" 2>/dev/null || echo CRASH)
  [ "$status" = ok ] || failed+=("$t")
  runs=$(sed -n 's/^stat::number_of_executed_units: *//p' "$log" | tail -1)
  speed=$(sed -n 's/^stat::average_exec_per_sec: *//p' "$log" | tail -1)
  printf '%-14s %10s %8s %8s %6s\n' "$t" "${runs:-?}" "${speed:-?}" "$(ls "$corpus" | wc -l)" \
    "$status"
done
if [ ${#failed[@]} -gt 0 ]; then
  for t in "${failed[@]}"; do
    echo "--- fuzz_$t found a crash ($build/fuzz-logs/$t.log):"
    grep -m1 -A30 -E '^==[0-9]+==|runtime error|deadly signal|timeout|out-of-memory' \
      "$build/fuzz-logs/$t.log" || tail -40 "$build/fuzz-logs/$t.log"
  done
  exit 1
fi
