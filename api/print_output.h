#pragma once

#include <string>
#include <vector>

#include "api/pages.h"
#include "api/print_layout.h"
#include "core/mesh.h"
#include "core/net.h"

namespace papernet {

/// Everything the print writers need, as the command line and the service fill it.
struct OutputOptions {
  PrintOptions print;
  PageOptions page;
  bool paper = true;  ///< false: one SVG sized to the net (PDF always uses paper)
};

/// Writes one output file, the format chosen by the extension of `path` (case-insensitive):
/// `.svg` (one page when it fits or no paper; else `<stem>-1.svg`, `<stem>-2.svg`, ... one per
/// page), `.pdf` (one page per tile), `.glb` / `.obj` (the mesh the net folds into).
/// `.json` is the net JSON writer's job, not this function's. Returns the files written.
/// \throw InvalidInputException for an unknown extension or invalid options,
///        IOException when a file cannot be written.
std::vector<std::string> write_output_file(const std::string& path, const Mesh& mesh,
                                           const Net& net, const OutputOptions& options);

/// True when write_output_file knows the extension of `path`.
bool is_print_output(const std::string& path);

}  // namespace papernet
