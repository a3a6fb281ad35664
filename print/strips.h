#pragma once

#include <array>
#include <string>
#include <utility>
#include <vector>

#include "print/tabs.h"

namespace papernet {

/// A glue strip: a separate rectangle printed in free space, for a cut edge that has no room
/// for a tab in place. Cut it out, glue one half under each side of the edge (the seam line
/// down its middle goes where the two sides meet); both halves carry the edge's number.
/// `corners` are counter-clockwise; corners[0] -> corners[1] is one long side, and the seam runs
/// from the middle of corners[3]-corners[0] to the middle of corners[1]-corners[2].
struct GlueStrip {
  int edge = -1;  ///< index into the edge list
  std::array<Vec2, 4> corners;
  std::string text;      ///< the edge's label, printed on both halves ("" for none)
  double text_size = 0;  ///< its height in layout units
};

struct StripOptions {
  double max_half_width = 6;  ///< glue width on each side of the seam, at most
  double min_half_width = 2;  ///< ... and at least; half the edge's length in between
  double min_length = 4;      ///< strips of shorter edges are this long
  double gap = 1;             ///< free paper kept around a strip so it can be cut out
  double cell = 2;            ///< resolution of the free-space search
  double search_radius = 30;  ///< how far from its edge a strip is looked for first
  double hug = 3;  ///< ... where it stays this close to the net (beyond its own half size)
  std::vector<std::pair<Vec2, Vec2>> within;  ///< boxes (lo, hi) strips must lie in, if any
  /// With `within`: a strip with no room near its edge takes the free place nearest its edge
  /// anywhere in the box that holds the edge (a sheet of a fit layout, which prints anyway),
  /// largest strips first, before the scan from the top left.
  bool nearest_in_box = false;
};

/// One strip to place: for `edge`, `length` x `width`, as near `near` as it can go.
struct StripRequest {
  int edge = -1;
  double length = 0, width = 0;
  Vec2 near;
};

/// The strips for the edges in `which` (indices into `edges`, cut edges of the net): as long as
/// the edge (at least min_length), twice half its length wide (within min/max_half_width), near
/// the middle of its side a.
std::vector<StripRequest> strip_requests(const std::vector<std::array<Vec2, 3>>& faces,
                                         const std::vector<NetEdge>& edges,
                                         const std::vector<int>& which,
                                         const StripOptions& options = {});

/// Places every requested strip where it overlaps neither a face, a tab, one of `others` nor
/// another strip, keeping `gap` of free paper around it: in the free window of the bounding box
/// of faces, tabs and `others` nearest `near` (within `search_radius`, lying or standing) that
/// hugs the net (so that it prints on a page the net needs anyway), else (nearest_in_box) the
/// nearest free window in the edge's box, else in the first free window of the box (scanning
/// from the top left), else in rows below the box. With
/// `options.within` set, windows inside the box must also lie inside one of those boxes.
/// Checked geometrically with convex_overlap, never by the raster alone.
std::vector<GlueStrip> place_strips(const std::vector<std::array<Vec2, 3>>& faces,
                                    const std::vector<Tab>& tabs,
                                    const std::vector<StripRequest>& requests,
                                    const std::vector<GlueStrip>& others = {},
                                    const StripOptions& options = {});

/// Where a strip's seam runs and where its two labels go: centre of each half, with the
/// direction of the seam in radians.
struct StripMarks {
  Vec2 seam0, seam1;
  std::array<Vec2, 2> label_at;
  double angle = 0;
  double half_width = 0;
};
StripMarks strip_marks(const GlueStrip& strip);

}  // namespace papernet
