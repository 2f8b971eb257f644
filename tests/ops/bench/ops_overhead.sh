#!/usr/bin/env bash
# The cost of metrics and the dashboard on frame time, in one run (docs/BENCHMARKS.md): two stratad
# processes, A plain and B with --metrics-listen and --http, a dashboard viewer reading B's /events
# and a scraper reading B's /metrics every second. ROUNDS alternating loadtest runs (A, B, A, B, ...)
# of pt at 128x128 with 2 sessions. Printed: B's own measure of the observers' time on the frame path
# against its render time (strata_frame_observer_seconds_sum / strata_frame_render_seconds_sum: the
# direct ratio), and the ratio of B to A of frames/s and latency p50 (end to end, but on a shared
# machine the run-to-run noise is larger than the effect).
#   tests/ops/bench/ops_overhead.sh [BUILD_DIR] [OUT_DIR]
set -euo pipefail
BUILD=${1:-build/release}
OUT=${2:-out/bench/ops_overhead}
ROUNDS=${ROUNDS:-4}
SECONDS_PER_RUN=${SECONDS_PER_RUN:-10}
mkdir -p "$OUT"
"$BUILD/server/stratad" serve --listen 127.0.0.1:0 --port-file "$OUT/port_a" >"$OUT/a.log" 2>&1 &
A=$!
"$BUILD/server/stratad" serve --listen 127.0.0.1:0 --port-file "$OUT/port_b" --metrics-listen 127.0.0.1:0 --http 127.0.0.1:0 >"$OUT/b.log" 2>&1 &
B=$!
VIEWER="" SCRAPER=""
cleanup() {
  for p in $VIEWER $SCRAPER; do kill "$p" 2>/dev/null || true; done
  kill -TERM $A $B 2>/dev/null || true
  wait $A $B 2>/dev/null || true
}
trap cleanup EXIT
for _ in $(seq 100); do [ -s "$OUT/port_a" ] && [ -s "$OUT/port_b" ] && grep -q "dashboard on" "$OUT/b.log" && break; sleep 0.1; done
METRICS=$(grep -o 'metrics on http://[0-9.:]*' "$OUT/b.log" | cut -d/ -f3)
HTTP=$(grep -o 'dashboard on http://[0-9.:]*' "$OUT/b.log" | cut -d/ -f3)
curl -s -N "http://$HTTP/events" >/dev/null &
VIEWER=$!
( while true; do curl -s "http://$METRICS/metrics" >/dev/null; sleep 1; done ) &
SCRAPER=$!
for round in $(seq "$ROUNDS"); do
  for which in a b; do
    "$BUILD/client/strata" loadtest --server "127.0.0.1:$(cat "$OUT/port_$which")" -c 2 -z "$SECONDS_PER_RUN" --skip-first 2 \
      --method pt --width 128 --height 128 --encodings raw --out "$OUT/${which}_$round" >"$OUT/${which}_$round.log" 2>&1
  done
done
curl -s "http://$METRICS/metrics" >"$OUT/b_metrics.txt"
python3 - "$OUT" "$ROUNDS" <<'PY'
import json, sys, statistics
out, rounds = sys.argv[1], int(sys.argv[2])
sums = {}
for line in open(f"{out}/b_metrics.txt"):
    for name in ("strata_frame_observer_seconds_sum", "strata_frame_render_seconds_sum", "strata_frame_observer_seconds_count"):
        if line.startswith(name):
            sums[name] = sums.get(name, 0.0) + float(line.split()[-1])
obs, ren, n = sums["strata_frame_observer_seconds_sum"], sums["strata_frame_render_seconds_sum"], sums["strata_frame_observer_seconds_count"]
print(f"observers on the frame path: {obs * 1e6 / n:.1f} us per frame over {int(n)} frames; render {ren * 1e3 / n:.2f} ms per frame; "
      f"ratio {obs / ren:.5f} ({100 * obs / ren:.3f} %)")
def load(w): return [json.load(open(f"{out}/{w}_{i}/report.json"))["strata"] for i in range(1, rounds + 1)]
a, b = load("a"), load("b")
fa = statistics.mean(x["frames_per_second"] for x in a); fb = statistics.mean(x["frames_per_second"] for x in b)
la = statistics.mean(x["latency_ms"]["p50"] for x in a); lb = statistics.mean(x["latency_ms"]["p50"] for x in b)
print(f"plain:             {fa:.2f} frames/s, latency p50 {la:.2f} ms (runs: {[round(x['frames_per_second'], 2) for x in a]})")
print(f"metrics+dashboard: {fb:.2f} frames/s, latency p50 {lb:.2f} ms (runs: {[round(x['frames_per_second'], 2) for x in b]})")
print(f"ratio (with / without): frame time {fa / fb:.4f} (from frames/s), latency p50 {lb / la:.4f}")
PY
