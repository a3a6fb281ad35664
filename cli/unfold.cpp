// `papernet unfold FILE -o OUT [-o OUT]... [options]`: argv into JobOptions and output paths,
// the engine's pipeline (engine/pipeline.h), then the files and what to tell the user.
#include <algorithm>
#include <cctype>
#include <cstdio>
#include <exception>
#include <fstream>
#include <iostream>
#include <optional>
#include <set>
#include <string>
#include <vector>

#include "cli/commands.h"
#include "cli/local_files.h"
#include "core/errors.h"
#include "engine/pipeline.h"
#include "print/layout.h"

namespace papernet::cli {
namespace {

constexpr const char* kUsageLine = "usage: papernet unfold FILE -o OUT [-o OUT]... [options]\n";
constexpr const char* kUsage =
    "FILE: glb, gltf, drc, obj, off, ply or stl (the files it names beside it are read too), or\n"
    "a folder that holds one such file.\n"
    "OUT is chosen by extension: .json (papernet.net/2), .svg (one page, or OUT-1.svg ... per\n"
    "page), .pdf (one page per sheet), .glb / .obj (the mesh the net folds into). Beside a\n"
    ".json: the model's textures, OUT.texture-K.png (or .jpg), K as in its \"textures\".\n"
    "Exit codes: 0 net written (also an approximate one: a net of a coarser mesh, and one in\n"
    "pieces where no net in one piece was found, each said on stderr and in the JSON), 2 input\n"
    "cannot be unfolded, 1 other errors. Prints one summary line (key=value) on stdout;\n"
    "grown=K counts the parts unfolded in pieces grown from single faces.\n"
    "Options (the service's names, README.md 'Options'; --name=value works too):\n";

// After a mistake in the command, below the usage line: where the rest is (the whole usage
// would scroll the message naming the mistake off the screen).
constexpr const char* kTryHelp = "papernet unfold --help lists every option\n";

// The command line's limits: those of the loader (core/io/load.h), and 60 s by default.
const PipelineLimits kLimits{std::size_t{256} << 20, 2'000'000, 60};

std::string extension(const std::string& path) {
  const auto dot = path.find_last_of('.'), slash = path.find_last_of('/');
  if (dot == std::string::npos || (slash != std::string::npos && dot < slash)) return {};
  std::string ext = path.substr(dot + 1);
  std::transform(ext.begin(), ext.end(), ext.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return ext;
}

// The parts that no net in one piece was found for: the warning "unfolded_in_pieces" counts them.
std::size_t grown_parts(const NetDocument& doc) {
  for (const NetRepair& w : doc.warnings)
    if (w.code == "unfolded_in_pieces") return w.count;
  return 0;
}

// An option's message with the option named as on the command line ("--detail").
std::string in_flags(const InvalidOptionException& e) {
  std::string message = e.what();
  if (const auto at = message.find("option '" + e.option() + "'");
      !e.option().empty() && at != std::string::npos)
    message.replace(at, e.option().size() + 9, option_flag(e.option()));
  return message;
}

struct Command {
  std::string file;
  std::vector<std::string> outputs;
  JobOptions options;
};

// Parses argv. Returns nothing after --help. \throw std::exception with a message for the user.
std::optional<Command> parse(int argc, char** argv) {
  Command c;
  for (int i = 1; i < argc; ++i) {
    std::string arg = argv[i];
    std::optional<std::string> value;
    if (arg.starts_with("--") && arg.find('=') != std::string::npos) {
      value = arg.substr(arg.find('=') + 1);
      arg.resize(arg.find('='));
    }
    const auto next = [&]() -> std::string {
      if (value) return *value;
      if (i + 1 >= argc) throw std::invalid_argument(arg + " needs a value");
      return argv[++i];
    };
    if (arg == "--help" || arg == "-h") return std::nullopt;
    if (arg == "-o" || arg == "--output") {
      c.outputs.push_back(next());
      const std::string ext = extension(c.outputs.back());
      if (ext != "json" && ext != "svg" && ext != "pdf" && ext != "glb" && ext != "obj")
        throw std::invalid_argument("unknown output type '" + c.outputs.back() +
                                    "': use .json, .svg, .pdf, .glb or .obj");
    } else if (is_boolean_flag(arg)) {
      // A yes/no option alone means yes; a yes/no word after it is its value.
      if (!value && i + 1 < argc) {
        const std::string word = argv[i + 1];
        for (const char* w : {"true", "false", "yes", "no", "on", "off", "1", "0"})
          if (word == w) value = argv[++i];
      }
      apply_option_flag(c.options, arg, value);
    } else if (arg.starts_with("--")) {
      if (!apply_option_flag(c.options, arg, next()))
        throw std::invalid_argument("unknown option " + arg);
    } else if (!arg.empty() && arg[0] == '-') {
      throw std::invalid_argument("unknown option " + arg);
    } else if (c.file.empty()) {
      c.file = arg;
    } else {
      throw std::invalid_argument("more than one input file");
    }
  }
  if (c.file.empty()) throw std::invalid_argument("no input file");
  if (c.outputs.empty()) throw std::invalid_argument("no output (-o FILE)");
  validate_options(c.options, {1e9, kLimits.max_faces});
  if (c.options.callback_url)
    throw std::invalid_argument("--callback-url is an option of the service (papernet serve)");
  return c;
}

DocumentRequest documents_for(const std::vector<std::string>& outputs) {
  DocumentRequest r;
  for (const std::string& o : outputs) {
    const std::string ext = extension(o);
    r.svg_pages |= ext == "svg";
    r.pdf |= ext == "pdf";
    r.glb |= ext == "glb";
    r.obj |= ext == "obj";
  }
  return r;
}

void write_file(const std::string& path, const std::string& bytes) {
  std::ofstream out(path, std::ios::binary);
  out.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
  out.close();
  if (!out) throw IOException("cannot write " + path);
}

// Writes one output; returns the files written (an SVG of several pages is several files).
std::vector<std::string> write_output(const std::string& path, const UnfoldOutcome& outcome) {
  const std::string ext = extension(path);
  const Documents& d = outcome.documents;
  if (ext == "json") {
    write_file(path, d.net_json + "\n");
    // The textures beside it (docs/colour.md): OUT.json -> OUT.texture-K.png / .jpg.
    std::vector<std::string> files{path};
    const std::vector<Texture>& textures = outcome.net.colour.textures;
    for (std::size_t k = 0; k < textures.size(); ++k) {
      files.push_back(path.substr(0, path.size() - 5));
      files.back() += ".texture-";
      files.back() += std::to_string(k);
      files.back() += textures[k].mime_type == "image/jpeg" ? ".jpg" : ".png";
      write_file(files.back(), textures[k].bytes);
    }
    return files;
  } else if (ext == "pdf" || ext == "glb" || ext == "obj") {
    write_file(path, ext == "pdf" ? d.pdf : ext == "glb" ? d.glb : d.obj);
  } else if (d.svg_pages.size() == 1) {
    write_file(path, d.svg_pages.front());
  } else {
    std::vector<std::string> files;
    const std::string stem = path.substr(0, path.size() - 4);
    for (std::size_t i = 0; i < d.svg_pages.size(); ++i) {
      files.push_back(stem + "-" + std::to_string(i + 1) + ".svg");
      write_file(files.back(), d.svg_pages[i]);
    }
    return files;
  }
  return {path};
}

// What the pass that makes room for glue tabs did, and why edges stay without room.
void say_tab_room(const TabRoomSummary& room) {
  if (room.rejected)
    std::cerr << "papernet unfold: internal error, the net with tab room fails its check; "
                 "printing the unfolder's net\n";
  std::cerr << "papernet unfold: tab room: " << room.blocked_before << " -> " << room.blocked_after
            << " cut edges without room for a tab (" << room.moves << " moves, " << room.kicks
            << " kicks, " << room.evaluations << " evaluated, " << room.seconds << " s)\n";
  if (room.blocked_after > 0)
    std::cerr << "papernet unfold: tab room: " << room.leaves_without_room << " of the "
              << room.blocked_after << " end at a leaf of the cut tree where no leaf has room "
              << "(only " << room.leaf_room_vertices << " of " << room.interior_vertices
              << " vertices are sharp enough at this size); print larger (--size) or simplify "
                 "(--detail N faces, or --detail auto) for fewer glue strips\n";
}

}  // namespace

int unfold(int argc, char** argv) {
  std::optional<Command> c;
  try {
    c = parse(argc, argv);
  } catch (const InvalidOptionException& e) {
    std::cerr << "papernet unfold: " << in_flags(e) << "\n" << kUsageLine << kTryHelp;
    return 1;
  } catch (const std::exception& e) {
    std::cerr << "papernet unfold: " << e.what() << "\n" << kUsageLine << kTryHelp;
    return 1;
  }
  if (!c) {
    std::cout << kUsageLine << kUsage << options_help();
    return 0;
  }
  const std::string& file = c->file;
  UnfoldOutcome out;
  PipelineProgress quiet;
  try {
    out = run_pipeline(read_local_input(file, kLimits.max_bytes), c->options, kLimits,
                       documents_for(c->outputs), quiet);
  } catch (const InvalidOptionException& e) {
    std::cerr << "papernet unfold: " << in_flags(e) << "\n";
    return 1;
  } catch (const IOException& e) {
    std::cerr << "papernet unfold: " << file << ": " << e.what() << "\n";
    return 2;
  } catch (const InvalidInputException& e) {
    std::cerr << "papernet unfold: " << file << ": cannot be unfolded: " << e.what() << "\n";
    return 2;
  } catch (const std::logic_error& e) {
    std::cerr << "papernet unfold: internal error, " << e.what() << "\n";
    return 1;
  } catch (const std::exception& e) {
    std::cerr << "papernet unfold: " << file << ": " << e.what() << "\n";
    return 1;
  }
  const NetDocument& doc = out.net;
  for (const NetRepair& r : doc.repairs)
    std::cerr << "papernet unfold: " << file << ": "
              << (r.code == "skipped_on_load" || r.code == "dropped_components" ? "note"
                                                                                : "repaired")
              << ": " << r.message << "\n";
  for (const NetRepair& w : doc.warnings)
    std::cerr << "papernet unfold: " << file << ": warning: " << w.message << "\n";
  // Printed with layout fit, a part may be cut into several pieces: each names its part.
  std::set<std::size_t> parts;
  for (const NetPiece& p : doc.pieces) parts.insert(p.component);
  if (parts.size() > 1)
    std::cerr << "papernet unfold: " << file << ": " << parts.size()
              << " parts, each unfolded into a piece of its own\n";
  if (out.simplified && doc.mesh.faces.size() < doc.input.faces)
    std::cerr << "papernet unfold: " << file << ": simplified from " << doc.input.faces << " to "
              << doc.mesh.faces.size() << " faces\n";
  if (out.tab_room) say_tab_room(*out.tab_room);
  std::cout << "result=" << doc.result << " faces=" << doc.mesh.faces.size()
            << " input_faces=" << doc.input.faces << " hausdorff=" << doc.metrics.hausdorff
            << " overlaps=" << doc.metrics.overlaps << " iterations=" << out.iterations
            << " seconds=" << doc.metrics.seconds
            << " coverage=" << doc.metrics.coverage.value_or(0)
            << " aspect_ratio=" << doc.metrics.aspect_ratio.value_or(1)
            << " pieces=" << doc.pieces.size() << " repairs=" << doc.repairs.size()
            << " grown=" << grown_parts(doc) << " check=ok\n";
  if (doc.result == "approximate")
    std::cerr << "papernet unfold: " << file << ": approximate result: the net folds into a "
              << (doc.mesh.faces.size() < doc.input.faces
                      ? "coarser mesh of " + std::to_string(doc.mesh.faces.size()) + " of " +
                            std::to_string(doc.input.faces) + " faces"
                      : "mesh of " + std::to_string(doc.mesh.faces.size()) +
                            " faces, edges flipped from the input's " +
                            std::to_string(doc.input.faces))
              << ", Hausdorff distance " << doc.metrics.hausdorff
              << " of the bounding-box diagonal\n";
  for (const std::string& output : c->outputs) {
    try {
      for (const std::string& written : write_output(output, out))
        if (extension(output) != "json") std::cerr << "papernet unfold: wrote " << written << "\n";
    } catch (const std::exception& e) {
      std::cerr << "papernet unfold: " << output << ": " << e.what() << "\n";
      return 1;
    }
    const std::string ext = extension(output);
    if (out.print && (ext == "svg" || ext == "pdf")) {
      std::cerr << "papernet unfold: " << output << ": ";
      // Without paper the SVG is one drawing of the net (the PDF's pages are A4 tiles of it).
      if (ext == "svg" && !has_paper(c->options))
        std::cerr << "one drawing of the net (paper none)";
      else
        std::cerr << out.print->pages << " page(s) (" << out.print->layout
                  << (!out.print->overview ? ""
                      : out.print->overview_pages <= 1
                          ? ", page 1 an overview"
                          : ", pages 1 to " + std::to_string(out.print->overview_pages) +
                                " an overview")
                  << ")";
      std::cerr << ", " << out.print->pieces << " piece(s), " << out.print->tabs << " glue tabs, "
                << out.print->strips << " glue strips, " << out.print->tabs_omitted
                << " cut edges without glue, ";
      if (out.print->labels == 0) {
        std::cerr << "no edge labels\n";
      } else {
        const double smallest = out.print->smallest_label_mm;
        char mm[32];  // 1.50 mm, 0.05 mm, 4e-06 mm
        std::snprintf(mm, sizeof mm, smallest >= 0.01 ? "%.2f" : "%.2g", smallest);
        std::cerr << "smallest label " << mm << " mm (" << out.print->small_labels << " under "
                  << kLegibleLabelMm << " mm)\n";
      }
      if (!out.print->layout_note.empty())
        std::cerr << "papernet unfold: " << output << ": " << out.print->layout_note << "\n";
    }
  }
  return 0;
}

}  // namespace papernet::cli
