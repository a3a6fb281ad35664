#!/usr/bin/env bash
# A throwaway PostgreSQL server from Debian's postgresql package, for the tests (ctest's
# "postgres" fixture and the tests that restart a server of their own), the store benchmark and
# docker/check-steps.sh. It lives in DIR: initdb into DIR/data, a Unix socket in DIR/socket,
# and with PORT also TCP on 127.0.0.1:PORT. It runs as an unprivileged user (PostgreSQL refuses
# root, and CI runs as root): the system user papernet-pg, created when missing.
#
#   scripts/test-postgres.sh start DIR [PORT]   prints the superuser's URL (also in DIR/url)
#   scripts/test-postgres.sh stop|restart DIR
#   scripts/test-postgres.sh destroy DIR        stops the server and removes DIR
#
# Logins: postgres (the superuser, no password), and papernet_login with the password
# "papernet" (scram-sha-256: tests of a wrong password). The server trades durability for
# speed (fsync off) unless PG_DURABLE=1. Exit code 77 (ctest: skipped) when the PostgreSQL
# binaries are missing: install them with scripts/install-deps.sh.
set -euo pipefail
command=${1:-}
dir=${2:-}
port=${3:-}
[ -n "$command" ] && [ -n "$dir" ] || {
  echo "usage: $0 start|stop|restart|destroy DIR [PORT]" >&2
  exit 2
}

bindir=${PAPERNET_PG_BINDIR:-$(ls -d /usr/lib/postgresql/*/bin 2>/dev/null | sort -V | tail -1)}
if [ -z "$bindir" ] || [ ! -x "$bindir/initdb" ]; then
  echo "PostgreSQL binaries not found (no /usr/lib/postgresql/*/bin/initdb): install Debian's" \
    "postgresql package (scripts/install-deps.sh does)" >&2
  exit 77
fi

as_owner=()
if [ "$(id -u)" -eq 0 ]; then
  id papernet-pg >/dev/null 2>&1 ||
    useradd --system --user-group --no-create-home --shell /usr/sbin/nologin papernet-pg
  as_owner=(runuser -u papernet-pg --)
fi
data=$dir/data
socket=$dir/socket
ctl() { "${as_owner[@]}" "$bindir/pg_ctl" -D "$data" -l "$dir/server.log" -w -t 60 "$@"; }

case "$command" in
  start)
    mkdir -p "$dir"
    if [ ! -f "$data/PG_VERSION" ]; then
      mkdir -p "$socket"
      [ ${#as_owner[@]} -eq 0 ] || chown papernet-pg:papernet-pg "$dir" "$socket"
      chmod 755 "$dir" "$socket"
      "${as_owner[@]}" "$bindir/initdb" -D "$data" -U postgres -A trust -E UTF8 --no-sync \
        --no-instructions >"$dir/initdb.log" 2>&1 ||
        { cat "$dir/initdb.log" >&2; exit 1; }
      {
        echo "local all papernet_login scram-sha-256"
        echo "host all papernet_login 127.0.0.1/32 scram-sha-256"
        echo "local all all trust"
        echo "host all all 127.0.0.1/32 trust"
      } | "${as_owner[@]}" tee "$data/pg_hba.conf" >/dev/null
      {
        echo "unix_socket_directories = '$socket'"
        echo "listen_addresses = '${port:+127.0.0.1}'"
        echo "port = ${port:-5432}"
        echo "max_connections = 300"
        echo "shared_buffers = 32MB"
        if [ "${PG_DURABLE:-0}" != 1 ]; then
          echo "fsync = off"
          echo "synchronous_commit = off"
          echo "full_page_writes = off"
        fi
      } | "${as_owner[@]}" tee -a "$data/postgresql.conf" >/dev/null
      fresh=1
    fi
    # Started already (a run that did not stop it): use it as it is.
    if ! "${as_owner[@]}" "$bindir/pg_ctl" -D "$data" status >/dev/null 2>&1; then
      ctl start >/dev/null || { cat "$dir/server.log" >&2; exit 1; }
    fi
    port=$(sed -n 's/^port = //p' "$data/postgresql.conf" | tail -1)
    url="postgresql://postgres@/postgres?host=$socket&port=$port"
    if [ "${fresh:-0}" = 1 ]; then
      "$bindir/psql" -q -X -v ON_ERROR_STOP=1 "$url" \
        -c "CREATE ROLE papernet_login LOGIN SUPERUSER PASSWORD 'papernet'" >/dev/null
    fi
    echo "$url" >"$dir/url"
    echo "$url"
    ;;
  stop) ctl -m fast stop >/dev/null ;;
  restart) ctl -m fast restart >/dev/null ;;
  destroy)
    if [ -f "$data/postmaster.pid" ]; then ctl -m immediate stop >/dev/null 2>&1 || true; fi
    rm -rf "$dir"
    ;;
  *)
    echo "usage: $0 start|stop|restart|destroy DIR [PORT]" >&2
    exit 2
    ;;
esac
