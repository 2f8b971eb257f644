#!/usr/bin/env bash
# The main job: starts `stratad serve` on 127.0.0.1 (a free port), waits until its health is
# SERVING, streams carousel-bounce (objects and the camera move; the light comes mostly off a lit
# patch of wall, one bounce away) with the default method, auto (the
# session measures pt and restir-gather on its first frames and keeps the one with the lower error at
# equal time; docs/ARCHITECTURE.md, "Method auto") with `strata stream` into out/main
# (frame_NNNN.exr, frame_NNNN.png, frames.json), then stops the server with SIGTERM (graceful drain). Exits non-zero
# on any failure. STRATA_BUILD (default build/release) and STRATA_OUT (default out/main) override
# the build and output folders.
set -euo pipefail
cd "$(dirname "$0")/.."

build=${STRATA_BUILD:-build/release}
out=${STRATA_OUT:-out/main}
stratad=$build/server/stratad
strata=$build/client/strata
for bin in "$stratad" "$strata"; do
  if [ ! -x "$bin" ]; then
    echo "run-main.sh: $bin is missing; build first: cmake --preset release && cmake --build --preset release" >&2
    exit 1
  fi
done

work=$(mktemp -d)
pid=""
cleanup() {
  if [ -n "$pid" ] && kill -0 "$pid" 2>/dev/null; then kill -KILL "$pid" 2>/dev/null || true; fi
  rm -rf "$work"
}
trap cleanup EXIT

"$stratad" serve --listen 127.0.0.1:0 --port-file "$work/port" >"$work/stratad.log" 2>&1 &
pid=$!
for _ in $(seq 600); do  # up to 60 s for the device and the listener
  [ -s "$work/port" ] && break
  if ! kill -0 "$pid" 2>/dev/null; then
    echo "run-main.sh: stratad serve exited before listening:" >&2
    cat "$work/stratad.log" >&2
    exit 1
  fi
  sleep 0.1
done
if [ ! -s "$work/port" ]; then
  echo "run-main.sh: stratad serve did not start listening within 60 s" >&2
  cat "$work/stratad.log" >&2
  exit 1
fi
address=127.0.0.1:$(cat "$work/port")
"$strata" health --server "$address" --wait 30

mkdir -p "$out"
rm -f "$out"/frame_*.exr "$out"/frame_*.png "$out"/frames.json
if ! "$strata" stream --server "$address" --scene carousel-bounce --width 256 --height 256 \
    --frames 30 --seed 0 --out "$out"; then
  echo "run-main.sh: strata stream failed; stratad said:" >&2
  cat "$work/stratad.log" >&2
  exit 1
fi

kill -TERM "$pid"
status=0
wait "$pid" || status=$?
pid=""
cat "$work/stratad.log"
if [ "$status" -ne 0 ]; then
  echo "run-main.sh: stratad serve exited with status $status after SIGTERM" >&2
  exit 1
fi
echo "run-main.sh: 30 frames of carousel-bounce (method auto: see frames.json for the method it kept), EXR + PNG each, and frames.json in $out"
