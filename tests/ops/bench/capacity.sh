#!/usr/bin/env bash
# Capacity of one stratad on this machine (docs/BENCHMARKS.md): for pt and restir-gather at 128x128
# and 256x256, one `strata loadtest` run per concurrency 1, 2, 4, 8 (closed loop: each session
# sends its next input when its frame arrives), SECONDS_PER_POINT seconds each, the first frames of
# every session left out (lavapipe compiles pipelines at the first dispatch). Prints a Markdown table.
#   tests/ops/bench/capacity.sh [BUILD_DIR] [OUT_DIR]
set -euo pipefail
BUILD=${1:-build/release}
OUT=${2:-out/bench/capacity}
SECONDS_PER_POINT=${SECONDS_PER_POINT:-10}
mkdir -p "$OUT"
"$BUILD/server/stratad" serve --listen 127.0.0.1:0 --port-file "$OUT/port" --max-sessions 8 >"$OUT/stratad.log" 2>&1 &
DAEMON=$!
trap 'kill -TERM $DAEMON 2>/dev/null; wait $DAEMON 2>/dev/null || true' EXIT
for _ in $(seq 100); do [ -s "$OUT/port" ] && break; sleep 0.1; done
ADDR=127.0.0.1:$(cat "$OUT/port")
echo "| method | size | sessions | frames/s | latency p50 ms | latency p99 ms | server GPU ms mean |"
echo "|---|---|---|---|---|---|---|"
for method in pt restir-gather; do
  for size in 128 256; do
    for c in 1 2 4 8; do
      dir="$OUT/${method}_${size}_c$c"
      "$BUILD/client/strata" loadtest --server "$ADDR" -c "$c" -z "$SECONDS_PER_POINT" --skip-first 2 --method "$method" \
        --width "$size" --height "$size" --encodings raw --timeout 120 --out "$dir" >"$dir.log" 2>&1
      python3 - "$dir/report.json" "$method" "$size" "$c" <<'PY'
import json, sys
r = json.load(open(sys.argv[1])); s = r["strata"]
print(f"| {sys.argv[2]} | {sys.argv[3]}x{sys.argv[3]} | {sys.argv[4]} | {s['frames_per_second']:.2f} | "
      f"{s['latency_ms']['p50']:.1f} | {s['latency_ms']['p99']:.1f} | {s['server_gpu_ms']['mean']:.1f} |")
PY
    done
  done
done
