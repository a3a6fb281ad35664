// The SQLite store's callback deliveries (JobStore::webhook, claim_webhook, update_webhook).
#include "core/io/json_text.h"
#include "server/internal/sqlite_statement.h"
#include "server/sqlite_store.h"

namespace papernet::server {
namespace {

using sqlite::Statement;
using sqlite::Transaction;

constexpr const char* kDeliveryColumns = "job_id, url, state, attempts, next_at";

WebhookDelivery read_delivery(const Statement& s) {
  WebhookDelivery d;
  d.job_id = s.text(0);
  d.url = s.text(1);
  d.state = s.text(2);
  d.attempts = nlohmann::json::parse(s.text(3));
  d.next_at = s.real(4);
  return d;
}

}  // namespace

std::optional<WebhookDelivery> SqliteJobStore::webhook(const std::string& id) {
  std::lock_guard lock(mutex_);
  Statement s(db_, std::string("SELECT ") + kDeliveryColumns + " FROM webhooks WHERE job_id=?");
  s.bind(1, id);
  if (!s.step()) return std::nullopt;
  return read_delivery(s);
}

std::optional<WebhookDelivery> SqliteJobStore::claim_webhook(const std::string& node, double now,
                                                             double lease_seconds) {
  std::lock_guard lock(mutex_);
  Transaction tx(db_);
  std::optional<WebhookDelivery> out;
  {
    Statement s(db_, std::string("SELECT ") + kDeliveryColumns +
                         " FROM webhooks WHERE state='pending' AND next_at<=? AND lease_until<=? "
                         "AND job_id IN (SELECT id FROM jobs WHERE status IN ('succeeded', "
                         "'approximated', 'failed', 'cancelled')) ORDER BY next_at LIMIT 1");
    s.bind(1, now).bind(2, now);
    if (!s.step()) return std::nullopt;
    out = read_delivery(s);
  }
  Statement(db_, "UPDATE webhooks SET claimed_by=?, lease_until=? WHERE job_id=?")
      .bind(1, node)
      .bind(2, now + lease_seconds)
      .bind(3, out->job_id)
      .run();
  tx.commit();
  return out;
}

bool SqliteJobStore::update_webhook(const WebhookDelivery& d, const std::string& node) {
  std::lock_guard lock(mutex_);
  return Statement(db_,
                   "UPDATE webhooks SET state=?, attempts=?, next_at=?, claimed_by='', "
                   "lease_until=0 WHERE job_id=? AND claimed_by=?")
             .bind(1, d.state)
             .bind(2, json_text(d.attempts))
             .bind(3, d.next_at)
             .bind(4, d.job_id)
             .bind(5, node)
             .run() > 0;
}

}  // namespace papernet::server
