#!/usr/bin/env bash
# Runs the Dockerfile's steps without a Docker engine, as closely as this machine allows:
#   1. deps:    scripts/install-deps.sh build + runtime      (same script, same arguments)
#   2. build:   make build DEPS=build BUILD=... CMAKE_FLAGS=... in a clean clone of HEAD
#               (only the files `git archive` would send, like COPY . . with .dockerignore)
#   3. runtime: every shared library the binary needs comes from a package of
#               `install-deps.sh runtime` or of debian:12-slim's base; then the server runs as an
#               unprivileged user from the runtime paths with the image's environment
#               (0.0.0.0, PAPERNET_WEB_ROOT), the HEALTHCHECK script passes, GET / serves the
#               demo, and the compose client-test command (JS client tests at PAPERNET_URL) passes.
#   4. compose: its services (PostgreSQL, two nodes, nginx) from their scripts on loopback, the
#               client tests through the balancer, a node killed under a job (check-cluster.sh).
#   docker/check-steps.sh [WORKDIR]      (default: a new directory under /tmp)
#   REUSE_BUILD=1 docker/check-steps.sh WORKDIR   skips steps 1-2 when WORKDIR has a build
set -euo pipefail
repo=$(cd "$(dirname "$0")/.." && pwd)
work=${1:-$(mktemp -d /tmp/papernet-docker-steps.XXXXXX)}
step() { printf '\n== %s\n' "$*"; }
fail() { echo "FAILED: $*" >&2; exit 1; }
start=$(date +%s)

bin=$work/build/bin/papernet
web=$work/build/clients/web/dist
if [ "${REUSE_BUILD:-0}" = 1 ] && [ -x "$bin" ]; then
  step "reusing the build in $work/build (steps 1-2 skipped)"
else
  step "deps layer: scripts/install-deps.sh build && scripts/install-deps.sh runtime"
  bash "$repo/scripts/install-deps.sh" build
  bash "$repo/scripts/install-deps.sh" runtime

  step "build stage: clean tree of HEAD in $work/src, make build (as the Dockerfile)"
  rm -rf "$work/src" && mkdir -p "$work/src"
  git -C "$repo" archive HEAD | tar -x -C "$work/src"
  (cd "$work/src" && make build DEPS=build BUILD="$work/build" \
    CMAKE_FLAGS="-DPAPERNET_WERROR=ON -DPAPERNET_BUILD_TESTS=OFF" JOBS=2)
fi
[ -x "$bin" ] && [ -f "$web/index.html" ] && [ -f "$web/app.js" ] ||
  fail "the build did not produce the binary and the web bundle"

step "runtime stage: shared libraries come from runtime packages or the slim base"
runtime=$(sed -n 's/^runtime=(\(.*\))$/\1/p' "$repo/scripts/install-deps.sh")
base="libc6 libgcc-s1 libstdc++6 libssl3 zlib1g libzstd1 liblzma5 libbz2-1.0 libselinux1 libpcre2-8-0"
# The runtime packages and everything they depend on, recursively.
# shellcheck disable=SC2086
covered=" $base $(apt-cache depends --recurse --no-recommends --no-suggests --no-conflicts \
  --no-breaks --no-replaces --no-enhances $runtime 2>/dev/null | grep -v '^ ' | sed 's/:amd64$//' | tr '\n' ' ') "
missing=()
for lib in $(ldd "$bin" | awk '/=>/ {print $3}'); do
  # dpkg knows a file by the path its package ships (/lib or /usr/lib): match the file name.
  real=$(readlink -f "$lib")
  pkg=$(dpkg -S "*/$(basename "$(dirname "$real")")/$(basename "$real")" 2>/dev/null | head -1 |
    cut -d: -f1 || true)
  [[ -n "$pkg" && "$covered" == *" $pkg "* ]] || missing+=("$lib(${pkg:-no package})")
done
[ ${#missing[@]} -eq 0 ] || fail "libraries not brought by install-deps.sh runtime: ${missing[*]}"
echo "all $(ldd "$bin" | grep -c '=>') shared libraries are covered"

step "runtime stage: serve as an unprivileged user with the image's environment"
id papernet-check >/dev/null 2>&1 || useradd --system --no-create-home --shell /usr/sbin/nologin papernet-check
mkdir -p "$work/var" && chown papernet-check "$work/var"
chmod -R a+rX "$work/build/bin" "$web" "$work"
port=$(python3 -c 'import socket; s=socket.socket(); s.bind(("127.0.0.1",0)); print(s.getsockname()[1])')
setpriv --reuid=papernet-check --regid=papernet-check --init-groups env PAPERNET_HOST=0.0.0.0 PAPERNET_PORT="$port" PAPERNET_DATA="$work/var" \
  PAPERNET_WEB_ROOT="$web" PAPERNET_WORKERS=1 "$bin" serve >"$work/serve.log" 2>&1 &
pid=$!
trap 'kill -TERM $pid 2>/dev/null || true; wait $pid 2>/dev/null || true' EXIT
for _ in $(seq 100); do
  PAPERNET_PORT=$port bash "$repo/docker/healthcheck.sh" 2>/dev/null && break
  kill -0 $pid 2>/dev/null || fail "serve exited: $(cat "$work/serve.log")"
  sleep 0.2
done
PAPERNET_PORT=$port bash "$repo/docker/healthcheck.sh" && echo "HEALTHCHECK passes"
[ "$(ps -o user= -p $pid)" = papernet-check ] || fail "server does not run as the unprivileged user"
grep -q "listening on http://0.0.0.0:$port" "$work/serve.log" || fail "not listening on 0.0.0.0"
curl -fsS "http://127.0.0.1:$port/" | grep -q '<script type="module" src="app.js">' || fail "GET / is not the demo"
echo "GET / serves the web demo"

step "compose client-test: node --test clients/js/test/client.test.js against PAPERNET_URL"
(cd "$work/src" && PAPERNET_URL="http://127.0.0.1:$port" PAPERNET_TEST_DATA="$work/src/tests/data" \
  node --test clients/js/test/client.test.js)

kill -TERM $pid && wait $pid || true
trap - EXIT

step "compose cluster: PostgreSQL, two nodes, nginx, client tests (docker/check-cluster.sh)"
(cd "$work/src" && bash docker/check-cluster.sh "$bin" "$work/cluster")
echo "docker steps OK in $(($(date +%s) - start)) s (work dir $work)"
