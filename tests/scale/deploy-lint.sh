#!/usr/bin/env bash
# Checks deploy/ with the tools Debian packages: yamllint for the Kubernetes manifests, `haproxy -c`
# for deploy/haproxy/haproxy.cfg and the proxy config inside deploy/k8s/proxy.yaml, `nginx -t` for
# deploy/nginx/nginx.conf, `systemd-analyze verify` for the unit where systemd is there, and the
# shell scripts' syntax. Fails on the first tool that complains, with its output.
set -euo pipefail
root=$(cd "$(dirname "$0")/../.." && pwd)
tmp=$(mktemp -d /tmp/strata-deploy-lint.XXXXXX)
trap 'rm -rf "$tmp"' EXIT
step() { echo "deploy-lint: $*"; }

step "yamllint deploy/"
yamllint -s -c "$root/deploy/yamllint.yaml" "$root/deploy"

step "haproxy -c deploy/haproxy/haproxy.cfg"
STRATA_PROXY_LISTEN=127.0.0.1:50051 STRATA_BACKEND_1=127.0.0.1:50061 STRATA_BACKEND_2=127.0.0.1:50062 \
STRATA_BACKEND_3=127.0.0.1:50063 STRATA_HAPROXY_ADMIN=$tmp/admin.sock \
STRATA_HEALTH_CHECK=$root/deploy/haproxy/strata-health-check STRATA_CHECK_PATH=/usr/bin \
  haproxy -c -q -f "$root/deploy/haproxy/haproxy.cfg"

step "haproxy -c on deploy/k8s/proxy.yaml's haproxy.cfg"
python3 - "$root/deploy/k8s/proxy.yaml" "$tmp/k8s-haproxy.cfg" <<'PY'
import sys, yaml
docs = [d for d in yaml.safe_load_all(open(sys.argv[1])) if d and d.get("kind") == "ConfigMap"]
open(sys.argv[2], "w").write(docs[0]["data"]["haproxy.cfg"])
PY
# The cluster's DNS name does not resolve here; the config is otherwise checked as it is.
sed 's/stratad\.strata\.svc\.cluster\.local/localhost/' "$tmp/k8s-haproxy.cfg" > "$tmp/k8s-haproxy-local.cfg"
haproxy -c -q -f "$tmp/k8s-haproxy-local.cfg"

step "nginx -t deploy/nginx/nginx.conf"
mkdir -p "$tmp/nginx/tmp"
nginx -q -t -p "$tmp/nginx" -c "$root/deploy/nginx/nginx.conf"

if command -v systemd-analyze >/dev/null && [ -d /run/systemd/system ]; then
  step "systemd-analyze verify deploy/systemd/stratad@.service"
  cp "$root/deploy/systemd/stratad@.service" "$tmp/stratad@50061.service"
  systemd-analyze verify "$tmp/stratad@50061.service"
else
  step "systemd is not running here: checking the unit's required keys only"
fi
unit=$root/deploy/systemd/stratad@.service
for key in ExecStart= KillSignal=SIGTERM TimeoutStopSec= User=strata; do
  grep -q "^$key" "$unit" || { echo "deploy-lint: $unit lacks $key" >&2; exit 1; }
done
# Stopping must outlast the drain: TimeoutStopSec above the drain timeout.
stop=$(sed -n 's/^TimeoutStopSec=//p' "$unit"); drain=$(sed -n 's/^Environment=STRATAD_DRAIN_TIMEOUT=//p' "$unit")
[ "$stop" -gt "$drain" ] || { echo "deploy-lint: TimeoutStopSec=$stop is not above the drain timeout $drain" >&2; exit 1; }

step "Kubernetes: terminationGracePeriodSeconds above --drain-timeout"
python3 - "$root/deploy/k8s/stratad.yaml" <<'PY'
import sys, yaml
dep = [d for d in yaml.safe_load_all(open(sys.argv[1])) if d and d.get("kind") == "Deployment"][0]
spec = dep["spec"]["template"]["spec"]
c = spec["containers"][0]
drain = int(c["args"][c["args"].index("--drain-timeout") + 1])
assert spec["terminationGracePeriodSeconds"] > drain + 2, (spec["terminationGracePeriodSeconds"], drain)
assert "grpc" in c["readinessProbe"], c["readinessProbe"]
assert "preStop" in c["lifecycle"], c["lifecycle"]
PY

step "Dockerfile: Debian 12, the install script, a non-root user"
df=$root/deploy/docker/Dockerfile
grep -q '^FROM debian:12' "$df" && grep -q 'install-deps.sh' "$df" && grep -q '^USER strata' "$df" ||
  { echo "deploy-lint: $df must be FROM debian:12, run deploy/install-deps.sh and switch to USER strata" >&2; exit 1; }

step "shell syntax"
for f in "$root"/deploy/*.sh "$root"/deploy/haproxy/*.sh "$root"/tests/scale/*.sh; do bash -n "$f"; done
sh -n "$root/deploy/haproxy/strata-health-check"
echo "deploy-lint: OK"
