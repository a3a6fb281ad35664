#pragma once

#include <algorithm>
#include <cmath>
#include <limits>

namespace papernet {

/// A point or vector in the plane of the net.
struct Vec2 {
  double x = 0, y = 0;
};

/// A point or vector in space.
struct Vec3 {
  double x = 0, y = 0, z = 0;
};

inline Vec2 operator+(Vec2 a, Vec2 b) { return {a.x + b.x, a.y + b.y}; }
inline Vec2 operator-(Vec2 a, Vec2 b) { return {a.x - b.x, a.y - b.y}; }
inline Vec2 operator*(double s, Vec2 a) { return {s * a.x, s * a.y}; }
inline bool operator==(Vec2 a, Vec2 b) { return a.x == b.x && a.y == b.y; }
inline double dot(Vec2 a, Vec2 b) { return a.x * b.x + a.y * b.y; }
/// z component of the 3D cross product: positive when b is counter-clockwise of a.
inline double cross(Vec2 a, Vec2 b) { return a.x * b.y - a.y * b.x; }
inline double norm(Vec2 a) { return std::sqrt(dot(a, a)); }

inline Vec3 operator+(Vec3 a, Vec3 b) { return {a.x + b.x, a.y + b.y, a.z + b.z}; }
inline Vec3 operator-(Vec3 a, Vec3 b) { return {a.x - b.x, a.y - b.y, a.z - b.z}; }
inline Vec3 operator*(double s, Vec3 a) { return {s * a.x, s * a.y, s * a.z}; }
inline bool operator==(Vec3 a, Vec3 b) { return a.x == b.x && a.y == b.y && a.z == b.z; }
inline double dot(Vec3 a, Vec3 b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
inline Vec3 cross(Vec3 a, Vec3 b) {
  return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
}
inline double norm(Vec3 a) { return std::sqrt(dot(a, a)); }

/// An axis-aligned box in the plane. Box2::empty() holds nothing (lo above hi) until a point is
/// added.
struct Box2 {
  Vec2 lo, hi;
  static Box2 empty() {
    constexpr double inf = std::numeric_limits<double>::infinity();
    return {{inf, inf}, {-inf, -inf}};
  }
  void add(Vec2 p) {
    lo = {std::min(lo.x, p.x), std::min(lo.y, p.y)};
    hi = {std::max(hi.x, p.x), std::max(hi.y, p.y)};
  }
  void add(const Box2& b) {
    lo = {std::min(lo.x, b.lo.x), std::min(lo.y, b.lo.y)};
    hi = {std::max(hi.x, b.hi.x), std::max(hi.y, b.hi.y)};
  }
  Vec2 size() const { return hi - lo; }
};

/// An axis-aligned box in space; as Box2.
struct Box3 {
  Vec3 lo, hi;
  static Box3 empty() {
    constexpr double inf = std::numeric_limits<double>::infinity();
    return {{inf, inf, inf}, {-inf, -inf, -inf}};
  }
  void add(Vec3 p) {
    lo = {std::min(lo.x, p.x), std::min(lo.y, p.y), std::min(lo.z, p.z)};
    hi = {std::max(hi.x, p.x), std::max(hi.y, p.y), std::max(hi.z, p.z)};
  }
  Vec3 size() const { return hi - lo; }
};

/// A rotation about the origin followed by a translation: x -> to + R (x - from).
struct Rigid {
  Vec2 from, to;
  double c = 1, s = 0;
  Vec2 operator()(Vec2 x) const {
    const Vec2 d = x - from;
    return {to.x + c * d.x - s * d.y, to.y + s * d.x + c * d.y};
  }
};

}  // namespace papernet
