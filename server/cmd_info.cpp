// `papernet info FILE`: first cut, counts only; validation comes with core/validate.
#include <exception>
#include <iostream>

#include "core/errors.h"
#include "core/load.h"
#include "server/commands.h"

namespace papernet::cli {

int info(int argc, char** argv) {
  if (argc != 2) {
    std::cerr << "usage: papernet info FILE\n";
    return 1;
  }
  try {
    const LoadedMesh loaded = load_mesh_file(argv[1]);
    std::cout << "format:   " << format_name(loaded.format) << "\n"
              << "vertices: " << loaded.mesh.vertices.size() << "\n"
              << "faces:    " << loaded.mesh.faces.size() << "\n";
    return 0;
  } catch (const IOException& e) {
    std::cerr << "papernet: " << argv[1] << ": " << e.what() << "\n";
    return 1;
  }
}

}  // namespace papernet::cli
