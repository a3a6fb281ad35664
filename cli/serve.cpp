// `papernet serve`: the command line's part of the service is its configuration; the service
// itself is server/run_service.h.
#include <iostream>

#include "cli/commands.h"
#include "server/config.h"
#include "server/run_service.h"

namespace papernet::cli {

int serve(int argc, char** argv) {
  std::optional<server::ServerConfig> config;
  try {
    config = server::parse_serve_config(argc, argv);
  } catch (const server::ConfigError& e) {
    std::cerr << "papernet serve: " << e.what() << "\n";
    return 2;
  }
  if (!config) {
    std::cout << server::serve_usage();
    return 0;
  }
  return server::run_service(*config);
}

}  // namespace papernet::cli
