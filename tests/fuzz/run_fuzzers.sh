#!/bin/sh
# `make fuzz`: every fuzz target for SECONDS, JOBS at a time; usage: run_fuzzers.sh BUILD SECONDS JOBS.
# Each target starts from its committed corpus (tests/fuzz/corpus/<target>), its regressions and,
# for `scene`, every scene in configs/scenes/; the scene target gets a dictionary of the strings
# those scenes use. What it finds new is kept in BUILD/fuzz/<target>/corpus (not committed), and an
# input that crashed in BUILD/fuzz/<target>/artifacts. Prints executions per second and corpus
# size per target; fails when any target left an artifact.
set -eu
build=$1 seconds=$2 jobs=$3
here=$(cd "$(dirname "$0")" && pwd)
root=$(cd "$here/../.." && pwd)
targets=${FUZZ_TARGETS:-"scene ply obj exr hdr"}  # FUZZ_TARGETS: a subset
symbolizer=/usr/lib/llvm-14/bin/llvm-symbolizer
export ASAN_OPTIONS="detect_leaks=1:external_symbolizer_path=$symbolizer"
export LSAN_OPTIONS="suppressions=$here/lsan.supp"
export UBSAN_OPTIONS="print_stacktrace=1:halt_on_error=1:external_symbolizer_path=$symbolizer"

# The scenes as seeds (libFuzzer reads directories recursively: copies, without generators/).
scenes="$build/fuzz/scene_seeds"
rm -rf "$scenes"
mkdir -p "$scenes"
cp "$root"/configs/scenes/*.json "$scenes/"
dictionary="$build/fuzz/scene.dict"
grep -ohE '"[A-Za-z0-9_./-]+"' "$scenes"/*.json |
  sort -u | sed 's/\\/\\\\/g; s/"/\\"/g; s/^/"/; s/$/"/' > "$dictionary"

run_target() {
  t=$1
  work="$build/fuzz/$t"
  rm -rf "$work/artifacts"
  mkdir -p "$work/corpus" "$work/artifacts"
  set -- "$work/corpus" "$here/corpus/$t"
  [ -d "$here/regressions/$t" ] && set -- "$@" "$here/regressions/$t"
  extra=""
  if [ "$t" = scene ]; then
    set -- "$@" "$scenes"
    extra="-dict=$dictionary"
  fi
  # -timeout: a 1x1 render of any valid scene takes far less; a slower input is a finding.
  # -rss_limit_mb: the loader must reject what would need more memory than this.
  "$build/bin/fuzz_$t" -max_total_time="$seconds" -timeout=60 -rss_limit_mb=4096 \
    -print_final_stats=1 -artifact_prefix="$work/artifacts/" $extra "$@" \
    > "$work/log" 2>&1 || true
}

pids=""
running=0
for t in $targets; do
  run_target "$t" &
  pids="$pids $!"
  running=$((running + 1))
  if [ "$running" -ge "$jobs" ]; then wait; running=0; fi
done
wait

status=0
printf '%-6s %12s %10s %8s %s\n' target executions exec/s corpus findings
for t in $targets; do
  work="$build/fuzz/$t"
  runs=$(sed -n 's/^stat::number_of_executed_units: *//p' "$work/log" | tail -1)
  rate=$(sed -n 's/^stat::average_exec_per_sec: *//p' "$work/log" | tail -1)
  corpus=$(find "$work/corpus" -type f | wc -l)
  findings=$(find "$work/artifacts" -type f | wc -l)
  printf '%-6s %12s %10s %8s %s\n' "$t" "${runs:-?}" "${rate:-?}" "$corpus" "$findings"
  if [ "$findings" -gt 0 ] || [ -z "$runs" ]; then
    status=1
    echo "  $t: see $work/log and $work/artifacts/" >&2
  fi
done
exit $status
