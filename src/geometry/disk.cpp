// exact area of a disk inside an axis-aligned rectangle (φ of disk packings, docs/physics.md §2.5):
// inclusion–exclusion over four "quadrant" areas, each an integral of chord lengths with the
// closed-form antiderivative ∫√(1−x²)dx = (x√(1−x²) + asin x)/2
#include <algorithm>
#include <cmath>
#include <numbers>

#include "geometry/polygon.hpp"

namespace gs {

namespace {

// antiderivative of the unit circle's upper half, ∫√(1−x²)dx, for x in [−1, 1]
double half_chord_integral(double x) {
  x = std::clamp(x, -1.0, 1.0);
  return 0.5 * (x * std::sqrt(std::max(0.0, 1.0 - x * x)) + std::asin(x));
}

// area of the unit disk in the quadrant {x >= a, y >= b}.
// The vertical chord at x is cut from below by y = b: its length is √(1−x²) − b where
// |x| <= x_b = √(1−b²), and outside that band either 0 (b >= 0, the chord lies below b) or the
// full 2√(1−x²) (b < 0, the chord lies above b). Integrate each band over [a, 1].
double quadrant_area(double a, double b) {
  if (a >= 1.0 || b >= 1.0) return 0.0;
  a = std::max(a, -1.0);
  const auto I = half_chord_integral;
  if (b <= -1.0) return 2.0 * (I(1.0) - I(a));
  const double xb = std::sqrt(std::max(0.0, 1.0 - b * b));
  double area = 0.0;
  // central band |x| <= x_b: √(1−x²) − b
  const double lo = std::max(a, -xb);
  if (lo < xb) area += (I(xb) - I(lo)) - b * (xb - lo);
  // outer bands: the whole chord when b < 0
  if (b < 0.0) {
    if (a < -xb) area += 2.0 * (I(-xb) - I(a));
    const double lo2 = std::max(a, xb);
    area += 2.0 * (I(1.0) - I(lo2));
  }
  return area;
}

}  // namespace

double disk_area_in_rect(Vec2 c, double r, double x0, double y0, double x1, double y1) {
  if (!(r > 0.0) || !(x0 < x1) || !(y0 < y1)) return 0.0;
  // the disk's bounding box decides the easy cases exactly
  if (c.x + r <= x0 || c.x - r >= x1 || c.y + r <= y0 || c.y - r >= y1) return 0.0;
  if (c.x - r >= x0 && c.x + r <= x1 && c.y - r >= y0 && c.y + r <= y1)
    return std::numbers::pi * r * r;
  // unit-disk coordinates of the rectangle, then inclusion–exclusion of the quadrants
  const double u0 = (x0 - c.x) / r, u1 = (x1 - c.x) / r;
  const double v0 = (y0 - c.y) / r, v1 = (y1 - c.y) / r;
  const double q =
      quadrant_area(u0, v0) - quadrant_area(u1, v0) - quadrant_area(u0, v1) + quadrant_area(u1, v1);
  return std::max(0.0, q) * r * r;
}

}  // namespace gs
