#!/usr/bin/env bash
# Installs everything strata needs on Debian 12 (bookworm). Idempotent; run as root (or with sudo).
# bookworm-backports is enabled with a pin so that only Mesa's Vulkan drivers (lavapipe with
# VK_KHR_ray_query needs Mesa >= 24.1) and the libraries they pull in come from it.
set -euo pipefail

SUDO=""
if [ "$(id -u)" -ne 0 ]; then SUDO="sudo"; fi

. /etc/os-release
if [ "${VERSION_CODENAME:-}" != "bookworm" ]; then
  echo "install-deps.sh: expected Debian 12 (bookworm), found '${PRETTY_NAME:-unknown}'; continuing anyway" >&2
fi

BACKPORTS_LIST=/etc/apt/sources.list.d/strata-bookworm-backports.list
PIN_FILE=/etc/apt/preferences.d/strata-backports-mesa
if ! grep -rqs "bookworm-backports" /etc/apt/sources.list /etc/apt/sources.list.d/; then
  echo "deb http://deb.debian.org/debian bookworm-backports main" | $SUDO tee "$BACKPORTS_LIST" >/dev/null
fi
# Backports stay at their default low priority except for Mesa and its direct companions.
$SUDO tee "$PIN_FILE" >/dev/null <<'PIN'
Package: mesa-vulkan-drivers libdrm* libllvm* libgl1-mesa-dri libglx-mesa0 libegl-mesa0 libglapi-mesa libgbm1 mesa-libgallium libwayland* libvulkan1 libvulkan-dev
Pin: release n=bookworm-backports
Pin-Priority: 600
PIN

export DEBIAN_FRONTEND=noninteractive
$SUDO apt-get update -qq

PKGS=(
  build-essential cmake ninja-build pkg-config git
  libvulkan-dev vulkan-validationlayers glslang-tools spirv-tools vulkan-tools
  mesa-vulkan-drivers
  libgrpc++-dev protobuf-compiler-grpc libprotobuf-dev protobuf-compiler
  libopenexr-dev libtinygltf-dev libmeshoptimizer-dev libglm-dev
  libgtest-dev libgmock-dev libbenchmark-dev nlohmann-json3-dev libcli11-dev libpng-dev
  libjpeg-dev  # libjpeg-turbo: the viewer's JPEG frames (server/http/frame_jpeg.cpp)
  libssl-dev
  python3
  # deploy/ and its tests (proxies, runtime API, manifest lint, certificates, libFuzzer)
  haproxy nginx-light socat yamllint openssl clang libclang-rt-dev
  chromium
  prometheus-cpp-dev libcivetweb-dev prometheus
  assimp-testmodels libstb-dev  # glTF 2.0 test corpus (tests/unit/gltf_conformance_test.cpp); stb_image decodes textures and .hdr
)
# npm runs at build time (uPlot for the eval report and the dashboard, cmake/uplot); Debian's nodejs and npm
# only when no npm is on PATH already (a newer Node may be installed some other way).
if ! command -v npm >/dev/null 2>&1; then PKGS+=(nodejs npm); fi
$SUDO apt-get install -y -qq --no-install-recommends "${PKGS[@]}"

# Check that lavapipe is new enough for ray queries.
ver=$(dpkg-query -W -f='${Version}' mesa-vulkan-drivers 2>/dev/null || echo 0)
major=${ver%%.*}; major=${major##*:}
if [ "${major:-0}" -lt 24 ]; then
  echo "install-deps.sh: mesa-vulkan-drivers $ver is older than 24.1; lavapipe will lack VK_KHR_ray_query" >&2
  exit 1
fi
echo "install-deps.sh: done (mesa-vulkan-drivers $ver)"
