#!/usr/bin/env bash
# The services of docker/compose.yaml without a Docker engine: each runs here on loopback with
# the script its container runs, and the compose file's checks run against them.
#   postgres     scripts/install-deps.sh postgres; docker/postgres.sh (PGLISTEN=127.0.0.1)
#   papernet-a/b the papernet binary as an unprivileged user, PAPERNET_STORE at that database
#   balancer     scripts/install-deps.sh nginx; docker/nginx.sh over the two nodes
#   client-test  node --test clients/js/test/client.test.js against the balancer
# Then: the HEALTHCHECK script passes through the balancer and on each node; a job submitted
# through the balancer is answered by both nodes; the node running a job is killed (kill -9)
# and the job still succeeds, answered through the balancer.
#   docker/check-cluster.sh BIN [WORKDIR]    (BIN: a built papernet binary)
set -euo pipefail
repo=$(cd "$(dirname "$0")/.." && pwd)
bin=$(readlink -f "${1:?usage: $0 BIN [WORKDIR]}")
work=${2:-$(mktemp -d /tmp/papernet-cluster.XXXXXX)}
step() { printf '\n== %s\n' "$*"; }
fail() { echo "FAILED: $*" >&2; exit 1; }
free_port() { python3 -c 'import socket; s=socket.socket(); s.bind(("127.0.0.1",0)); print(s.getsockname()[1])'; }
pids=()
cleanup() { for pid in "${pids[@]}"; do kill -TERM "$pid" 2>/dev/null || true; done; wait 2>/dev/null || true; }
trap cleanup EXIT
mkdir -p "$work"
chmod 755 "$work"

step "postgres: install-deps.sh postgres, docker/postgres.sh on 127.0.0.1"
bash "$repo/scripts/install-deps.sh" postgres
pg_port=$(free_port)
rm -rf "$work/pgdata"
PGDATA=$work/pgdata POSTGRES_PASSWORD=cluster-check PGLISTEN=127.0.0.1 PGPORT=$pg_port \
  bash "$repo/docker/postgres.sh" >"$work/postgres.log" 2>&1 &
pids+=($!)
for _ in $(seq 100); do
  pg_isready -q -h 127.0.0.1 -p "$pg_port" && break
  sleep 0.2
done
pg_isready -h 127.0.0.1 -p "$pg_port" || fail "postgres did not start: $(cat "$work/postgres.log")"

step "papernet-a, papernet-b: two nodes on one store, as an unprivileged user"
id papernet-check >/dev/null 2>&1 ||
  useradd --system --no-create-home --shell /usr/sbin/nologin papernet-check
store="postgres://papernet:cluster-check@127.0.0.1:$pg_port/papernet"
declare -A node_port node_pid
for node in a b; do
  node_port[$node]=$(free_port)
  mkdir -p "$work/$node" && chown papernet-check "$work/$node"
  setpriv --reuid=papernet-check --regid=papernet-check --init-groups env \
    PAPERNET_STORE="$store" PAPERNET_PORT="${node_port[$node]}" PAPERNET_DATA="$work/$node" \
    PAPERNET_WORKERS=1 PAPERNET_LEASE=5 "$bin" serve >"$work/$node.log" 2>&1 &
  node_pid[$node]=$!
  pids+=($!)
done
for node in a b; do
  for _ in $(seq 100); do
    PAPERNET_PORT=${node_port[$node]} bash "$repo/docker/healthcheck.sh" 2>/dev/null && break
    kill -0 "${node_pid[$node]}" 2>/dev/null || fail "node $node exited: $(cat "$work/$node.log")"
    sleep 0.2
  done
  PAPERNET_PORT=${node_port[$node]} bash "$repo/docker/healthcheck.sh" ||
    fail "node $node is not ready"
done
echo "both nodes ready"

step "balancer: install-deps.sh nginx, docker/nginx.sh over both nodes"
bash "$repo/scripts/install-deps.sh" nginx
lb_port=$(free_port)
PAPERNET_NODES="127.0.0.1:${node_port[a]} 127.0.0.1:${node_port[b]}" \
  PAPERNET_LISTEN="127.0.0.1:$lb_port" bash "$repo/docker/nginx.sh" >"$work/nginx.log" 2>&1 &
pids+=($!)
for _ in $(seq 50); do
  PAPERNET_PORT=$lb_port bash "$repo/docker/healthcheck.sh" 2>/dev/null && break
  sleep 0.2
done
PAPERNET_PORT=$lb_port bash "$repo/docker/healthcheck.sh" && echo "HEALTHCHECK passes through the balancer"
lb=http://127.0.0.1:$lb_port

step "a job through the balancer, answered by both nodes"
id=$(curl -fsS --data-binary @"$repo/tests/data/mirror.ply" -H 'Content-Type: model/x-ply' \
  "$lb/v1/jobs?strategy=TU" | sed 's/.*"id":"\([0-9a-f]*\)".*/\1/')
for node in a b; do
  curl -fsS "http://127.0.0.1:${node_port[$node]}/v1/jobs/$id" >/dev/null ||
    fail "node $node does not know job $id"
done
echo "job $id is known to both nodes"

step "client-test: the JS client tests against the balancer"
(cd "$repo" && PAPERNET_URL=$lb PAPERNET_TEST_DATA="$repo/tests/data" \
  node --test clients/js/test/client.test.js)

step "kill -9 the node running a job; the other finishes it"
id=$(curl -fsS --data-binary @"$repo/tests/data/Duck.glb" -H 'Content-Type: model/gltf-binary' \
  "$lb/v1/jobs?strategy=TU&seed=11" | sed 's/.*"id":"\([0-9a-f]*\)".*/\1/')
runner=""
for _ in $(seq 300); do
  for node in a b; do grep -q "job $id queued -> running" "$work/$node.log" && runner=$node; done
  [ -n "$runner" ] && break
  sleep 0.1
done
[ -n "$runner" ] || fail "no node ran job $id"
kill -KILL "${node_pid[$runner]}"
echo "killed node $runner while it ran job $id"
status=""
for _ in $(seq 600); do
  status=$(curl -sS "$lb/v1/jobs/$id" | sed 's/.*"status":"\([a-z]*\)".*/\1/')
  [ "$status" = succeeded ] && break
  sleep 0.2
done
[ "$status" = succeeded ] || fail "job $id ended $status after its node was killed"
curl -fsS -o /dev/null "$lb/v1/jobs/$id/net.pdf" || fail "no result through the balancer"
echo "job $id succeeded on the other node; its result is served through the balancer"
echo "cluster steps OK (work dir $work)"
