#pragma once

#include <cstddef>
#include <string>
#include <string_view>
#include <vector>

#include "core/mesh/mesh.h"
#include "core/unfold/net.h"
#include "print/layout.h"
#include "print/pages.h"

namespace papernet {

/// Everything the print writers need, as the command line and the service fill it.
struct OutputOptions {
  PrintOptions print;
  PageOptions page;
  bool paper = true;  ///< false: one SVG sized to the net (PDF always uses paper)
};

/// What write_output_file wrote.
struct WrittenOutput {
  std::vector<std::string> files;
  int pages = 0;  ///< printed pages (SVG/PDF), 0 for meshes
  std::size_t tabs = 0, strips = 0, tabs_omitted = 0;
};

/// Writes one output file, the format chosen by the extension of `path` (case-insensitive):
/// `.svg` (one page when it fits or no paper; else `<stem>-1.svg`, `<stem>-2.svg`, ... one per
/// page), `.pdf` (one page per tile), `.glb` / `.obj` (the mesh the net folds into).
/// `.json` is the net JSON writer's job, not this function's.
/// \throw InvalidInputException for an unknown extension or invalid options,
///        IOException when a file cannot be written.
WrittenOutput write_output_file(const std::string& path, const Mesh& mesh, const Net& net,
                                const OutputOptions& options);

/// Applies one command-line option of the print writers to `options`; every one takes a value:
/// --size 200mm | --scale 2 | --paper A4|A3|Letter|WxHmm|none | --margin 10mm |
/// --overlap 10mm | --tabs auto|strips|none | --tab-height 6mm (0: no tabs) |
/// --min-tab-height 2mm | --tab-room on|off | --flat-angle 1 (degrees) |
/// --labels on|off. Returns false when `name` is not one of them.
/// \throw InvalidInputException naming the option when its value is bad.
bool apply_output_option(std::string_view name, std::string_view value, OutputOptions& options);

/// One line per option of apply_output_option, for --help.
std::string output_options_help();

/// True when write_output_file knows the extension of `path`.
bool is_print_output(const std::string& path);

}  // namespace papernet
