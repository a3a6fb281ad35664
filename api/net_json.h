#pragma once

#include <cstddef>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include <nlohmann/json.hpp>

#include "core/mesh/colour.h"
#include "core/mesh/mesh.h"
#include "core/unfold/net.h"
#include "print/placements.h"

namespace papernet {

/// The `input` object of a net document: what was handed in, after repair.
struct NetInput {
  std::size_t vertices = 0, faces = 0;
  std::size_t components = 1;  ///< connected parts
  int genus = 0;               ///< summed over the parts
  std::size_t boundaries = 0;  ///< boundary loops, summed over the parts
};

/// One entry of `repairs`: a kind of repair made to the input (core/mesh/repair.h), or a note
/// of what loading skipped or what `components=largest` dropped.
struct NetRepair {
  std::string code;
  std::size_t count = 0;
  std::string message;
};

/// One entry of `pieces`: a part of the input unfolded on its own into one piece, or, printed
/// with layout fit, a piece cut out of one so that it fits a sheet (it inherits the part's
/// result and hausdorff).
struct NetPiece {
  std::size_t component = 0;        ///< which part of the input (largest first)
  std::string result = "complete";  ///< "complete" or "approximate"
  std::size_t faces = 0;            ///< faces of this piece
  double hausdorff = 0;             ///< an approximation's distance to its part
};

/// The `metrics` object. coverage and aspect_ratio are written as null while unknown.
struct NetMetrics {
  std::size_t faces = 0;
  std::optional<double> coverage, aspect_ratio;
  double hausdorff = 0;  ///< the largest of the pieces'
  std::size_t overlaps = 0;
  double seconds = 0;
};

/// The `print` object: how the pieces lie on the printed sheets (README.md "The net").
struct NetPrint {
  std::string paper;  ///< a name of named_papers() (print/pages.h) or "WxHmm"
  double page_width_mm = 0, page_height_mm = 0;  ///< the page as printed (landscape when tiled so)
  double margin_mm = 0;                          ///< unprinted border on each side of a page
  double mm_per_unit = 1;                        ///< the print's scale
  int pages = 0;
  std::string layout;                      ///< "fit" or "tile"
  std::string title;                       ///< the option `title`; written when there is one
  std::vector<PiecePlacement> placements;  ///< one per piece of `pieces`
  std::vector<PageWindow> tiles;           ///< layout tile: what each page shows of the grid
  /// The overview page (0-based; docs/print.md "The overview page"), -1 without one; written
  /// only when there is one.
  int overview_page = -1;
  /// The overview's pages, from overview_page on: 1, or more for a print of many sheets and
  /// pieces; 0 without an overview (written with overview_page).
  int overview_pages = 0;
};

/// A `papernet.net/2` document (README.md "The net"): the pieces and the mesh they fold into.
/// `net.points[i]` and `piece[i]` belong to `mesh.faces[i]`; each piece's faces form one tree
/// (its root's parent is -1) in the piece's own 2D frame.
/// The detail the net was made at (JobOptions::detail): "auto", "full" or "faces", and the faces
/// it folds into.
struct NetDetail {
  std::string mode = "full";
  std::size_t faces = 0;
};

struct NetDocument {
  std::string result = "complete";  ///< "approximate" when any piece is
  std::string strategy;             ///< "AUTO", "TU", "QQ", "SEMP", "SEQ"
  NetInput input;
  std::vector<NetRepair> repairs;
  NetDetail detail;
  /// What a user should know before printing the result (code, count, message as repairs):
  /// "detail_unbuildable", "small_parts_left_out", "texture_not_printed", ...
  std::vector<NetRepair> warnings;
  Mesh mesh;
  /// The mesh's colour (docs/colour.md): `mesh.uvs`, `mesh.colors`, `mesh.face_materials`,
  /// `materials` and `textures` in the JSON, present when the input has colour. The textures'
  /// bytes are not written into the document (they are served beside it).
  MeshColour colour;
  Net net;
  std::vector<int> piece;  ///< the piece of each face
  std::vector<NetPiece> pieces;
  NetMetrics metrics;
  /// The sheets, when the run printed on paper; `piece`, `net.parent` and `pieces` are then the
  /// pieces as printed (cut to fit a sheet with layout fit).
  std::optional<NetPrint> print;
  /// An overlap-free net of a coarser mesh handed out while the job still runs: the JSON then
  /// carries `level` (kind "intermediate", its faces and the input's).
  bool intermediate = false;
};

/// The document as JSON, fields exactly as README.md "The net" names them.
nlohmann::json net_to_json(const NetDocument& doc);

/// Serialised document; `indent` < 0 writes one line.
std::string write_net_json(const NetDocument& doc, int indent = -1);

/// Parses a `papernet.net/2` document.
/// \throw IOException naming the fault (not JSON, wrong format tag, missing or mistyped field,
///        sizes that do not match).
NetDocument read_net_json(std::string_view text);

}  // namespace papernet
