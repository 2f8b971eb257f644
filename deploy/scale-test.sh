#!/usr/bin/env bash
# Scale test on 127.0.0.1 only: three stratad daemons behind HAProxy (deploy/haproxy/haproxy.cfg),
# 16 sessions streaming through the proxy, then a drain and a kill.
#   1. Every call of a session (GetServerStatus, CreateSession, Stream, DeleteSession) reaches one
#      daemon, and all three daemons get sessions.
#   2. Draining one daemon (HAProxy runtime API) sends no new sessions there, while the streams it
#      holds go on and finish normally.
#   3. Killing one daemon (SIGKILL) ends only its sessions: their clients fail with UNAVAILABLE,
#      the other sessions keep streaming and finish.
# Bounded: 16 + 6 sessions of 16x16 frames, every wait has a deadline, everything it started is
# stopped on exit.
#   deploy/scale-test.sh [BUILD_DIR]   (default build/release)   env: SCALE_FRAMES, SCALE_SESSIONS
set -euo pipefail

root=$(cd "$(dirname "$0")/.." && pwd)
build=${1:-$root/build/release}
stratad=$build/server/stratad
strata=$build/client/strata
sessions=${SCALE_SESSIONS:-16}
frames=${SCALE_FRAMES:-400}   # per wave-1 session: long enough for the drain and the kill to happen mid-stream
late_sessions=6
deadline=$((SECONDS + ${SCALE_TIMEOUT:-240}))
for tool in haproxy socat python3; do command -v $tool >/dev/null || { echo "scale-test: $tool is not installed" >&2; exit 2; }; done

tmp=$(mktemp -d /tmp/strata-scale.XXXXXX)
pids=()
cleanup() {
  for p in "${pids[@]}"; do kill -9 "$p" 2>/dev/null || true; done
  wait 2>/dev/null || true
  if [ "${keep_tmp:-0}" = 1 ]; then echo "scale-test: logs kept in $tmp" >&2; else rm -rf "$tmp"; fi
}
trap cleanup EXIT
fail() {
  echo "scale-test: FAIL: $*" >&2
  keep_tmp=1
  for f in "$tmp"/*.log; do echo "--- $f (tail)" >&2; tail -n 5 "$f" >&2; done
  exit 1
}
check_time() { [ $SECONDS -lt $deadline ] || fail "out of time ($1)"; }
free_port() { python3 -c 'import socket; s=socket.socket(); s.bind(("127.0.0.1", 0)); print(s.getsockname()[1])'; }
# The software renderer shares this machine's cores among three daemons.
export LP_NUM_THREADS=${LP_NUM_THREADS:-1}

# ---- three daemons ---------------------------------------------------------------------------
declare -A daemon_pid daemon_addr
for i in 1 2 3; do
  "$stratad" serve --listen 127.0.0.1:0 --port-file "$tmp/s$i.port" --instance-id "s$i" --max-sessions 16 \
    --max-pixels 65536 --drain-timeout 5 --idle-timeout 60 > "$tmp/stratad-s$i.log" 2>&1 &
  daemon_pid[s$i]=$!; pids+=($!)
done
for i in 1 2 3; do
  until [ -s "$tmp/s$i.port" ]; do check_time "stratad s$i start"; sleep 0.1; done
  daemon_addr[s$i]=127.0.0.1:$(cat "$tmp/s$i.port")
done

# ---- HAProxy in front ------------------------------------------------------------------------
proxy=127.0.0.1:$(free_port)
admin=$tmp/haproxy.sock
STRATA_PROXY_LISTEN=$proxy STRATA_BACKEND_1=${daemon_addr[s1]} STRATA_BACKEND_2=${daemon_addr[s2]} \
STRATA_BACKEND_3=${daemon_addr[s3]} STRATA_HAPROXY_ADMIN=$admin STRATA_HEALTH_CHECK=$root/deploy/haproxy/strata-health-check \
STRATA_CHECK_PATH=$(dirname "$strata"):/usr/bin:/bin \
  haproxy -db -f "$root/deploy/haproxy/haproxy.cfg" > "$tmp/haproxy.log" 2>&1 &
pids+=($!)
server_state() { echo "show stat" | socat -t 2 stdio "unix-connect:$admin" 2>/dev/null | awk -F, -v s="$1" '$1=="stratad" && $2==s {print $18}'; }
for s in s1 s2 s3; do
  until [ "$(server_state $s)" = UP ]; do check_time "HAProxy sees $s UP"; sleep 0.2; done
done
echo "scale-test: 3 daemons (${daemon_addr[*]}) behind HAProxy on $proxy"

# ---- clients ---------------------------------------------------------------------------------
declare -A client_pid client_instance
start_client() {  # id frames
  "$strata" stream --server "$proxy" --session-id "$1" --method pt --width 16 --height 16 --frames "$2" --encodings raw \
    --out "$tmp/$1" --timeout 120 > "$tmp/client-$1.log" 2>&1 &
  client_pid[$1]=$!; pids+=($!)
}
frames_of() { ls "$tmp/$1" 2>/dev/null | grep -c '^frame_.*\.exr$' || true; }
instance_of() { sed -n 's/.*, instance \([^)]*\)).*/\1/p' "$tmp/client-$1.log" | head -n 1; }
running() { kill -0 "${client_pid[$1]}" 2>/dev/null; }
# Sets rc to the client's exit status (not in a $(...) subshell: only this shell can wait for it).
exit_of() { rc=0; wait "${client_pid[$1]}" || rc=$?; }
wait_streaming() {  # ids...: created and at least 2 frames each
  for id in "$@"; do
    until [ -n "$(instance_of "$id")" ] && [ "$(frames_of "$id")" -ge 2 ]; do
      running "$id" || [ "$(frames_of "$id")" -ge 2 ] || fail "$id ended before streaming: $(tail -n 2 "$tmp/client-$id.log")"
      check_time "$id streaming"; sleep 0.1
    done
    client_instance[$id]=$(instance_of "$id")
  done
}

wave1=()
for n in $(seq 1 "$sessions"); do wave1+=("scale-$(printf %02d "$n")"); done
for id in "${wave1[@]}"; do start_client "$id" "$frames"; done
wait_streaming "${wave1[@]}"
declare -A per_instance=([s1]=0 [s2]=0 [s3]=0)
for id in "${wave1[@]}"; do per_instance[${client_instance[$id]}]=$((per_instance[${client_instance[$id]}] + 1)); done
echo "scale-test: $sessions sessions streaming: s1=${per_instance[s1]} s2=${per_instance[s2]} s3=${per_instance[s3]}"
for s in s1 s2 s3; do [ "${per_instance[$s]}" -gt 0 ] || fail "daemon $s got no session of $sessions"; done

# ---- drain one daemon: no new sessions there, its streams go on ------------------------------
drained=s1
victim=s2
"$root/deploy/haproxy/drain.sh" "$admin" "$drained" drain > /dev/null
late=()
for n in $(seq 1 $late_sessions); do late+=("late-$n"); start_client "late-$n" 3; done
for id in "${late[@]}"; do
  exit_of "$id"
  [ "$rc" = 0 ] || fail "$id (started during the drain) failed: $(tail -n 2 "$tmp/client-$id.log")"
  inst=$(instance_of "$id")
  [ "$inst" != "$drained" ] || fail "$id went to the drained daemon $drained"
  echo "scale-test: $id (during the drain of $drained) -> $inst"
done

# ---- kill one daemon: only its sessions end --------------------------------------------------
victims=(); others=()
for id in "${wave1[@]}"; do
  if [ "${client_instance[$id]}" = "$victim" ]; then victims+=("$id"); else others+=("$id"); fi
done
for id in "${wave1[@]}"; do running "$id" || fail "$id finished before the kill: raise SCALE_FRAMES (now $frames)"; done
declare -A before
for id in "${others[@]}"; do before[$id]=$(frames_of "$id"); done
kill -9 "${daemon_pid[$victim]}"
{ wait "${daemon_pid[$victim]}"; } 2>/dev/null || true  # reaped here, quietly
echo "scale-test: killed $victim (${#victims[@]} sessions)"
for id in "${victims[@]}"; do
  until ! running "$id"; do check_time "$id ends after the kill"; sleep 0.1; done
  exit_of "$id"
  [ "$rc" != 0 ] || fail "$id's daemon was killed but it exited 0"
  grep -q "UNAVAILABLE" "$tmp/client-$id.log" || fail "$id did not report UNAVAILABLE: $(tail -n 2 "$tmp/client-$id.log")"
done
sleep 1
for id in "${others[@]}"; do
  [ "$(frames_of "$id")" -gt "${before[$id]}" ] || running "$id" || [ "$(frames_of "$id")" -eq "$frames" ] ||
    fail "$id (on ${client_instance[$id]}) stopped streaming after $victim was killed"
done

# ---- the others (the drained daemon's included) finish normally, each on one daemon ----------
for id in "${others[@]}"; do
  until ! running "$id"; do check_time "$id finishes"; sleep 0.2; done
  exit_of "$id"
  [ "$rc" = 0 ] || fail "$id (on ${client_instance[$id]}) failed: $(tail -n 2 "$tmp/client-$id.log")"
  [ "$(frames_of "$id")" -eq "$frames" ] || fail "$id got $(frames_of "$id") of $frames frames"
  python3 - "$tmp/$id/frames.json" "${client_instance[$id]}" <<'PY' || fail "$id: its calls reached more than one daemon"
import json, sys
doc = json.load(open(sys.argv[1]))
calls = doc["server"]["instances"]
assert set(calls) == {"GetServerStatus", "CreateSession", "Stream", "DeleteSession"}, calls
assert set(calls.values()) == {sys.argv[2]}, calls
PY
done
echo "scale-test: PASS: ${#others[@]} sessions finished on their daemons (${per_instance[$drained]} on the drained $drained)," \
     "${#victims[@]} ended with UNAVAILABLE when $victim was killed, ${#late[@]} new sessions avoided $drained; ${SECONDS}s"
