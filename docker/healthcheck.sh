#!/usr/bin/env bash
# Container health: GET /readyz answers 200. Uses bash's /dev/tcp, so the image needs no curl.
#   PAPERNET_HEALTH_HOST (default 127.0.0.1), PAPERNET_PORT (default 8080)
set -euo pipefail
host=${PAPERNET_HEALTH_HOST:-127.0.0.1}
port=${PAPERNET_PORT:-8080}
exec 3<>"/dev/tcp/$host/$port"
printf 'GET /readyz HTTP/1.0\r\nHost: %s\r\n\r\n' "$host" >&3
IFS= read -r -t 5 status <&3
exec 3<&-
case "$status" in
  "HTTP/1."[01]" 200 "*) exit 0 ;;
  *) echo "readyz: ${status:-no answer}" >&2; exit 1 ;;
esac
