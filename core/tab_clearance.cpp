// Tab clearance: changes which edges of a net are cut so that cut edges get room for a glue tab.
//
// Why moves and not tab shapes: an edge without room is almost always a near-slit, a leaf of the
// cut tree at an almost flat vertex v (or an edge of a hair, a path of cut edges from such a
// leaf). The faces around v are then all linked but across that edge, so the edge's two sides
// meet at v at the angle defect of v (a few degrees) and no tab of printable height fits between
// them. Only cutting a second edge at v opens the slit. A move therefore cuts a tree link across
// an edge at an end of the blocked edge and glues a cut edge on the cycle that link closes (an
// edge swap of the spanning tree); the side of the tree that moves is laid out again from the new
// link and must not overlap the rest. A tabu search over these moves (Clearance::run) keeps the
// net with the fewest blocked edges it has seen.
#include "core/tab_clearance.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <numbers>
#include <utility>

#include "core/dual_graph.h"
#include "core/errors.h"
#include "core/overlap.h"
#include "core/tab_clearance_report.h"
#include "core/unfold_tree.h"

namespace papernet {

namespace {

// Overlap tolerance relative to the mesh's bounding-box diagonal (as the unfolder's).
constexpr double kRelativeTolerance = 1e-9;
// Cut edges farther along the cut tree tried per link (see Clearance::candidates).
constexpr std::size_t kFarGlues = 32;
// A vertex this far from flat (angle defect, radians: 10 degrees) hosts a leaf of the cut tree
// without harm: its slit opens by that angle.
constexpr double kSharpDefect = 10 * std::numbers::pi / 180;
// Tabu search (Clearance::run): how many blocked edges a move may close net, for how many
// steps a move's edges stay tabu, how many sweeps without a new best end a stage, and the
// candidate moves evaluated per step in each stage.
constexpr long long kMaxWorsening = 1;
constexpr int kTenure = 40;
constexpr int kStallSweeps = 3;
constexpr std::array<std::size_t, 4> kStepCaps = {50, 200, 800, static_cast<std::size_t>(-1) / 2};

class Clearance {
 public:
  Clearance(const Mesh& mesh, const Net& net, const TabClearanceOptions& options);
  std::size_t blocked_count() const { return blocked_count_; }
  std::vector<EdgeSide> blocked_edges() const;
  void run(Progress& progress);
  Net net() const { return Net{parent_, pos_}; }
  std::size_t moves_ = 0, evaluations_ = 0;

 private:
  int canon(int f, int k) const {
    const int n = adj_[f][k];
    return n < 0 || f < n ? 3 * f + k : 3 * n + adj_edge_[f][k];
  }
  bool linked(int f, int k) const { return links_[f] >> k & 1; }
  bool coincident(int f, int k) const;
  bool is_cut(int f, int k) const { return adj_[f][k] >= 0 && !linked(f, k) && !coincident(f, k); }
  bool side_has_room(int f, int k) const;
  bool blocked(int f, int k) const {
    return is_cut(f, k) && !side_has_room(f, k) && !side_has_room(adj_[f][k], adj_edge_[f][k]);
  }
  void root_tree();
  bool in_sub(int top, int x) const {
    return static_cast<unsigned>(tin_[x] - tin_[top]) < static_cast<unsigned>(size_[top]);
  }
  void set_link(int f, int k, bool on);
  void place(int f, const Triangle2& p);
  /// What a move changes: blocked edges and flat leaves of the cut tree (after - before).
  struct Change {
    long long blocked = 0, flat_leaves = 0;
  };
  bool apply_move(int tf, int tk, int lf, int lk, int cf, int ck, Change& out);
  void undo();
  void commit();
  template <class Consider>
  bool candidates(int f, int k, Consider&& consider);
  /// A leaf of the cut tree at v does no harm: v is on the boundary or far from flat.
  bool harmless(int v) const { return vboundary_[v] || std::abs(defect_[v]) >= kSharpDefect; }

  const Mesh& mesh_;
  int nf_ = 0;
  std::vector<std::array<int, 3>> adj_;
  std::vector<std::array<std::int8_t, 3>> adj_edge_;
  std::vector<FaceShape> shape_;
  std::vector<std::vector<int>> vertex_faces_;
  std::vector<Triangle2> pos_;
  std::vector<Box2> box_;
  std::vector<std::uint8_t> links_;
  OverlapGrid grid_;
  double tol_ = 0, height_ = 0;
  std::size_t budget_ = 0;
  double time_limit_ = 0;       // seconds; <= 0: none
  std::size_t step_limit_ = 0;  // evaluations_ allowed up to in the current step of run()
  bool keep_bounds_ = true;
  Box2 bounds_;  // of the input net
  std::vector<TabShape> shapes_;
  std::vector<char> blocked_;  // by canonical half-edge 3 * f + k
  std::size_t blocked_count_ = 0;
  std::vector<int> parent_, tin_, size_, order_;
  std::vector<double> defect_;             // angle defect by vertex (0 on the boundary)
  std::vector<char> vboundary_;            // vertex on the mesh's boundary
  std::vector<int> cut_degree_;            // cut edges (unlinked interior edges) at each vertex
  std::array<int, 4> pending_{};           // the applied move: lf, lk, cf, ck
  std::vector<std::uint32_t> tabu_until_;  // by canonical half-edge: step until which it stays

  // Scratch of apply_move.
  std::vector<int> moving_, from_, mark_;
  std::vector<char> is_moving_;
  std::vector<Triangle2> new_pos_, old_pos_;
  std::vector<int> affected_;
  std::vector<std::uint32_t> stamp_;
  std::uint32_t epoch_ = 0;
};

Clearance::Clearance(const Mesh& mesh, const Net& net, const TabClearanceOptions& options)
    : mesh_(mesh), nf_(static_cast<int>(mesh.faces.size())) {
  DualGraph graph = build_dual_graph(mesh);
  vboundary_ = boundary_vertices(mesh, graph);
  adj_ = std::move(graph.neighbour);
  adj_edge_ = std::move(graph.neighbour_edge);
  shape_.resize(nf_);
  vertex_faces_.assign(mesh.vertices.size(), {});
  for (int f = 0; f < nf_; ++f) {
    shape_[f] = face_shape(mesh, f);
    for (int v : mesh.faces[f]) vertex_faces_[v].push_back(f);
  }
  pos_ = net.points;
  box_.resize(nf_);
  links_.assign(nf_, 0);
  for (int f = 0; f < nf_; ++f) {
    const int p = net.parent[f];
    if (p < 0) continue;
    for (int k = 0; k < 3; ++k)
      if (adj_[f][k] == p) {
        set_link(f, k, true);
        break;
      }
  }
  tol_ = kRelativeTolerance * bounding_box_diagonal(mesh);
  height_ = options.min_height;
  budget_ = options.max_evaluations;
  time_limit_ = options.time_limit_seconds;
  shapes_ = tab_shapes(options.angle_deg);
  double total = 0;
  for (const auto& t : pos_)
    for (int k = 0; k < 3; ++k) total += norm(t[(k + 1) % 3] - t[k]);
  const double mean = total / (3.0 * std::max(1, nf_));
  grid_.reset(mean > 0 && std::isfinite(mean) ? mean : 1.0);
  keep_bounds_ = options.keep_bounds;
  for (int f = 0; f < nf_; ++f) {
    box_[f] = triangle_box(pos_[f]);
    grid_.insert(f, box_[f]);
    const Box2& b = box_[f];
    bounds_ = f == 0 ? b
                     : Box2{{std::min(bounds_.lo.x, b.lo.x), std::min(bounds_.lo.y, b.lo.y)},
                            {std::max(bounds_.hi.x, b.hi.x), std::max(bounds_.hi.y, b.hi.y)}};
  }
  blocked_.assign(3 * static_cast<std::size_t>(nf_), 0);
  for (int f = 0; f < nf_; ++f)
    for (int k = 0; k < 3; ++k)
      if (canon(f, k) == 3 * f + k && blocked(f, k)) {
        blocked_[3 * f + k] = 1;
        ++blocked_count_;
      }
  parent_.assign(nf_, -1);
  tin_.assign(nf_, 0);
  size_.assign(nf_, 1);
  is_moving_.assign(nf_, 0);
  from_.assign(nf_, -1);
  stamp_.assign(3 * static_cast<std::size_t>(nf_), 0);
  defect_ = angle_defects(mesh);
  cut_degree_.assign(mesh.vertices.size(), 0);
  for (int f = 0; f < nf_; ++f)
    for (int k = 0; k < 3; ++k)
      if (f < adj_[f][k] && !linked(f, k))
        ++cut_degree_[mesh.faces[f][k]], ++cut_degree_[mesh.faces[f][(k + 1) % 3]];
  root_tree();
}

std::vector<EdgeSide> Clearance::blocked_edges() const {
  std::vector<EdgeSide> out;
  for (int h = 0; h < 3 * nf_; ++h)
    if (blocked_[h]) out.push_back({h / 3, h % 3});
  return out;
}

bool Clearance::coincident(int f, int k) const {
  const int n = adj_[f][k], kn = adj_edge_[f][k];
  const Vec2 a0 = pos_[f][k], a1 = pos_[f][(k + 1) % 3];
  const Vec2 b0 = pos_[n][kn], b1 = pos_[n][(kn + 1) % 3];
  const double close = 1e-6 * norm(a1 - a0);
  return norm(a0 - b1) <= close && norm(a1 - b0) <= close;
}

bool Clearance::side_has_room(int f, int k) const {
  const double len = norm(pos_[f][(k + 1) % 3] - pos_[f][k]);
  if (!(len > 0)) return false;
  const double h = std::min(height_, 0.5 * len);
  for (const TabShape& shape : shapes_) {
    const auto t = tab_trapezoid(pos_[f], k, shape, h);
    const Triangle2 t0{t[0], t[1], t[2]}, t1{t[0], t[2], t[3]};
    Box2 box = triangle_box(t0);
    for (Vec2 p : {t[3]})
      box = {{std::min(box.lo.x, p.x), std::min(box.lo.y, p.y)},
             {std::max(box.hi.x, p.x), std::max(box.hi.y, p.y)}};
    bool hit = false;
    grid_.query(box, [&](int c) {
      if (hit) return;
      hit = triangles_overlap(t0, pos_[c], tol_) || triangles_overlap(t1, pos_[c], tol_);
    });
    if (!hit) return true;
  }
  return false;
}

void Clearance::set_link(int f, int k, bool on) {
  const int n = adj_[f][k], kn = adj_edge_[f][k];
  if (on) {
    links_[f] |= static_cast<std::uint8_t>(1u << k);
    links_[n] |= static_cast<std::uint8_t>(1u << kn);
  } else {
    links_[f] &= static_cast<std::uint8_t>(~(1u << k));
    links_[n] &= static_cast<std::uint8_t>(~(1u << kn));
  }
}

void Clearance::root_tree() {
  order_.clear();
  std::vector<int> stack{0};
  parent_[0] = -1;
  while (!stack.empty()) {
    const int x = stack.back();
    stack.pop_back();
    tin_[x] = static_cast<int>(order_.size());
    order_.push_back(x);
    for (int k = 0; k < 3; ++k)
      if (linked(x, k) && adj_[x][k] != parent_[x]) {
        parent_[adj_[x][k]] = x;
        stack.push_back(adj_[x][k]);
      }
  }
  for (int i = nf_ - 1; i >= 0; --i) {
    const int x = order_[i];
    size_[x] = 1;
    for (int k = 0; k < 3; ++k)
      if (linked(x, k) && adj_[x][k] != parent_[x]) size_[x] += size_[adj_[x][k]];
  }
}

void Clearance::place(int f, const Triangle2& p) {
  grid_.remove(f);
  pos_[f] = p;
  box_[f] = triangle_box(p);
  grid_.insert(f, box_[f]);
}

// Cuts the link across edge lk of face lf and glues cut edge ck of face cf and leaves the change
// applied (commit() or undo() next) when it adds no overlap and gives blocked edge tk of face tf
// room (or glues it); `out` then says how the number of blocked edges and of flat leaves would
// change. Returns false, with nothing changed, otherwise.
bool Clearance::apply_move(int tf, int tk, int lf, int lk, int cf, int ck, Change& out) {
  const int lp = adj_[lf][lk];
  const int top = parent_[lf] == lp ? lf : lp;
  const int cq = adj_[cf][ck];
  if (in_sub(top, cf) == in_sub(top, cq)) return false;  // the glue would close a cycle
  ++evaluations_;
  const bool small_is_sub = 2 * size_[top] <= nf_;
  const auto moving = [&](int x) { return in_sub(top, x) == small_is_sub; };
  const int anchor = moving(cf) ? cf : cq, fixed = anchor == cf ? cq : cf;
  const int ka = anchor == cf ? ck : adj_edge_[cf][ck], kf = anchor == cf ? adj_edge_[cf][ck] : ck;

  // Lay out the moving side again from the new link, nearest faces first, each checked at once
  // for overlap with the side that stays (and, keep_bounds, for leaving the net's box).
  const auto clashes = [&](const Triangle2& t) {
    const Box2 b = triangle_box(t);
    bool hit = keep_bounds_ && (b.lo.x < bounds_.lo.x || b.lo.y < bounds_.lo.y ||
                                b.hi.x > bounds_.hi.x || b.hi.y > bounds_.hi.y);
    grid_.query(b, [&](int c) {
      if (!hit && !moving(c)) hit = triangles_overlap(t, pos_[c], tol_);
    });
    return hit;
  };
  const auto give_up = [&] {
    for (int x : moving_) is_moving_[x] = 0;
    return false;
  };
  moving_.assign(1, anchor);
  new_pos_.assign(1, place_across(pos_[fixed], kf, ka, shape_[anchor]));
  is_moving_[anchor] = 1;
  if (clashes(new_pos_[0])) return give_up();
  for (std::size_t i = 0; i < moving_.size(); ++i) {
    const int x = moving_[i];
    for (int k = 0; k < 3; ++k) {
      const int y = adj_[x][k];
      if (!linked(x, k) || is_moving_[y]) continue;
      if ((x == lf && k == lk) || (x == lp && k == adj_edge_[lf][lk])) continue;  // the cut link
      is_moving_[y] = 1;
      moving_.push_back(y);
      new_pos_.push_back(place_across(new_pos_[i], k, adj_edge_[x][k], shape_[y]));
      if (clashes(new_pos_.back())) return give_up();
    }
  }
  // Apply it, and drop it at once when the edge it is for still has no room.
  old_pos_.resize(moving_.size());
  for (std::size_t i = 0; i < moving_.size(); ++i) {
    old_pos_[i] = pos_[moving_[i]];
    place(moving_[i], new_pos_[i]);
  }
  set_link(lf, lk, false);
  set_link(cf, ck, true);
  pending_ = {lf, lk, cf, ck};
  if (blocked(tf, tk)) {
    undo();
    return false;
  }
  // Edges whose room may change: cut edges of faces near the border between the two sides,
  // before and after the move (a tab is at most height_ away from its edge).
  if (++epoch_ == 0) std::fill(stamp_.begin(), stamp_.end(), 0), epoch_ = 1;
  affected_.clear();
  const auto mark = [&](int f) {
    for (int k = 0; k < 3; ++k) {
      if (adj_[f][k] < 0) continue;
      const int h = canon(f, k);
      if (stamp_[h] != epoch_) stamp_[h] = epoch_, affected_.push_back(h);
    }
  };
  const auto near = [&](const Box2& b, int s) {
    const Box2 grown{{b.lo.x - height_, b.lo.y - height_}, {b.hi.x + height_, b.hi.y + height_}};
    grid_.query(grown, [&](int c) {
      if (is_moving_[c]) return;
      const Box2& o = box_[c];
      if (o.lo.x > grown.hi.x || o.hi.x < grown.lo.x || o.lo.y > grown.hi.y || o.hi.y < grown.lo.y)
        return;
      mark(c);
      mark(s);
    });
  };
  for (std::size_t i = 0; i < moving_.size(); ++i) {
    near(triangle_box(old_pos_[i]), moving_[i]);
    near(box_[moving_[i]], moving_[i]);
  }
  mark(lf);
  mark(cf);
  long long before = 0, after = 0;
  mark_.clear();
  for (int h : affected_) {
    before += blocked_[h];
    const int b = blocked(h / 3, h % 3) ? 1 : 0;
    mark_.push_back(b);
    after += b;
  }
  out.blocked = after - before;
  // Flat leaves: the cut link's ends gain a cut edge, the glued edge's ends lose one.
  const int ends[4] = {mesh_.faces[lf][lk], mesh_.faces[lf][(lk + 1) % 3], mesh_.faces[cf][ck],
                       mesh_.faces[cf][(ck + 1) % 3]};
  const auto flat_leaf = [&](int v, int degree) { return degree == 1 && !harmless(v); };
  out.flat_leaves = 0;
  for (int i = 0; i < 4; ++i) {
    bool seen = false;
    for (int j = 0; j < i; ++j) seen = seen || ends[j] == ends[i];
    if (seen) continue;
    int degree = cut_degree_[ends[i]];
    for (int j = 0; j < 4; ++j)
      if (ends[j] == ends[i]) degree += j < 2 ? 1 : -1;
    out.flat_leaves +=
        (flat_leaf(ends[i], degree) ? 1 : 0) - (flat_leaf(ends[i], cut_degree_[ends[i]]) ? 1 : 0);
  }
  return true;
}

void Clearance::undo() {
  const auto [lf, lk, cf, ck] = pending_;
  set_link(cf, ck, false);
  set_link(lf, lk, true);
  for (std::size_t i = 0; i < moving_.size(); ++i) place(moving_[i], old_pos_[i]);
  for (int x : moving_) is_moving_[x] = 0;
}

void Clearance::commit() {
  const auto [lf, lk, cf, ck] = pending_;
  for (int x : moving_) is_moving_[x] = 0;
  long long delta = 0;
  for (std::size_t i = 0; i < affected_.size(); ++i) {
    delta += mark_[i] - blocked_[affected_[i]];
    blocked_[affected_[i]] = static_cast<char>(mark_[i]);
  }
  blocked_count_ = static_cast<std::size_t>(static_cast<long long>(blocked_count_) + delta);
  ++cut_degree_[mesh_.faces[lf][lk]], ++cut_degree_[mesh_.faces[lf][(lk + 1) % 3]];
  --cut_degree_[mesh_.faces[cf][ck]], --cut_degree_[mesh_.faces[cf][(ck + 1) % 3]];
  root_tree();
  ++moves_;
}

// Offers the moves around blocked edge k of face f to `consider(lf, lk, cf, ck)` (cut the link
// across edge lk of face lf, glue cut edge ck of face cf), which returns true to stop: first cut
// a link across an edge at one of its ends and glue a cut edge between nearby faces (the fan of
// its ends and one ring around); then, wider, cut any link in that ring and glue a cut edge
// within two rings; then farther glues (below). Returns true when `consider` stopped it.
template <class Consider>
bool Clearance::candidates(int f, int k, Consider&& consider) {
  const int u = mesh_.faces[f][k], v = mesh_.faces[f][(k + 1) % 3];
  std::vector<int> fan;  // faces at u or v
  for (int w : {u, v})
    for (int x : vertex_faces_[w])
      if (std::find(fan.begin(), fan.end(), x) == fan.end()) fan.push_back(x);
  const auto grow = [&](std::vector<int> faces) {
    const std::size_t n = faces.size();
    for (std::size_t i = 0; i < n; ++i)
      for (int y : adj_[faces[i]])
        if (y >= 0 && std::find(faces.begin(), faces.end(), y) == faces.end()) faces.push_back(y);
    std::sort(faces.begin(), faces.end());
    return faces;
  };
  const std::vector<int> ring1 = grow(fan), ring2 = grow(ring1);
  const auto at_ends = [&](int x, int j) {
    const int a = mesh_.faces[x][j], b = mesh_.faces[x][(j + 1) % 3];
    return a == u || a == v || b == u || b == v;
  };
  const auto links_in = [&](const std::vector<int>& faces, bool ends_only) {
    std::vector<std::pair<int, int>> out;
    for (int x : faces)
      for (int j = 0; j < 3; ++j)
        if (linked(x, j) && x < adj_[x][j] && (!ends_only || at_ends(x, j)) &&
            std::binary_search(faces.begin(), faces.end(), adj_[x][j]))
          out.push_back({x, j});
    return out;
  };
  const auto cuts_in = [&](const std::vector<int>& faces) {
    std::vector<std::pair<int, int>> out;
    for (int x : faces)
      for (int j = 0; j < 3; ++j) {
        const int y = adj_[x][j];
        if (y > x && !linked(x, j) && std::binary_search(faces.begin(), faces.end(), y))
          out.push_back({x, j});
      }
    return out;
  };
  const auto try_all = [&](const std::vector<std::pair<int, int>>& cuts,
                           const std::vector<std::pair<int, int>>& glues) {
    for (const auto& [lf, lk] : cuts)
      for (const auto& [cf, ck] : glues) {
        if (evaluations_ >= std::min(budget_, step_limit_)) return false;
        if (consider(lf, lk, cf, ck)) return true;
      }
    return false;
  };
  const auto narrow_cuts = links_in(ring1, true), narrow_glues = cuts_in(ring1);
  if (try_all(narrow_cuts, narrow_glues)) return true;
  std::vector<std::pair<int, int>> wide_cuts;
  for (const auto& c : links_in(ring1, false))
    if (std::find(narrow_cuts.begin(), narrow_cuts.end(), c) == narrow_cuts.end())
      wide_cuts.push_back(c);
  std::vector<std::pair<int, int>> wide_glues;
  for (const auto& c : cuts_in(ring2))
    if (std::find(narrow_glues.begin(), narrow_glues.end(), c) == narrow_glues.end())
      wide_glues.push_back(c);
  if (try_all(narrow_cuts, wide_glues) || try_all(wide_cuts, narrow_glues) ||
      try_all(wide_cuts, wide_glues))
    return true;
  // Farther: for a link at an end, the cut edges anywhere on the cycle it closes in the cut
  // tree (one face on each side of the link), nearest first, that leave no new flat leaf of the
  // cut tree (each end keeps another cut edge, or is sharp or on the boundary): gluing those
  // cannot create a new near-slit.
  const Vec3 mid = 0.5 * (mesh_.vertices[u] + mesh_.vertices[v]);
  const std::vector<int>& degree = cut_degree_;
  std::vector<std::pair<int, int>> all_cuts = narrow_cuts;
  all_cuts.insert(all_cuts.end(), wide_cuts.begin(), wide_cuts.end());
  for (const std::pair<int, int>& cut : all_cuts) {
    // Not a structured binding: the lambda below uses them, which clang 14 refuses.
    const int lf = cut.first, lk = cut.second;
    const int l0 = mesh_.faces[lf][lk], l1 = mesh_.faces[lf][(lk + 1) % 3];
    const int lp = adj_[lf][lk], top = parent_[lf] == lp ? lf : lp;
    const bool sub_small = 2 * size_[top] <= nf_;
    std::vector<std::pair<double, std::pair<int, int>>> far;
    const auto side = [&](int x) {  // the cut edges from face x of the smaller side
      for (int j = 0; j < 3; ++j) {
        const int y = adj_[x][j];
        if (y < 0 || linked(x, j) || in_sub(top, y) == sub_small) continue;
        const int a = mesh_.faces[x][j], b = mesh_.faces[x][(j + 1) % 3];
        const int gain_a = a == l0 || a == l1 ? 1 : 0;
        const int gain_b = b == l0 || b == l1 ? 1 : 0;
        if ((degree[a] + gain_a - 1 < 2 && !harmless(a)) ||
            (degree[b] + gain_b - 1 < 2 && !harmless(b)))
          continue;
        const Vec3 m = 0.5 * (mesh_.vertices[a] + mesh_.vertices[b]);
        far.push_back({norm(m - mid), {x, j}});
      }
    };
    const int lo = tin_[top], hi = tin_[top] + size_[top];
    if (sub_small) {
      for (int i = lo; i < hi; ++i) side(order_[i]);
    } else {
      for (int i = 0; i < lo; ++i) side(order_[i]);
      for (int i = hi; i < nf_; ++i) side(order_[i]);
    }
    std::sort(far.begin(), far.end());
    if (far.size() > kFarGlues) far.resize(kFarGlues);
    std::vector<std::pair<int, int>> glues;
    for (const auto& [d, g] : far) glues.push_back(g);
    if (try_all({{lf, lk}}, glues)) return true;
  }
  return false;
}

// Tabu search over the moves of candidates(): for each blocked edge in turn, the first move
// that lowers the number of blocked edges is made at once; when there is none, the best move
// that opens the edge (fewest blocked edges, then fewest flat leaves) is made even when it closes
// others, unless it closes more than kMaxWorsening edges net or re-cuts or re-glues an edge a
// recent move changed (tabu for kTenure steps). The best net seen is kept. Each step first
// offers an edge only its first kStepCaps[0] candidates (most overlap; the easy moves elsewhere
// come first); after kStallSweeps sweeps over the blocked edges without a new best, the next cap;
// after the last, it stops. It stops too when the budget is spent.
void Clearance::run(Progress& progress) {
  std::vector<std::uint8_t> best_links = links_;
  std::vector<Triangle2> best_pos = pos_;
  std::vector<char> best_blocked = blocked_;
  std::vector<int> best_degree = cut_degree_;
  std::size_t best_count = blocked_count_, best_moves = moves_;
  tabu_until_.assign(3 * static_cast<std::size_t>(nf_), 0);
  std::uint32_t step = 0;
  std::size_t level = 0;
  const auto start = std::chrono::steady_clock::now();
  const auto out_of_time = [&] {
    return time_limit_ > 0 &&
           std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count() >=
               time_limit_;
  };
  for (int stall = 0; blocked_count_ > 0 && evaluations_ < budget_ && !out_of_time();) {
    if (stall >= kStallSweeps) {
      if (++level == kStepCaps.size()) break;
      stall = 0;
    }
    const std::size_t sweep_best = best_count;
    for (int h = 0; h < 3 * nf_ && evaluations_ < budget_; ++h) {
      if (!blocked_[h]) continue;
      if (progress.cancelled()) throw CancelledException();
      if (out_of_time()) break;
      ++step;
      step_limit_ = evaluations_ + std::min(kStepCaps[level], budget_);
      const int f = h / 3, k = h % 3;
      struct Pick {
        Change change{kMaxWorsening + 1, 0};
        std::array<int, 4> move{-1, -1, -1, -1};
      } pick;
      const auto tabu = [&](int x, int j) { return tabu_until_[canon(x, j)] > step; };
      const bool improved = candidates(f, k, [&](int lf, int lk, int cf, int ck) {
        if (tabu(lf, lk) || tabu(cf, ck)) return false;
        Change change;
        if (!apply_move(f, k, lf, lk, cf, ck, change)) return false;
        if (change.blocked < 0) {
          commit();
          return true;
        }
        if (change.blocked < pick.change.blocked ||
            (change.blocked == pick.change.blocked &&
             change.flat_leaves < pick.change.flat_leaves)) {
          pick.change = change;
          pick.move = {lf, lk, cf, ck};
        }
        undo();
        return false;
      });
      if (!improved) {
        Change change;
        if (pick.move[0] < 0 ||
            !apply_move(f, k, pick.move[0], pick.move[1], pick.move[2], pick.move[3], change))
          continue;
        commit();
      }
      // Neither undo this move nor redo the one it replaced for a while.
      const std::uint32_t until = step + static_cast<std::uint32_t>(kTenure);
      tabu_until_[canon(pending_[0], pending_[1])] = until;
      tabu_until_[canon(pending_[2], pending_[3])] = until;
      if (blocked_count_ < best_count) {
        best_count = blocked_count_;
        best_links = links_;
        best_pos = pos_;
        best_blocked = blocked_;
        best_degree = cut_degree_;
        best_moves = moves_;
      }
    }
    stall = best_count < sweep_best ? 0 : stall + 1;
  }
  if (moves_ == best_moves) return;
  // Back to the best net seen.
  links_ = std::move(best_links);
  for (int f = 0; f < nf_; ++f)
    if (pos_[f] != best_pos[f]) place(f, best_pos[f]);
  blocked_ = std::move(best_blocked);
  cut_degree_ = std::move(best_degree);
  blocked_count_ = best_count;
  moves_ = best_moves;
  root_tree();
}

}  // namespace

std::vector<EdgeSide> edges_without_tab_room(const Mesh& mesh, const Net& net,
                                             const TabClearanceOptions& options) {
  if (!(options.min_height > 0)) return {};
  return Clearance(mesh, net, options).blocked_edges();
}

TabClearanceResult clear_tab_room(const Mesh& mesh, const Net& net,
                                  const TabClearanceOptions& options, Progress& progress) {
  TabClearanceResult result;
  result.net = net;
  if (!(options.min_height > 0) || mesh.faces.empty()) return result;
  Clearance state(mesh, net, options);
  result.blocked_before = state.blocked_count();
  state.run(progress);
  result.blocked_after = state.blocked_count();
  result.moves = state.moves_;
  result.evaluations = state.evaluations_;
  if (result.moves > 0) result.net = state.net();
  return result;
}

}  // namespace papernet
