#include "core/unfold/net_check.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <string>
#include <utility>

namespace papernet {

namespace {

class Collector {
 public:
  Collector(NetCheckReport& report, std::size_t max) : report_(report), max_(max) {}
  void fail(const std::string& message) {
    ++report_.failure_count;
    if (report_.failures.size() < max_) report_.failures.push_back(message);
  }

 private:
  NetCheckReport& report_;
  std::size_t max_;
};

std::string face_name(std::size_t f) { return "face " + std::to_string(f); }

double orient(Vec2 a, Vec2 b, Vec2 c) { return cross(b - a, c - a); }

// Segments pq and rs cross at a point inside both: each one's ends lie strictly on opposite
// sides of the other's line, farther than `tiny` from it. Collinear and touching segments do
// not cross; the callers shrink triangles first, so touching never means overlapping.
bool segments_cross(Vec2 p, Vec2 q, Vec2 r, Vec2 s, double tiny) {
  const double lrs = norm(s - r), lpq = norm(q - p);
  const double d1 = orient(r, s, p), d2 = orient(r, s, q), d3 = orient(p, q, r),
               d4 = orient(p, q, s);
  const auto apart = [tiny](double x, double y, double len) {
    return (x > tiny * len && y < -tiny * len) || (x < -tiny * len && y > tiny * len);
  };
  return apart(d1, d2, lrs) && apart(d3, d4, lpq);
}

// Point inside or on the counter-clockwise triangle t.
bool inside(const std::array<Vec2, 3>& t, Vec2 p) {
  return orient(t[0], t[1], p) >= 0 && orient(t[1], t[2], p) >= 0 && orient(t[2], t[0], p) >= 0;
}

// The triangle shrunk towards its incentre by `d`; false when it vanishes (thinner than d).
bool shrink(const std::array<Vec2, 3>& t, double d, std::array<Vec2, 3>& out) {
  const double a = norm(t[1] - t[2]), b = norm(t[2] - t[0]), c = norm(t[0] - t[1]);
  const double perimeter = a + b + c;
  const Vec2 centre = (1.0 / perimeter) * (a * t[0] + b * t[1] + c * t[2]);
  const double inradius = std::abs(orient(t[0], t[1], t[2])) / perimeter;
  if (inradius <= d) return false;
  const double s = 1 - d / inradius;
  for (int k = 0; k < 3; ++k) out[k] = centre + s * (t[k] - centre);
  return true;
}

// Interiors of two counter-clockwise triangles intersect by more than d.
bool interiors_meet(const std::array<Vec2, 3>& t, const std::array<Vec2, 3>& u, double d) {
  const double tiny = 1e-6 * d;
  std::array<Vec2, 3> a, b;
  if (!shrink(t, d, a) || !shrink(u, d, b)) return false;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j)
      if (segments_cross(a[i], a[(i + 1) % 3], b[j], b[(j + 1) % 3], tiny)) return true;
  for (int k = 0; k < 3; ++k)
    if (inside(a, b[k]) || inside(b, a[k])) return true;
  return false;
}

}  // namespace

std::string NetCheckReport::summary() const {
  std::string s;
  for (const std::string& f : failures) s += (s.empty() ? "" : "; ") + f;
  if (failure_count > failures.size())
    s += "; and " + std::to_string(failure_count - failures.size()) + " more";
  return s;
}

NetCheckReport check_net(const Mesh& mesh, const Net& net, const NetCheckOptions& options) {
  NetCheckReport report;
  Collector out(report, options.max_messages);
  const std::size_t nf = mesh.faces.size();
  if (net.parent.size() != nf || net.points.size() != nf) {
    out.fail("the net has " + std::to_string(net.parent.size()) + " parents and " +
             std::to_string(net.points.size()) + " triangles for " + std::to_string(nf) + " faces");
    return report;
  }
  const double diag = bounding_box_diagonal(mesh);
  const double len_tol = options.length_tolerance * diag;

  // Congruence and orientation.
  for (std::size_t f = 0; f < nf; ++f) {
    const auto& c = mesh.faces[f];
    const auto& p = net.points[f];
    for (int k = 0; k < 3; ++k) {
      const double l3 = norm(mesh.vertices[c[(k + 1) % 3]] - mesh.vertices[c[k]]);
      const double l2 = norm(p[(k + 1) % 3] - p[k]);
      if (!(std::abs(l3 - l2) <= len_tol)) {
        out.fail(face_name(f) + " edge " + std::to_string(k) + " is " + std::to_string(l2) +
                 " long in the net but " + std::to_string(l3) + " on the mesh");
        break;
      }
    }
    if (!(orient(p[0], p[1], p[2]) > 0)) out.fail(face_name(f) + " is flipped in the net");
  }

  // One spanning tree: one root, parents in range, every face reaches the root.
  std::size_t roots = 0;
  bool parents_ok = true;
  for (std::size_t f = 0; f < nf; ++f) {
    const int p = net.parent[f];
    if (p == -1) {
      ++roots;
    } else if (p < 0 || static_cast<std::size_t>(p) >= nf || static_cast<std::size_t>(p) == f) {
      out.fail(face_name(f) + " has parent " + std::to_string(p) + ", which is not a face");
      parents_ok = false;
    }
  }
  if (roots != 1) out.fail("the net has " + std::to_string(roots) + " roots instead of one");
  if (parents_ok) {
    std::vector<int> state(nf, 0);  // 0 unknown, 1 on the current walk, 2 reaches the root
    std::vector<std::size_t> walk;
    for (std::size_t s = 0; s < nf; ++s) {
      walk.clear();
      std::size_t f = s;
      for (;;) {
        if (state[f] == 2) break;
        if (state[f] == 1) {
          out.fail("the parent links of " + face_name(f) + " form a cycle");
          break;
        }
        state[f] = 1;
        walk.push_back(f);
        if (net.parent[f] < 0) break;
        f = static_cast<std::size_t>(net.parent[f]);
      }
      for (std::size_t w : walk) state[w] = 2;
    }
  }

  // Glued links: a shared mesh edge at the same 2D place in both faces.
  for (std::size_t f = 0; f < nf && parents_ok; ++f) {
    const int p = net.parent[f];
    if (p < 0) continue;
    int shared = 0;
    bool glued = true;
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j)
        if (mesh.faces[f][i] == mesh.faces[p][j]) {
          ++shared;
          if (!(norm(net.points[f][i] - net.points[p][j]) <= len_tol)) glued = false;
        }
    if (shared < 2)
      out.fail(face_name(f) + " and its parent " + face_name(p) + " share no edge");
    else if (!glued)
      out.fail(face_name(f) + " is not glued to its parent " + face_name(p) +
               ": the shared edge is at different places");
  }

  // Overlaps, over a grid of cells about an average edge long.
  Box2 box = Box2::empty();
  double edge_sum = 0;
  for (const auto& t : net.points)
    for (int k = 0; k < 3; ++k) {
      box.add(t[k]);
      edge_sum += norm(t[(k + 1) % 3] - t[k]);
    }
  const double lo_x = box.lo.x, lo_y = box.lo.y;
  if (nf == 0 || !std::isfinite(lo_x) || !std::isfinite(lo_y) || !(edge_sum > 0)) return report;
  const double cell = edge_sum / (3.0 * static_cast<double>(nf));
  std::map<std::pair<long long, long long>, std::vector<std::size_t>> grid;
  const auto range = [&](const std::array<Vec2, 3>& t) {
    double x0 = t[0].x, x1 = t[0].x, y0 = t[0].y, y1 = t[0].y;
    for (const Vec2 v : t) {
      x0 = std::min(x0, v.x), x1 = std::max(x1, v.x);
      y0 = std::min(y0, v.y), y1 = std::max(y1, v.y);
    }
    const auto c = [&](double v, double lo) {
      return static_cast<long long>(std::floor((v - lo) / cell));
    };
    return std::array<long long, 4>{c(x0, lo_x), c(y0, lo_y), c(x1, lo_x), c(y1, lo_y)};
  };
  for (std::size_t f = 0; f < nf; ++f) {
    const auto r = range(net.points[f]);
    if ((r[2] - r[0] + 1) * (r[3] - r[1] + 1) > 4096) {
      out.fail(face_name(f) + " is far larger than an average face in the net");
      return report;
    }
    for (long long x = r[0]; x <= r[2]; ++x)
      for (long long y = r[1]; y <= r[3]; ++y) grid[{x, y}].push_back(f);
  }
  const double d = options.overlap_tolerance * diag;
  std::vector<std::size_t> tested(nf, SIZE_MAX);
  for (std::size_t f = 0; f < nf; ++f) {
    const auto r = range(net.points[f]);
    for (long long x = r[0]; x <= r[2]; ++x)
      for (long long y = r[1]; y <= r[3]; ++y)
        for (std::size_t g : grid[{x, y}]) {
          if (g <= f || tested[g] == f) continue;
          tested[g] = f;
          if (interiors_meet(net.points[f], net.points[g], d)) {
            ++report.overlapping_pairs;
            out.fail(face_name(f) + " and " + face_name(g) + " overlap");
          }
        }
  }
  return report;
}

}  // namespace papernet
