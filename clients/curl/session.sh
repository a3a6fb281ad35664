#!/usr/bin/env bash
# The papernet HTTP API with nothing but curl: submit a mesh, follow it, fetch the results.
# Every request is printed before it runs, so the output reads as the README's curl session.
#
#   PAPERNET_URL=http://127.0.0.1:8080 clients/curl/session.sh [MESH]
#   PAPERNET_BIN=build/bin/papernet clients/curl/session.sh   # starts its own server
#
# Exits non-zero (naming the step) when any answer is not what the API promises; the test suite
# runs it against a live server.
set -euo pipefail

here=$(cd "$(dirname "$0")" && pwd)
data=${PAPERNET_TEST_DATA:-$here/../../tests/data}
mesh=${1:-$data/sample.obj}
work=$(mktemp -d)
server_pid=
cleanup() {
  if [ -n "$server_pid" ]; then kill -TERM "$server_pid" 2>/dev/null || true; wait "$server_pid" 2>/dev/null || true; fi
  rm -rf "$work"
}
trap cleanup EXIT
fail() { echo "FAILED: $*" >&2; exit 1; }
# Prints a command (to stderr, so its output can be captured) and runs it.
show() { { printf '$'; printf ' %q' "$@"; echo; } >&2; "$@"; }

url=${PAPERNET_URL:-}
if [ -z "$url" ]; then
  [ -n "${PAPERNET_BIN:-}" ] || fail "set PAPERNET_URL to a running server or PAPERNET_BIN to the binary"
  # The file exists before the server starts: the loop below may read it before the shell that
  # starts the server has opened it for its output.
  : >"$work/server.out"
  "$PAPERNET_BIN" serve --host 127.0.0.1 --port 0 --data "$work/var" --access-log false >"$work/server.out" 2>&1 &
  server_pid=$!
  for _ in $(seq 100); do
    url=$(sed -n 's/^papernet listening on \(http:[^ ]*\).*/\1/p' "$work/server.out" | head -1)
    [ -n "$url" ] && break
    kill -0 "$server_pid" 2>/dev/null || fail "papernet serve exited: $(cat "$work/server.out")"
    sleep 0.1
  done
  [ -n "$url" ] || fail "papernet serve did not say where it listens: $(cat "$work/server.out")"
fi
cd "$work"

# Is it up?
show curl -fsS "$url/readyz"; echo

# 1. Submit: the mesh as the body, its format as Content-Type, options as query parameters.
#    202 Accepted, the job as JSON and its address in Location.
show curl -sS -D headers.txt -o job.json -w '%{http_code}\n' \
  -H 'Content-Type: model/obj' --data-binary "@$mesh" \
  "$url/v1/jobs?strategy=TU&size_mm=120&paper=A4&title=Kitchen%20Duck" | tee code.txt
[ "$(cat code.txt)" = 202 ] || fail "submit answered $(cat code.txt): $(cat job.json)"
id=$(sed -n 's/.*"id":"\([0-9a-f]\{32\}\)".*/\1/p' job.json)
[ -n "$id" ] || fail "no job id in $(cat job.json)"
grep -qi "^location: /v1/jobs/$id" headers.txt || fail "no Location header: $(cat headers.txt)"
echo "job $id"

# 2. Follow it: the Server-Sent Events stream ends with `event: done` (curl -N: unbuffered).
show curl -fsS -N --max-time 120 "$url/v1/jobs/$id/events" >events.txt
grep -q '^event: done' events.txt || fail "the event stream did not end with done: $(tail -3 events.txt)"
echo "$(grep -c '^event: ' events.txt) events, the last: $(grep '^event: ' events.txt | tail -1)"

# ... or poll until the status is final.
status=
for _ in $(seq 240); do
  curl -fsS "$url/v1/jobs/$id" >status.json
  status=$(sed -n 's/.*"status":"\([a-z]*\)".*/\1/p' status.json)
  case "$status" in succeeded | approximated | failed | cancelled) break ;; esac
  sleep 0.5
done
printf '$ curl -fsS %s   # until the status is final\nstatus: %s\n' "$url/v1/jobs/$id" "$status"
case "$status" in succeeded | approximated) ;; *) fail "job ended $status: $(cat status.json)" ;; esac

# 3. Fetch the results: the net as JSON, print-ready SVG and PDF, and the folded mesh as GLB.
show curl -fsS -D level.txt -o net.json "$url/v1/jobs/$id/net.json"
grep -i '^x-papernet-level:' level.txt || fail "no X-Papernet-Level header"
show curl -fsS -o net.svg "$url/v1/jobs/$id/net.svg"
show curl -fsS -o net.pdf "$url/v1/jobs/$id/net.pdf"
show curl -fsS -o mesh.glb "$url/v1/jobs/$id/mesh.glb"
grep -q '"format":"papernet.net/2"' net.json || fail "net.json is not papernet.net/2"
grep -q '<svg' net.svg || fail "net.svg is no SVG"
[ "$(head -c 5 net.pdf)" = "%PDF-" ] || fail "net.pdf is no PDF"
[ "$(head -c 4 mesh.glb)" = "glTF" ] || fail "mesh.glb is no GLB"
ls -l net.json net.svg net.pdf mesh.glb
# Saved under the name the server gives (Content-Disposition: the kit's title, a page's number
# and .svg, which the page's URL lacks):
show curl -fsS -OJ "$url/v1/jobs/$id/pages/1"
[ -f "Kitchen Duck - page 1.svg" ] || fail "pages/1 was not saved as 'Kitchen Duck - page 1.svg': $(ls)"
grep -q '<title>Kitchen Duck · page 1 of ' "Kitchen Duck - page 1.svg" || fail "page 1 has no title"

# 4. Errors are problem documents with a stable code.
show curl -sS -o problem.json -w '%{http_code}\n' -H 'Content-Type: model/obj' \
  --data-binary "@$mesh" "$url/v1/jobs?color=red" | tee code.txt
cat problem.json; echo
[ "$(cat code.txt)" = 400 ] || fail "an unknown option answered $(cat code.txt)"
grep -q '"code":"unknown_option"' problem.json || fail "no unknown_option code"

# 5. Cancelling a finished job is refused (409 job_finished).
show curl -sS -o problem.json -w '%{http_code}\n' -X DELETE "$url/v1/jobs/$id" | tee code.txt
[ "$(cat code.txt)" = 409 ] || fail "cancelling a finished job answered $(cat code.txt)"
# 6. A .gltf with its buffer file, options as a JSON part (multipart/form-data).
show curl -sS -o job2.json -w '%{http_code}\n' -F "mesh=@$data/gltf_external/Box.gltf" -F "buffers=@$data/gltf_external/Box0.bin" \
  -F 'options={"strategy":"TU","seed":5};type=application/json' "$url/v1/jobs" | tee code.txt
[ "$(cat code.txt)" = 202 ] || fail "multipart submit answered $(cat code.txt): $(cat job2.json)"
id2=$(sed -n 's/.*"id":"\([0-9a-f]\{32\}\)".*/\1/p' job2.json)
show curl -fsS -N --max-time 120 "$url/v1/jobs/$id2/events" | grep -A1 '^event: done' | tail -1 >done.txt
grep -q '"status":"succeeded"' done.txt || fail "the .gltf job did not succeed: $(cat done.txt)"
echo "job $id2 succeeded"

# 7. Recent jobs and the Prometheus metrics.
# (Each answer goes to a file first: grep stops reading at its first match, and under pipefail a
# curl still writing into the closed pipe would fail the step.)
show curl -fsS -o jobs.json "$url/v1/jobs?limit=10"
grep -q "$id2" jobs.json || fail "the job list lacks $id2"
show curl -fsS -o metrics.txt "$url/metrics"
grep -m1 '^papernet_' metrics.txt || fail "no papernet_ metrics"
echo "curl session OK"
