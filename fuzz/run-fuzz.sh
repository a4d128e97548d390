#!/usr/bin/env bash
# Runs every fuzz target of a fuzz build (make fuzz) for SECONDS each: seeds gathered afresh by
# fuzz/seed-corpus.sh, a fresh work corpus per target, the target's dictionary, and limits on
# time per input, memory and total time. Prints executions and exec/s per target and fails when
# any target found a crash, leak, UB, timeout or OOM; the input that did it is in
# BUILD_DIR/fuzz-findings/<target>/ (minimize it with -minimize_crash=1 and save it under
# tests/regression/<target>/).
#
# Usage: fuzz/run-fuzz.sh BUILD_DIR SECONDS [TARGET...]   (default: every target)
# Environment: FUZZ_TIMEOUT (s per input, 10), FUZZ_RSS_MB (2048), FUZZ_JOBS (targets run at
# once, 1), FUZZ_FLAGS (more libFuzzer flags, e.g. "-seed=1" for a reproducible smoke).
set -euo pipefail

build_dir=$(cd "${1:?usage: fuzz/run-fuzz.sh BUILD_DIR SECONDS [TARGET...]}" && pwd)
seconds=${2:?usage: fuzz/run-fuzz.sh BUILD_DIR SECONDS [TARGET...]}
shift 2
repo=$(cd "$(dirname "$0")/.." && pwd)
timeout_per_input=${FUZZ_TIMEOUT:-10}
rss_limit_mb=${FUZZ_RSS_MB:-2048}
read -r -a extra_flags <<<"${FUZZ_FLAGS:-}"

targets=("$@")
if [ ${#targets[@]} -eq 0 ]; then
  mapfile -t targets <"$build_dir/fuzz/targets.txt"
fi

dictionary_for() {
  case $1 in
    plan_text | llm_* | api_request | viewer_document) echo json ;;
    urdf | srdf | xacro | kautham_* | mesh_dae) echo xml ;;
    moveit_problem | joint_limits) echo yaml ;;
    *) echo "" ;;
  esac
}

# Leaks inside Debian's libraries (Coin's global field) are not findings; UB aborts.
export LSAN_OPTIONS="suppressions=$repo/tests/lsan.supp"
export UBSAN_OPTIONS="print_stacktrace=1:halt_on_error=1"

seeds="$build_dir/fuzz-seeds"
"$repo/fuzz/seed-corpus.sh" "$seeds"

# run_target TARGET: runs one target; its result line goes to $results/TARGET.
run_target() {
  local target=$1
  local binary="$build_dir/fuzz/fuzz_$target"
  local work="$build_dir/fuzz-work/$target"
  local findings="$build_dir/fuzz-findings/$target"
  local log="$build_dir/fuzz-logs/$target.log"
  rm -rf "$work" "$findings"
  mkdir -p "$work" "$findings" "$seeds/$target" "$(dirname "$log")"
  local flags=(-max_total_time="$seconds" -timeout="$timeout_per_input" -rss_limit_mb="$rss_limit_mb"
               -artifact_prefix="$findings/" -print_final_stats=1)
  local dictionary
  dictionary=$(dictionary_for "$target")
  [ -n "$dictionary" ] && flags+=(-dict="$repo/fuzz/dict/$dictionary.dict")
  echo "fuzz: $target for ${seconds} s ($(find "$seeds/$target" -type f | wc -l) seeds)"
  local status=0
  "$binary" "${flags[@]}" "${extra_flags[@]}" "$work" "$seeds/$target" >"$log" 2>&1 || status=$?
  local executions rate result=ok
  executions=$(sed -n 's/^stat::number_of_executed_units: *//p' "$log" | tail -n 1)
  rate=$(sed -n 's/^stat::average_exec_per_sec: *//p' "$log" | tail -n 1)
  if [ "$status" -ne 0 ]; then
    result="FAILED (exit $status)"
    { echo "fuzz: $target failed; the end of $log:"; grep -v '^#[0-9]' "$log" | tail -n 40; } >&2
  fi
  printf '%-18s %12s %10s  %s\n' "$target" "${executions:-?}" "${rate:-?}" "$result" >"$results/$target"
}

results="$build_dir/fuzz-results"
rm -rf "$results"
mkdir -p "$results"
jobs=${FUZZ_JOBS:-1}
for target in "${targets[@]}"; do
  while [ "$(jobs -rp | wc -l)" -ge "$jobs" ]; do wait -n || true; done
  run_target "$target" &
done
wait

failed=()
printf '\n%-18s %12s %10s  %s\n' target executions exec/s result
for target in "${targets[@]}"; do
  if [ ! -f "$results/$target" ]; then
    printf '%-18s %12s %10s  %s\n' "$target" "?" "?" "FAILED (no result)"
    failed+=("$target")
    continue
  fi
  cat "$results/$target"
  grep -q ' ok$' "$results/$target" || failed+=("$target")
done
echo "fuzz: $((${#targets[@]} - ${#failed[@]})) passed, ${#failed[@]} failed"
if [ ${#failed[@]} -ne 0 ]; then
  echo "fuzz: findings in ${failed[*]} (inputs in $build_dir/fuzz-findings/)" >&2
  exit 1
fi
