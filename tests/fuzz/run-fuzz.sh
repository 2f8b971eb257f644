#!/usr/bin/env bash
# Builds and runs the libFuzzer targets (tests/fuzz/CMakeLists.txt, a clang tree of its own).
#   run-fuzz.sh build BUILD_DIR            configure + build the targets into BUILD_DIR
#   run-fuzz.sh run BUILD_DIR TARGET SECS  replay TARGET's regression inputs, then fuzz for SECS
#                                          seconds from its seed corpus; print libFuzzer's stats
# New corpus entries go to a temporary directory, not into the source tree; a crash's input is
# kept in BUILD_DIR/crashes/TARGET/ to be added to tests/fuzz/regressions/TARGET/ once fixed.
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)
mode=${1:?build|run}; build=${2:?build directory}

case "$mode" in
  build)
    launcher=()
    if command -v ccache >/dev/null; then launcher=(-DCMAKE_CXX_COMPILER_LAUNCHER=ccache); fi
    cmake -S "$here" -B "$build" -G Ninja -DCMAKE_CXX_COMPILER=clang++ -DCMAKE_BUILD_TYPE=None "${launcher[@]}" > "$build.configure.log" 2>&1 ||
      { cat "$build.configure.log"; exit 1; }
    nice -n 10 cmake --build "$build"
    ;;
  run)
    target=${3:?target}; secs=${4:?seconds}
    bin=$build/strata_fuzz_$target
    [ -x "$bin" ] || { echo "run-fuzz: $bin is not built (run-fuzz.sh build $build)" >&2; exit 1; }
    export ASAN_OPTIONS=${ASAN_OPTIONS:-detect_leaks=1:abort_on_error=1}
    export UBSAN_OPTIONS=${UBSAN_OPTIONS:-print_stacktrace=1:halt_on_error=1}
    regressions=$here/regressions/$target
    if compgen -G "$regressions/*" > /dev/null; then
      echo "run-fuzz: $target: replaying $(ls "$regressions" | wc -l) regression input(s)"
      "$bin" -runs=1 "$regressions"/* 2>&1 | tail -n 3
    fi
    work=$(mktemp -d /tmp/strata-fuzz-$target.XXXXXX)
    trap 'rm -rf "$work"' EXIT
    mkdir -p "$build/crashes/$target"
    dict=()
    if [ -f "$here/dict/$target.dict" ]; then dict=(-dict="$here/dict/$target.dict"); fi
    # -timeout: one input taking seconds is a finding too (a client could stall a daemon's thread).
    "$bin" -max_total_time="$secs" -timeout=10 -rss_limit_mb=2048 -malloc_limit_mb=512 -max_len=65536 -print_final_stats=1 \
      -artifact_prefix="$build/crashes/$target/" "${dict[@]}" "$work" "$here/corpus/$target" > "$work/log" 2>&1 || {
      tail -n 60 "$work/log"; echo "run-fuzz: $target: FAILED; the input is in $build/crashes/$target/" >&2; exit 1; }
    grep -E "^stat::(number_of_executed_units|average_exec_per_sec|new_units_added|peak_rss_mb)" "$work/log" | tee "$build/stats-$target.txt"
    echo "run-fuzz: $target: no crash in ${secs}s"
    ;;
  *) echo "run-fuzz: unknown mode $mode" >&2; exit 2 ;;
esac
