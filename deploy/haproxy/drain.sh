#!/usr/bin/env bash
# Drains (or re-enables) one daemon through HAProxy's runtime API: drained, it takes no new
# sessions, while the calls of the sessions it holds (stick table) still reach it until they end.
#   deploy/haproxy/drain.sh SOCKET SERVER [drain|ready]     e.g. drain.sh /run/haproxy/admin.sock s2
set -euo pipefail
sock=${1:?runtime API socket}; server=${2:?server name (s1, s2, ...)}; state=${3:-drain}
case "$state" in drain|ready|maint) ;; *) echo "drain.sh: state must be drain, ready or maint" >&2; exit 2 ;; esac
reply=$(echo "set server stratad/$server state $state" | socat -t 2 stdio "unix-connect:$sock")
if [ -n "$reply" ]; then echo "drain.sh: $reply" >&2; exit 1; fi
echo "stratad/$server: $state"
