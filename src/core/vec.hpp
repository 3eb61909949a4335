// 2D vector for hot loops: a plain aggregate (two doubles, trivially copyable) so that
// structure-of-arrays code and pure force/geometry functions stay simple and inlinable.
// Eigen is used where real linear algebra is needed (fits, least squares).
#pragma once
#include <cmath>

namespace gs {

struct Vec2 {
  double x = 0.0;
  double y = 0.0;

  constexpr Vec2 operator+(Vec2 o) const { return {x + o.x, y + o.y}; }
  constexpr Vec2 operator-(Vec2 o) const { return {x - o.x, y - o.y}; }
  constexpr Vec2 operator-() const { return {-x, -y}; }
  constexpr Vec2 operator*(double s) const { return {x * s, y * s}; }
  constexpr Vec2 operator/(double s) const { return {x / s, y / s}; }
  constexpr Vec2& operator+=(Vec2 o) {
    x += o.x;
    y += o.y;
    return *this;
  }
  constexpr Vec2& operator-=(Vec2 o) {
    x -= o.x;
    y -= o.y;
    return *this;
  }
  constexpr Vec2& operator*=(double s) {
    x *= s;
    y *= s;
    return *this;
  }
  constexpr bool operator==(const Vec2&) const = default;
};

constexpr Vec2 operator*(double s, Vec2 v) { return {s * v.x, s * v.y}; }
constexpr double dot(Vec2 a, Vec2 b) { return a.x * b.x + a.y * b.y; }
/// 2D scalar cross product a × b
constexpr double cross(Vec2 a, Vec2 b) { return a.x * b.y - a.y * b.x; }
/// ω × r for a scalar angular velocity ω (out of plane)
constexpr Vec2 cross(double w, Vec2 r) { return {-w * r.y, w * r.x}; }
/// the vector rotated by +90°
constexpr Vec2 perp(Vec2 a) { return {-a.y, a.x}; }
constexpr double norm2(Vec2 a) { return dot(a, a); }
inline double norm(Vec2 a) { return std::sqrt(dot(a, a)); }
inline Vec2 normalized(Vec2 a) { return a / norm(a); }
inline Vec2 rotate(Vec2 a, double c, double s) { return {c * a.x - s * a.y, s * a.x + c * a.y}; }

}  // namespace gs
