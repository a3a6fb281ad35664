#pragma once

#include <cstddef>
#include <optional>
#include <string>
#include <string_view>

#include <nlohmann/json.hpp>

#include "core/mesh/mesh.h"
#include "core/unfold/net.h"

namespace papernet {

/// The `input` object of a net document: what was handed in, after welding.
struct NetInput {
  std::size_t vertices = 0, faces = 0;
  int genus = 0;
  std::size_t boundaries = 0;
};

/// The `metrics` object. coverage and aspect_ratio are written as null while unknown.
struct NetMetrics {
  std::size_t faces = 0;
  std::optional<double> coverage, aspect_ratio;
  double hausdorff = 0;
  std::size_t overlaps = 0;
  double seconds = 0;
};

/// A `papernet.net/1` document (README.md "The net"): the net and the mesh it folds into.
struct NetDocument {
  std::string result = "complete";  ///< "complete" or "approximate"
  std::string strategy;             ///< "AUTO", "TU", "QQ", "SEMP", "SEQ"
  NetInput input;
  Mesh mesh;
  Net net;
  NetMetrics metrics;
  /// An overlap-free net of a coarser mesh handed out while the job still runs: the JSON then
  /// carries `level` (kind "intermediate", its faces and the input's).
  bool intermediate = false;
};

/// The document as JSON, fields exactly as README.md "The net" names them.
nlohmann::json net_to_json(const NetDocument& doc);

/// Serialised document; `indent` < 0 writes one line.
std::string write_net_json(const NetDocument& doc, int indent = -1);

/// Parses a `papernet.net/1` document.
/// \throw IOException naming the fault (not JSON, wrong format tag, missing or mistyped field,
///        sizes that do not match).
NetDocument read_net_json(std::string_view text);

}  // namespace papernet
