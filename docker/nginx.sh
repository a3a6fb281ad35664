#!/usr/bin/env bash
# The load balancer in front of papernet nodes (docker/compose.yaml; docker/check-cluster.sh runs
# it the same way on loopback): nginx from Debian, round robin over PAPERNET_NODES. Any node
# answers for any job (they share one PostgreSQL store), so no stickiness is needed. Event
# streams are passed through unbuffered; uploads are buffered by nginx before they reach a node
# (slow clients then hold no papernet thread: docs/reliability.md).
#   PAPERNET_NODES ("host:port host:port ..."), PAPERNET_LISTEN (0.0.0.0:8080),
#   PAPERNET_MAX_BODY (65m: papernet's 64 MiB and the multipart framing)
set -euo pipefail
nodes=${PAPERNET_NODES:?PAPERNET_NODES must list the nodes, "host:port host:port"}
listen=${PAPERNET_LISTEN:-0.0.0.0:8080}
run=$(mktemp -d /tmp/papernet-nginx.XXXXXX)
chmod 755 "$run"  # nginx's workers (nobody, when it starts as root) keep temporary files here
servers=""
for node in $nodes; do servers+="    server $node max_fails=1 fail_timeout=5s;"$'\n'; done
cat >"$run/nginx.conf" <<CONF
worker_processes 1;
pid $run/nginx.pid;
error_log stderr warn;
events { worker_connections 1024; }
http {
  access_log off;
  client_body_temp_path $run/body;
  proxy_temp_path $run/proxy;
  fastcgi_temp_path $run/fastcgi;
  uwsgi_temp_path $run/uwsgi;
  scgi_temp_path $run/scgi;
  client_max_body_size ${PAPERNET_MAX_BODY:-65m};
  client_body_buffer_size 1m;
  upstream papernet {
$servers    keepalive 16;
  }
  server {
    listen $listen;
    proxy_http_version 1.1;
    proxy_set_header Connection "";
    proxy_set_header Host \$host;
    proxy_set_header X-Forwarded-For \$proxy_add_x_forwarded_for;
    # A node that is down or stopping: the request goes to the next one.
    proxy_next_upstream error timeout http_503;
    location / {
      proxy_pass http://papernet;
      proxy_read_timeout 300s;
    }
    location ~ ^/v1/jobs/[^/]+/events\$ {
      proxy_pass http://papernet;
      proxy_buffering off;
      proxy_read_timeout 1h;
    }
  }
}
CONF
exec nginx -c "$run/nginx.conf" -p "$run" -g "daemon off;"
