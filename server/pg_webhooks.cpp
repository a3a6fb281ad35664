// The PostgreSQL store's callback deliveries (JobStore::webhook, claim_webhook,
// update_webhook): several nodes claim due deliveries as they claim jobs, one node each.
#include "core/io/json_text.h"
#include "server/pg_store.h"

namespace papernet::server {
namespace {

using pg::Connection;
using pg::Params;
using pg::Result;

constexpr const char* kDeliveryColumns = "job_id, url, state, attempts, next_at";

WebhookDelivery read_delivery(const Result& r) {
  WebhookDelivery d;
  d.job_id = r.text(0, 0);
  d.url = r.text(0, 1);
  d.state = r.text(0, 2);
  d.attempts = nlohmann::json::parse(r.text(0, 3));
  d.next_at = r.real(0, 4);
  return d;
}

}  // namespace

std::optional<WebhookDelivery> PgJobStore::webhook(const std::string& id) {
  std::optional<WebhookDelivery> out;
  pool_.run([&](Connection& c) {
    Result r =
        c.exec(std::string("SELECT ") + kDeliveryColumns + " FROM webhooks WHERE job_id = $1",
               Params().text(id));
    if (r.rows() > 0) out = read_delivery(r);
  });
  return out;
}

std::optional<WebhookDelivery> PgJobStore::claim_webhook(const std::string& node, double now,
                                                         double lease_seconds) {
  std::optional<WebhookDelivery> out;
  pool_.run([&](Connection& c) {
    // As claim(): the row is locked from the SELECT to the UPDATE; one held by another node's
    // statement is skipped.
    Result r = c.exec(
        std::string("WITH next AS (SELECT w.job_id FROM webhooks w JOIN jobs j ON j.id = w.job_id "
                    "WHERE w.state = 'pending' AND w.next_at <= $2::float8 AND w.lease_until <= "
                    "$2::float8 AND j.status IN ('succeeded', 'approximated', 'failed', "
                    "'cancelled') ORDER BY w.next_at LIMIT 1 FOR UPDATE OF w SKIP LOCKED) "
                    "UPDATE webhooks SET claimed_by = $1, lease_until = $2::float8 + $3::float8 "
                    "FROM next WHERE webhooks.job_id = next.job_id RETURNING ") +
            "webhooks.job_id, url, state, attempts, next_at",
        Params().text(node).number(now).number(lease_seconds));
    out.reset();
    if (r.rows() > 0) out = read_delivery(r);
  });
  return out;
}

bool PgJobStore::update_webhook(const WebhookDelivery& d, const std::string& node) {
  bool held = false;
  pool_.run([&](Connection& c) {
    held = c.exec(
                "UPDATE webhooks SET state = $1, attempts = $2, next_at = $3::float8, "
                "claimed_by = '', lease_until = 0 WHERE job_id = $4 AND claimed_by = $5 "
                "RETURNING job_id",
                Params()
                    .text(d.state)
                    .text(json_text(d.attempts))
                    .number(d.next_at)
                    .text(d.job_id)
                    .text(node))
               .rows() > 0;
  });
  return held;
}

}  // namespace papernet::server
