#!/usr/bin/env bash
# PostgreSQL for the papernet nodes of docker/compose.yaml, and for docker/check-cluster.sh, which
# runs it the same way on loopback. On first start (PGDATA empty): initdb, a login "papernet"
# with the password POSTGRES_PASSWORD owning the database "papernet", scram-sha-256 for every
# network connection. Then PostgreSQL runs in the foreground as the postgres system user.
#   POSTGRES_PASSWORD (required), PGDATA (/var/lib/papernet-postgres),
#   PGLISTEN (listen_addresses, default *), PGPORT (5432)
set -euo pipefail
data=${PGDATA:-/var/lib/papernet-postgres}
password=${POSTGRES_PASSWORD:?POSTGRES_PASSWORD must be set}
listen=${PGLISTEN:-*}
port=${PGPORT:-5432}
bindir=$(ls -d /usr/lib/postgresql/*/bin | sort -V | tail -1)
as_postgres=()
if [ "$(id -u)" -eq 0 ]; then as_postgres=(runuser -u postgres --); fi

mkdir -p "$data"
[ ${#as_postgres[@]} -eq 0 ] || chown postgres:postgres "$data"
chmod 700 "$data"
if [ ! -f "$data/PG_VERSION" ]; then
  "${as_postgres[@]}" "$bindir/initdb" -D "$data" -U postgres -E UTF8 --auth-local=peer \
    --auth-host=scram-sha-256 --no-instructions >/dev/null
  echo "host all all all scram-sha-256" | "${as_postgres[@]}" tee -a "$data/pg_hba.conf" >/dev/null
  # The login and its database, over the socket only, before anything listens on the network.
  "${as_postgres[@]}" "$bindir/pg_ctl" -D "$data" -w -o "-c listen_addresses='' -c port=$port \
    -c unix_socket_directories='$data'" start >/dev/null
  escaped=${password//\'/\'\'}
  "${as_postgres[@]}" "$bindir/psql" -q -X -v ON_ERROR_STOP=1 -h "$data" -p "$port" -U postgres \
    -d postgres -c "CREATE ROLE papernet LOGIN PASSWORD '$escaped'" \
    -c "CREATE DATABASE papernet OWNER papernet" >/dev/null
  "${as_postgres[@]}" "$bindir/pg_ctl" -D "$data" -w -m fast stop >/dev/null
fi
exec "${as_postgres[@]}" "$bindir/postgres" -D "$data" -c listen_addresses="$listen" \
  -c port="$port" -c unix_socket_directories="$data"
