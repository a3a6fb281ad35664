#pragma once

#include "server/config.h"

namespace papernet::server {

/// Runs the job service with `config` until SIGINT or SIGTERM: opens the store under
/// `config.data_dir`, starts the workers, listens, then drains and stops. Returns the process
/// exit code (1 when the store cannot be opened or the address cannot be bound, 2 for a bad
/// web root).
int run_service(const ServerConfig& config);

}  // namespace papernet::server
