#!/usr/bin/env bash
# Proxy and TLS overhead on 127.0.0.1 (docs/BENCHMARKS.md): one run, frame latency of the same
# lockstep stream (strata stream --in-flight 1, 64x64 pt, raw frames) direct to stratad, through
# HAProxy (deploy/haproxy/haproxy.cfg with the same daemon as all three backends), and to a
# second stratad serving TLS; the rounds alternate so that machine load drifts hit all three.
#   tests/scale/overhead-bench.sh [BUILD_DIR] [FRAMES] [ROUNDS]
set -euo pipefail
root=$(cd "$(dirname "$0")/../.." && pwd)
build=${1:-$root/build/release}; frames=${2:-60}; rounds=${3:-3}
stratad=$build/server/stratad; strata=$build/client/strata
tmp=$(mktemp -d /tmp/strata-overhead.XXXXXX)
pids=()
trap 'for p in "${pids[@]}"; do kill "$p" 2>/dev/null || true; done; wait 2>/dev/null || true; rm -rf "$tmp"' EXIT
free_port() { python3 -c 'import socket; s=socket.socket(); s.bind(("127.0.0.1", 0)); print(s.getsockname()[1])'; }

(cd "$tmp" && openssl req -x509 -newkey ec -pkeyopt ec_paramgen_curve:prime256v1 -nodes -days 1 -subj /CN=bench-ca \
   -keyout ca.key -out ca.pem 2>/dev/null &&
 printf 'subjectAltName=IP:127.0.0.1\n' > ext &&
 openssl req -newkey ec -pkeyopt ec_paramgen_curve:prime256v1 -nodes -subj /CN=stratad -keyout s.key -out s.csr 2>/dev/null &&
 openssl x509 -req -in s.csr -CA ca.pem -CAkey ca.key -CAcreateserial -days 1 -extfile ext -out s.pem 2>/dev/null)

"$stratad" serve --listen 127.0.0.1:0 --port-file "$tmp/plain.port" --instance-id plain > "$tmp/plain.log" 2>&1 & pids+=($!)
"$stratad" serve --listen 127.0.0.1:0 --port-file "$tmp/tls.port" --instance-id tls --tls-cert "$tmp/s.pem" --tls-key "$tmp/s.key" \
  > "$tmp/tls.log" 2>&1 & pids+=($!)
for f in plain tls; do for _ in $(seq 600); do [ -s "$tmp/$f.port" ] && break; sleep 0.1; done; done
plain=127.0.0.1:$(cat "$tmp/plain.port"); tls=127.0.0.1:$(cat "$tmp/tls.port"); proxy=127.0.0.1:$(free_port)
STRATA_PROXY_LISTEN=$proxy STRATA_BACKEND_1=$plain STRATA_BACKEND_2=$plain STRATA_BACKEND_3=$plain \
STRATA_HAPROXY_ADMIN=$tmp/admin.sock STRATA_HEALTH_CHECK=$root/deploy/haproxy/strata-health-check \
STRATA_CHECK_PATH=$(dirname "$strata"):/usr/bin:/bin haproxy -db -f "$root/deploy/haproxy/haproxy.cfg" > "$tmp/haproxy.log" 2>&1 &
pids+=($!)
"$strata" health --server "$plain" --wait 60 > /dev/null; "$strata" health --server "$tls" --tls-ca "$tmp/ca.pem" --wait 60 > /dev/null
"$strata" health --server "$proxy" --wait 30 > /dev/null

stream() {  # name args...
  local name=$1; shift
  "$strata" stream "$@" --method pt --width 64 --height 64 --frames "$frames" --encodings raw --out "$tmp/out-$name" > /dev/null 2>&1
  python3 -c 'import json,sys; d=json.load(open(sys.argv[1])); l=sorted(f["client"]["latency_ms"] for f in d["frames"][5:]); print(l[len(l)//2])' \
    "$tmp/out-$name/frames.json"
}
stream warm --server "$plain" > /dev/null; stream warm --server "$tls" --tls-ca "$tmp/ca.pem" > /dev/null
declare -A sum=([direct]=0 [haproxy]=0 [tls]=0)
for r in $(seq "$rounds"); do
  d=$(stream direct --server "$plain"); p=$(stream haproxy --server "$proxy"); t=$(stream tls --server "$tls" --tls-ca "$tmp/ca.pem")
  echo "round $r: median frame latency direct $d ms, through HAProxy $p ms, TLS $t ms"
  sum[direct]=$(python3 -c "print(${sum[direct]} + $d)"); sum[haproxy]=$(python3 -c "print(${sum[haproxy]} + $p)")
  sum[tls]=$(python3 -c "print(${sum[tls]} + $t)")
done
python3 - "${sum[direct]}" "${sum[haproxy]}" "${sum[tls]}" "$rounds" <<'PY'
import sys
d, p, t, n = (float(x) for x in sys.argv[1:])
print(f"mean of round medians: direct {d/n:.2f} ms, HAProxy {p/n:.2f} ms (ratio {p/d:.3f}), TLS {t/n:.2f} ms (ratio {t/d:.3f})")
PY
