#!/usr/bin/env bash
# Installs the Debian 12 packages papernet builds, tests and runs with, if any are missing.
# Used by `make`, by CI and by the Dockerfile, so all three install the same things.
#   scripts/install-deps.sh          build + run + test dependencies
#   scripts/install-deps.sh runtime  only what the papernet binary needs to run
#   scripts/install-deps.sh postgres the database of several nodes (docker/compose.yaml)
#   scripts/install-deps.sh nginx    the load balancer in front of them (docker/compose.yaml)
#   scripts/install-deps.sh blender  the peer of `make print-benchmark` (docs/print.md)
set -euo pipefail

runtime=(libdraco7 libsqlite3-0 libpq5 libcairo2 libcpp-httplib0.11 libssl3 libpolyclipping22
  libpng16-16 libjpeg62-turbo ca-certificates)
build=(build-essential cmake pkg-config git clang-format ccache
  libdraco-dev libtinygltf-dev nlohmann-json3-dev libcpp-httplib-dev
  libgtest-dev libsqlite3-dev libpq-dev libcairo2-dev zlib1g-dev libssl-dev
  libpolyclipping-dev libpng-dev libjpeg-dev)
# Node.js and npm bundle the web demo and run the JS client tests. Any Node >= 18 with npm
# will do (Debian 12 ships 18); one already on the PATH is kept.
if ! command -v node >/dev/null || ! command -v npm >/dev/null; then
  build+=(nodejs npm)
fi
# Tools the tests call: SVG rendering and XML checking, PDF inspection; curl for the curl
# session; Chromium for the browser test of the web demo (driven by playwright-core from npm).
test_tools=(librsvg2-bin poppler-utils libxml2-utils curl chromium)
# clang with its sanitizer and libFuzzer runtimes: the ASan/UBSan/TSan builds and fuzz targets
# of `make test` (docs/reliability.md).
test_tools+=(clang libclang-rt-14-dev)
# PostgreSQL 15: the tests of the shared job store start real servers of their own
# (scripts/test-postgres.sh).
test_tools+=(postgresql)

case "${1:-all}" in
  runtime) wanted=("${runtime[@]}") ;;
  build) wanted=("${build[@]}") ;;
  all) wanted=("${runtime[@]}" "${build[@]}" "${test_tools[@]}") ;;
  postgres) wanted=(postgresql) ;;
  nginx) wanted=(nginx) ;;
  blender) wanted=(blender) ;;
  *) echo "usage: $0 [runtime|build|all|postgres|nginx|blender]" >&2; exit 2 ;;
esac

missing=()
for pkg in "${wanted[@]}"; do
  if ! dpkg-query -W -f='${Status}' "$pkg" 2>/dev/null | grep -q 'install ok installed'; then
    missing+=("$pkg")
  fi
done
[ ${#missing[@]} -eq 0 ] && exit 0

echo "installing missing Debian packages: ${missing[*]}"
sudo=()
if [ "$(id -u)" -ne 0 ]; then
  if command -v sudo >/dev/null; then sudo=(sudo); else
    echo "error: missing packages and not root: ${missing[*]}" >&2
    exit 1
  fi
fi
export DEBIAN_FRONTEND=noninteractive
"${sudo[@]}" apt-get update -qq
"${sudo[@]}" apt-get install -y -qq --no-install-recommends "${missing[@]}"
