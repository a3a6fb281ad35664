// Mesh repair: what modelling tools fix in one click (merge by distance, split non-manifold,
// separate loose parts), done so that an unfolding can follow. Every repair is counted and
// located, so the result can say what was changed.
#include "core/mesh/repair.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <string>
#include <unordered_map>
#include <utility>

#include "core/mesh/dual_graph.h"
#include "core/mesh/internal/describe.h"
#include "core/union_find.h"

namespace papernet {
namespace {

using mesh_detail::plural;
using mesh_detail::position;

// A face while it is repaired: its corners, the loader's vertex of each corner, the input face
// it comes from, whether it is still there, and the input corner (3 * face + k) whose texture
// coordinates and colour each corner carries.
struct Face {
  std::array<int, 3> v;
  std::array<int, 3> raw;
  int origin = 0;
  bool alive = true;
  std::array<int, 3> corner{};
};

// Collects the first few elements of one kind of repair.
struct Tally {
  std::size_t count = 0;
  std::vector<int> listed;
  void add(int element, std::size_t max_listed) {
    if (count++ < max_listed) listed.push_back(element);
  }
};

// "3, 8, 17, ..." for the elements a tally lists of all it counted.
std::string numbers(const Tally& t) {
  std::string s;
  for (std::size_t i = 0; i < t.listed.size(); ++i) {
    if (i) s += ", ";
    s += std::to_string(t.listed[i]);
  }
  return t.count > t.listed.size() ? s + ", ..." : s;
}

bool degenerate(const Mesh& m, const std::array<int, 3>& t, double eps) {
  if (t[0] == t[1] || t[1] == t[2] || t[0] == t[2]) return true;
  const Vec3 a = m.vertices[t[0]], b = m.vertices[t[1]], c = m.vertices[t[2]];
  const double longest = std::max({dot(b - a, b - a), dot(c - b, c - b), dot(a - c, a - c)});
  return !(0.5 * norm(cross(b - a, c - a)) > eps * longest);
}

// The zero-area faces of a mesh, removed by local edits that keep the surface closed (edge
// flips for caps, edge collapses for needles), else dropped. Adjacency is built only when there
// is such a face, and only as vertex -> faces.
class Degenerates {
 public:
  Degenerates(const Mesh& m, std::vector<Face>& faces, double eps)
      : m_(m), faces_(faces), eps_(eps), vertex_faces_(m.vertices.size()) {
    for (std::size_t f = 0; f < faces_.size(); ++f)
      if (faces_[f].alive)
        for (int v : faces_[f].v) vertex_faces_[v].push_back(int(f));
  }

  // Removes every zero-area face of `work`, counting them.
  void run(std::vector<int> work, Tally& tally, std::size_t max_listed) {
    std::size_t budget = 4 * faces_.size() + 16;  // every step removes a face or a degenerate one
    while (!work.empty() && budget-- > 0) {
      const int f = work.back();
      work.pop_back();
      if (!faces_[f].alive || !degenerate(m_, faces_[f].v, eps_)) continue;
      tally.add(faces_[f].origin, max_listed);
      const auto& v = faces_[f].v;
      if (v[0] != v[1] && v[1] != v[2] && v[0] != v[2] && (flip_cap(f) || collapse_needle(f, work)))
        continue;
      faces_[f].alive = false;
    }
  }

 private:
  // Lists in vertex_faces_ may hold faces an edit took the vertex out of: every use checks.
  bool has(int g, int x) const {
    return faces_[g].alive &&
           std::find(faces_[g].v.begin(), faces_[g].v.end(), x) != faces_[g].v.end();
  }
  std::vector<int> on_edge(int a, int b, int except) const {
    std::vector<int> out;
    for (int g : vertex_faces_[a])
      if (g != except && has(g, a) && has(g, b) &&
          std::find(out.begin(), out.end(), g) == out.end())
        out.push_back(g);
    return out;
  }
  static int corner_of(const Face& f, int v) {
    return int(std::find(f.v.begin(), f.v.end(), v) - f.v.begin());
  }

  // A cap: the corner opposite its longest edge lies inside that edge. The edge is flipped with
  // the face across it: (u, v, w) + (v, u, d) -> (u, d, w) + (d, v, w).
  bool flip_cap(int f) {
    Face& face = faces_[f];
    int k = 0;  // the longest edge runs from corner k to k + 1
    double longest = -1;
    for (int i = 0; i < 3; ++i) {
      const Vec3 e = m_.vertices[face.v[(i + 1) % 3]] - m_.vertices[face.v[i]];
      if (dot(e, e) > longest) longest = dot(e, e), k = i;
    }
    const int u = face.v[k], v = face.v[(k + 1) % 3], w = face.v[(k + 2) % 3];
    const Vec3 pu = m_.vertices[u], pv = m_.vertices[v], pw = m_.vertices[w];
    const double t = dot(pw - pu, pv - pu) / longest;
    if (!(t > 1e-3 && t < 1 - 1e-3)) return false;  // a needle: w almost on u or v
    const std::vector<int> across = on_edge(u, v, f);
    if (across.size() != 1) return false;
    const int g = across[0];
    Face& other = faces_[g];
    const int cu = corner_of(other, u), cv = corner_of(other, v);
    if ((cv + 1) % 3 != cu) return false;  // the neighbour runs the same way: not a flip
    const int cd = (cu + 1) % 3, d = other.v[cd];
    if (d == w || !on_edge(d, w, -1).empty()) return false;  // the new edge exists already
    const std::array<int, 3> a{u, d, w}, b{d, v, w};
    if (degenerate(m_, a, eps_) || degenerate(m_, b, eps_)) return false;
    const int rw = face.raw[(k + 2) % 3], ru = face.raw[k];
    const int rd = other.raw[cd], rv = other.raw[cv];
    const int kw = face.corner[(k + 2) % 3], ku = face.corner[k];
    const int kd = other.corner[cd], kv = other.corner[cv];
    face.v = a;
    face.raw = {ru, rd, rw};
    face.corner = {ku, kd, kw};
    other.v = b;
    other.raw = {rd, rv, rw};
    other.corner = {kd, kv, kw};
    vertex_faces_[d].push_back(f);
    vertex_faces_[w].push_back(g);
    return true;
  }

  // A needle: two corners almost together. Its shortest edge (a, b) is collapsed into a when the
  // link condition holds (the vertices next to both are those of the faces on the edge), so the
  // surface stays manifold; the faces on the edge go.
  bool collapse_needle(int f, std::vector<int>& work) {
    const Face& face = faces_[f];
    int k = 0;
    double shortest = -1;
    for (int i = 0; i < 3; ++i) {
      const Vec3 e = m_.vertices[face.v[(i + 1) % 3]] - m_.vertices[face.v[i]];
      if (shortest < 0 || dot(e, e) < shortest) shortest = dot(e, e), k = i;
    }
    const int a = face.v[k], b = face.v[(k + 1) % 3];
    const std::vector<int> on_ab = on_edge(a, b, -1);
    std::vector<int> opposite;
    for (int g : on_ab)
      for (int x : faces_[g].v)
        if (x != a && x != b) opposite.push_back(x);
    std::vector<int> next_a = neighbours(a), next_b = neighbours(b), common;
    std::set_intersection(next_a.begin(), next_a.end(), next_b.begin(), next_b.end(),
                          std::back_inserter(common));
    std::sort(opposite.begin(), opposite.end());
    opposite.erase(std::unique(opposite.begin(), opposite.end()), opposite.end());
    if (common != opposite || on_ab.size() > 2) return false;
    for (int g : on_ab) faces_[g].alive = false;
    for (int g : vertex_faces_[b]) {
      if (!has(g, b)) continue;
      for (int& x : faces_[g].v)
        if (x == b) x = a;
      vertex_faces_[a].push_back(g);
      work.push_back(g);
    }
    vertex_faces_[b].clear();
    return true;
  }

  std::vector<int> neighbours(int a) const {
    std::vector<int> out;
    for (int g : vertex_faces_[a])
      if (has(g, a))
        for (int x : faces_[g].v)
          if (x != a) out.push_back(x);
    std::sort(out.begin(), out.end());
    out.erase(std::unique(out.begin(), out.end()), out.end());
    return out;
  }

  const Mesh& m_;
  std::vector<Face>& faces_;
  double eps_;
  std::vector<std::vector<int>> vertex_faces_;
};

// One side of an edge: face f, from corner k to k + 1.
struct Side {
  std::uint64_t key;
  int f, k;
};

// Lists "3 (x, y, z), 8 (x, y, z), ..." (pairs: "3 (..)-4 (..)") of a tally's elements.
std::string located(const Mesh& mesh, const Tally& t, bool pairs) {
  std::string s;
  const std::size_t step = pairs ? 2 : 1;
  for (std::size_t i = 0; i + step <= t.listed.size(); i += step) {
    if (i) s += ", ";
    s += std::to_string(t.listed[i]) + " " + position(mesh, t.listed[i]);
    if (pairs) {
      s += '-';
      s += std::to_string(t.listed[i + 1]) + " " + position(mesh, t.listed[i + 1]);
    }
  }
  if (t.count * step > t.listed.size()) s += ", ...";
  return s;
}

// Edges, orientation and fans of the faces left; builds the repaired mesh into `out`.
void finish_repair(const Mesh& mesh, const std::vector<Face>& faces, const RepairOptions& options,
                   RepairResult& out) {
  const std::size_t nf = faces.size(), nv = mesh.vertices.size(), listed = options.max_listed;
  // Whether the loader's vertices say anything: some vertex of its is used by two faces. A
  // soup (STL) has none, and then every defect is the input's.
  bool indexed = false;
  {
    int most = -1;
    for (const Face& f : faces)
      if (f.alive) most = std::max({most, f.raw[0], f.raw[1], f.raw[2]});
    std::vector<char> seen(static_cast<std::size_t>(most + 1), 0);
    for (const Face& f : faces)
      for (int c = 0; c < 3 && f.alive && !indexed; ++c)
        indexed = std::exchange(seen[f.raw[c]], 1) != 0;
  }

  // Sides of every edge, grouped: more than two is a non-manifold edge, whose sides are all cut.
  std::vector<Side> sides;
  sides.reserve(3 * nf);
  for (std::size_t f = 0; f < nf; ++f)
    if (faces[f].alive)
      for (int k = 0; k < 3; ++k)
        sides.push_back({edge_key(faces[f].v[k], faces[f].v[(k + 1) % 3]), int(f), k});
  std::sort(sides.begin(), sides.end(), [](const Side& a, const Side& b) {
    return a.key != b.key ? a.key < b.key : a.f != b.f ? a.f < b.f : a.k < b.k;
  });
  std::vector<int> across(3 * nf, -1);  // the glued side of each side (3 * face + corner)
  std::vector<char> cut_vertex(nv, 0);  // an end of a cut edge (its splits are not pinches)
  Tally non_manifold;                   // listed as vertex pairs
  std::vector<int> suspects;  // sides of edges with more than two sides, or cut for orientation
  for (std::size_t i = 0; i < sides.size();) {
    std::size_t j = i;
    while (j < sides.size() && sides[j].key == sides[i].key) ++j;
    if (j - i == 2) {
      across[3 * sides[i].f + sides[i].k] = 3 * sides[i + 1].f + sides[i + 1].k;
      across[3 * sides[i + 1].f + sides[i + 1].k] = 3 * sides[i].f + sides[i].k;
    } else if (j - i > 2) {
      const int a = int(sides[i].key >> 32), b = int(sides[i].key & 0xffffffffu);
      for (std::size_t s = i; s < j; ++s) suspects.push_back(3 * sides[s].f + sides[s].k);
      cut_vertex[a] = cut_vertex[b] = 1;
      // Sides running opposite ways are glued in pairs (those the file joined first, then in
      // face order), so that a closed part with a fin on one edge stays closed; the rest are
      // cut. The ends of the edge are then split by fans below.
      const auto raw_key = [&](const Side& side) {
        const Face& f = faces[side.f];
        return edge_key(f.raw[side.k], f.raw[(side.k + 1) % 3]);
      };
      std::stable_sort(sides.begin() + long(i), sides.begin() + long(j),
                       [&](const Side& x, const Side& y) { return raw_key(x) < raw_key(y); });
      std::vector<char> paired(j - i, 0);
      for (std::size_t x = i; x < j; ++x)
        for (std::size_t y = x + 1; y < j && !paired[x - i]; ++y) {
          const int sx = 3 * sides[x].f + sides[x].k, sy = 3 * sides[y].f + sides[y].k;
          const Face& fx = faces[sides[x].f];
          const Face& fy = faces[sides[y].f];
          const bool opposite = fx.v[sides[x].k] == fy.v[(sides[y].k + 1) % 3];
          if (paired[y - i] || !opposite) continue;
          paired[x - i] = paired[y - i] = 1;
          across[sx] = sy;
          across[sy] = sx;
        }
      // The input's own when three sides share the loader's edge (or there are no shared
      // vertices to tell): else only the merge of touching surfaces made it, and it is undone.
      std::vector<std::uint64_t> raw;
      for (std::size_t s = i; s < j; ++s) {
        const Face& f = faces[sides[s].f];
        raw.push_back(edge_key(f.raw[sides[s].k], f.raw[(sides[s].k + 1) % 3]));
      }
      std::sort(raw.begin(), raw.end());
      bool own = !indexed;
      for (std::size_t s = 2; s < raw.size(); ++s) own |= raw[s] == raw[s - 2];
      if (own && non_manifold.count++ < listed)
        non_manifold.listed.insert(non_manifold.listed.end(), {a, b});
    }
    i = j;
  }
  const auto forward = [&](int side) {  // the side runs from the smaller vertex to the larger
    const Face& f = faces[side / 3];
    return f.v[side % 3] < f.v[(side % 3 + 1) % 3];
  };

  // Orientation: each part's faces agree with their neighbours (a flip bit per face); an edge
  // that contradicts what the part decided already is cut (a part that cannot be oriented).
  std::vector<int> flip(nf, -1), part(nf, -1), order;
  Tally non_orientable;
  int parts = 0;
  for (std::size_t seed = 0; seed < nf; ++seed) {
    if (!faces[seed].alive || flip[seed] >= 0) continue;
    flip[seed] = 0;
    part[seed] = parts;
    std::size_t head = order.size();
    order.push_back(int(seed));
    while (head < order.size()) {
      const int f = order[head++];
      for (int k = 0; k < 3; ++k) {
        const int s = 3 * f + k, o = across[s];
        if (o < 0) continue;
        const int g = o / 3, want = flip[f] ^ (forward(s) == forward(o) ? 1 : 0);
        if (flip[g] < 0) {
          flip[g] = want;
          part[g] = parts;
          order.push_back(g);
        } else if (flip[g] != want) {
          const int a = faces[f].v[k], b = faces[f].v[(k + 1) % 3];
          non_orientable.add(a, listed);
          cut_vertex[a] = cut_vertex[b] = 1;
          suspects.insert(suspects.end(), {s, o});
          across[s] = across[o] = -1;
        }
      }
    }
    ++parts;
  }
  // Each part as a whole: outward when it is closed (positive volume), else as most of its
  // faces were.
  std::vector<double> volume(parts, 0);
  std::vector<std::size_t> flipped(parts, 0), size(parts, 0);
  std::vector<char> closed(parts, 1);
  for (std::size_t f = 0; f < nf; ++f) {
    if (!faces[f].alive) continue;
    const int p = part[f];
    ++size[p];
    flipped[p] += flip[f];
    for (int k = 0; k < 3; ++k)
      if (across[3 * f + k] < 0) closed[p] = 0;
    const Vec3 a = mesh.vertices[faces[f].v[0]], b = mesh.vertices[faces[f].v[1]],
               c = mesh.vertices[faces[f].v[2]];
    volume[p] += (flip[f] ? -1.0 : 1.0) * dot(a, cross(b, c));
  }
  std::vector<char> invert(parts, 0);
  bool inverted = false;
  for (int p = 0; p < parts; ++p) {
    invert[p] = closed[p] ? volume[p] < 0 : 2 * flipped[p] > size[p];
    inverted |= closed[p] && invert[p];
  }

  // Fans: corners around a vertex joined across glued edges (corner c of face f is 3f + c).
  const auto fans_of = [&] {
    UnionFind fans(3 * nf);
    for (std::size_t f = 0; f < nf; ++f)
      for (int k = 0; k < 3; ++k) {
        const int s = 3 * int(f) + k, o = across[s];
        if (o < s) continue;  // each glued pair once (o is -1 when not glued)
        const int g = o / 3;
        for (int end : {k, (k + 1) % 3})
          for (int c = 0; c < 3; ++c)
            if (faces[g].v[c] == faces[f].v[end]) fans.unite(3 * int(f) + end, 3 * g + c);
      }
    return fans;
  };
  UnionFind fans = fans_of();
  // A cut side whose two ends stay in the fans of the sides it was cut from (the fans close
  // around it through other edges) would still share their edge: such a side's face is detached
  // at one end (its other side there is cut too), until every edge has at most one glued pair.
  // Only sides of edges with more than two sides, or cut for orientation, can be affected.
  for (bool again = !suspects.empty(); again;) {
    again = false;
    std::vector<std::pair<std::uint64_t, int>> keyed;
    for (int s : suspects) {
      const int f = s / 3, k = s % 3;
      keyed.push_back({edge_key(fans.find(3 * f + k), fans.find(3 * f + (k + 1) % 3)), s});
    }
    std::sort(keyed.begin(), keyed.end());
    for (std::size_t i = 0; i < keyed.size();) {
      std::size_t j = i;
      while (j < keyed.size() && keyed[j].first == keyed[i].first) ++j;
      int kept = -1;  // a glued pair within the group stays
      for (std::size_t x = i; x < j && kept < 0; ++x)
        for (std::size_t y = i; y < j; ++y)
          if (across[keyed[x].second] == keyed[y].second) kept = keyed[x].second;
      for (std::size_t x = i; x < j && j - i > 1; ++x) {
        const int s = keyed[x].second;
        if (s == kept || (kept >= 0 && s == across[kept])) continue;
        const int f = s / 3, k = s % 3, before = 3 * f + (k + 2) % 3;
        for (int side : {s, before})
          if (across[side] >= 0) {
            across[across[side]] = -1;
            across[side] = -1;
            again = true;
          }
        for (int c = 0; c < 3; ++c) cut_vertex[faces[f].v[c]] = 1;
      }
      i = j;
    }
    if (again) fans = fans_of();
  }
  // One vertex per fan; a vertex in several fans is a pinch of the input's when a vertex of the
  // loader's own lies in two of them (or there are none to tell). Ends of cut edges are counted
  // with those edges.
  // Vertices in several fans: found in one pass; only their corners are looked at again.
  std::vector<int> first_fan(nv, -1);
  std::vector<char> several(nv, 0);
  for (std::size_t f = 0; f < nf; ++f)
    for (int c = 0; c < 3 && faces[f].alive; ++c) {
      const int v = faces[f].v[c], fan = fans.find(3 * int(f) + c);
      if (first_fan[v] < 0) first_fan[v] = fan;
      several[v] |= first_fan[v] != fan;
    }
  std::vector<std::array<int, 3>> uses;  // (vertex, raw vertex, fan) of those vertices' corners
  for (std::size_t f = 0; f < nf; ++f)
    for (int c = 0; c < 3 && faces[f].alive; ++c)
      if (several[faces[f].v[c]] && !cut_vertex[faces[f].v[c]])
        uses.push_back({faces[f].v[c], faces[f].raw[c], fans.find(3 * int(f) + c)});
  std::sort(uses.begin(), uses.end());
  Tally pinched;
  for (std::size_t i = 0; i < uses.size();) {
    std::size_t j = i;
    bool own = !indexed;
    for (; j < uses.size() && uses[j][0] == uses[i][0]; ++j)
      own |= j > i && uses[j][1] == uses[j - 1][1] && uses[j][2] != uses[j - 1][2];
    if (own) pinched.add(uses[i][0], listed);
    i = j;
  }

  Mesh& m = out.mesh;
  std::vector<int> vertex_of_fan(3 * nf, -1);
  Tally reoriented;
  for (std::size_t f = 0; f < nf; ++f) {
    if (!faces[f].alive) continue;
    std::array<int, 3> t{};
    for (int c = 0; c < 3; ++c) {
      int& id = vertex_of_fan[fans.find(3 * int(f) + c)];
      if (id < 0) {
        id = int(m.vertices.size());
        m.vertices.push_back(mesh.vertices[faces[f].v[c]]);
      }
      t[c] = id;
    }
    std::array<int, 3> corner = faces[f].corner;
    if (flip[f] ^ invert[part[f]]) {
      std::swap(t[1], t[2]);
      std::swap(corner[1], corner[2]);  // a corner's texture coordinates turn with it
      reoriented.add(faces[f].origin, listed);
    }
    m.faces.push_back(t);
    out.corners.push_back(corner);
  }
  const auto add = [&](const char* code, const Tally& t, const std::string& message) {
    if (t.count) out.repairs.push_back({code, t.count, message, t.listed});
  };
  add("cut_non_manifold_edges", non_manifold,
      "cut " + plural(non_manifold.count, "edge", "edges") +
          " shared by more than two faces (faces beyond a pair keep their own side): edges " +
          located(mesh, non_manifold, true));
  add("split_pinched_vertices", pinched,
      "split " + plural(pinched.count, "vertex", "vertices") +
          " where faces that share no edge met (one vertex per fan): vertices " +
          located(mesh, pinched, false));
  add("cut_non_orientable_edges", non_orientable,
      "cut " + plural(non_orientable.count, "edge", "edges") +
          " of a part that cannot be oriented consistently (a Moebius strip): at vertices " +
          located(mesh, non_orientable, false));
  add("reoriented_faces", reoriented,
      "turned " + plural(reoriented.count, "face", "faces") + " to agree with their neighbours" +
          (inverted ? " and to face outwards" : "") + ": faces " + numbers(reoriented));
}

}  // namespace

RepairResult repair_mesh(const Mesh& mesh, const std::vector<std::array<int, 3>>& raw_corners,
                         const RepairOptions& options) {
  const std::size_t nf = mesh.faces.size(), listed = options.max_listed;
  std::vector<Face> faces(nf);
  for (std::size_t f = 0; f < nf; ++f)
    faces[f] = {mesh.faces[f],
                raw_corners.size() == nf ? raw_corners[f] : mesh.faces[f],
                int(f),
                true,
                {3 * int(f), 3 * int(f) + 1, 3 * int(f) + 2}};
  RepairResult out;
  const auto report = [&](const char* code, const Tally& t, const std::string& what,
                          const std::string& where) {
    if (t.count == 0) return;
    out.repairs.push_back({code, t.count, what + ": " + where + " " + numbers(t), t.listed});
  };

  // Duplicate faces (the same three vertices, either way round), then zero-area faces. A face
  // and its reverse hanging off a surface (a flap folded flat: some edge of theirs has two more
  // faces that are no such pair) both go, which leaves the surface as if the flap were never
  // there; otherwise (a sheet modelled two-sided, a face repeated) the first of them stays.
  Tally duplicates, degenerates;
  {
    std::vector<std::pair<std::array<int, 3>, int>> sorted(nf);
    for (std::size_t f = 0; f < nf; ++f) {
      auto t = faces[f].v;
      std::sort(t.begin(), t.end());
      sorted[f] = {t, int(f)};
    }
    std::sort(sorted.begin(), sorted.end());
    // Groups of faces on the same three distinct vertices, and which of them hold both turns.
    std::vector<std::pair<std::size_t, std::size_t>> groups;
    std::vector<char> grouped(nf, 0);  // 1: in a group holding both turns, 2: a repeat that goes
    for (std::size_t i = 0; i < nf;) {
      std::size_t j = i + 1;
      while (j < nf && sorted[j].first == sorted[i].first) ++j;
      const auto& t = sorted[i].first;
      if (j - i > 1 && t[0] != t[1] && t[1] != t[2]) {
        groups.push_back({i, j});
        // A turn is the cyclic order: the face's corners in the sorted triple's order or not.
        const auto turn = [&](std::size_t x) {
          const auto& v = faces[sorted[x].second].v;
          const int k = int(std::find(v.begin(), v.end(), t[0]) - v.begin());
          return v[(k + 1) % 3] == t[1];
        };
        bool mixed = false;
        for (std::size_t x = i + 1; x < j; ++x) mixed |= turn(x) != turn(i);
        for (std::size_t x = i; x < j; ++x) grouped[sorted[x].second] = mixed ? 1 : x > i ? 2 : 0;
      }
      i = j;
    }
    // Faces outside such groups on each edge of a group holding both turns.
    std::unordered_map<std::uint64_t, int> others;
    for (std::size_t f = 0; f < nf; ++f)
      if (grouped[f] == 1)
        for (int k = 0; k < 3; ++k) others[edge_key(faces[f].v[k], faces[f].v[(k + 1) % 3])] = 0;
    if (!others.empty())
      for (std::size_t f = 0; f < nf; ++f)
        for (int k = 0; k < 3 && !grouped[f]; ++k) {
          auto it = others.find(edge_key(faces[f].v[k], faces[f].v[(k + 1) % 3]));
          if (it != others.end()) ++it->second;
        }
    for (const auto& [i, j] : groups) {
      bool flap = false;
      const Face& first = faces[sorted[i].second];
      for (int k = 0; k < 3 && grouped[sorted[i].second] == 1; ++k)
        flap |= others[edge_key(first.v[k], first.v[(k + 1) % 3])] >= 2;
      for (std::size_t x = flap ? i : i + 1; x < j; ++x) {
        faces[sorted[x].second].alive = false;
        duplicates.add(sorted[x].second, listed);
      }
    }
    std::sort(duplicates.listed.begin(), duplicates.listed.end());
  }
  std::vector<int> zero_area;
  for (std::size_t f = nf; f-- > 0;)
    if (faces[f].alive && degenerate(mesh, faces[f].v, options.degenerate_area))
      zero_area.push_back(int(f));
  if (!zero_area.empty()) {
    std::reverse(zero_area.begin(), zero_area.end());
    Degenerates(mesh, faces, options.degenerate_area).run(zero_area, degenerates, listed);
    // A flip among other zero-area faces can make another (coordinates so small that every
    // face of a cluster has no area): what is still degenerate goes.
    for (std::size_t f = 0; f < nf; ++f)
      if (faces[f].alive && degenerate(mesh, faces[f].v, options.degenerate_area)) {
        faces[f].alive = false;
        degenerates.add(faces[f].origin, listed);
      }
  }
  std::sort(degenerates.listed.begin(), degenerates.listed.end());
  report("removed_degenerate_faces", degenerates,
         "removed " + plural(degenerates.count, "degenerate face", "degenerate faces") +
             " (zero area or a repeated vertex) without opening the surface",
         "faces");
  report("removed_duplicate_faces", duplicates,
         "removed " + plural(duplicates.count, "duplicate face", "duplicate faces") +
             " (the same three vertices as another face)",
         "faces");
  finish_repair(mesh, faces, options, out);
  return out;
}

}  // namespace papernet
