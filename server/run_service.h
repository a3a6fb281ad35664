#pragma once

#include "server/config.h"

namespace papernet::server {

/// Runs the job service with `config` until SIGINT or SIGTERM: opens the store (SQLite under
/// `config.data_dir`, or PostgreSQL), starts the workers, listens, then drains and stops.
/// Returns the process exit code (1 when the store cannot be opened, reached or migrated, or
/// the address cannot be bound; 2 for a bad web root).
int run_service(const ServerConfig& config);

}  // namespace papernet::server
