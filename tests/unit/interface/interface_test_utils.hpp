// Independent geometry used to set up and check the interface tests: exact clipping of a
// rectangle by a half-plane (Sutherland-Hodgman) and sub-sampled area fractions of shapes.
#pragma once

#include <array>
#include <cmath>
#include <cstddef>
#include <vector>

namespace granflow::interface::test {

struct Pt {
  double x, y;
};

// Area of the rectangle [x0,x1]x[y0,y1] intersected with {p : ax*p.x + ay*p.y <= d}.
inline double clipped_rectangle_area(double x0, double x1, double y0, double y1, double ax,
                                     double ay, double d) {
  const std::array<Pt, 4> rect{{{x0, y0}, {x1, y0}, {x1, y1}, {x0, y1}}};
  std::vector<Pt> out;
  out.reserve(8);
  for (std::size_t k = 0; k < rect.size(); ++k) {
    const Pt p = rect[k];
    const Pt q = rect[(k + 1) % rect.size()];
    const double fp = ax * p.x + ay * p.y - d;
    const double fq = ax * q.x + ay * q.y - d;
    if (fp <= 0.0) out.push_back(p);
    if ((fp < 0.0 && fq > 0.0) || (fp > 0.0 && fq < 0.0)) {
      const double t = fp / (fp - fq);
      out.push_back({p.x + t * (q.x - p.x), p.y + t * (q.y - p.y)});
    }
  }
  double area2 = 0.0;  // shoelace
  for (std::size_t k = 0; k < out.size(); ++k) {
    const Pt p = out[k];
    const Pt q = out[(k + 1) % out.size()];
    area2 += p.x * q.y - q.x * p.y;
  }
  return 0.5 * std::abs(area2);
}

// Fraction of [x0,x1]x[y0,y1] where inside(x, y) holds, by n x n midpoint sampling.
template <class Inside>
double sampled_fraction(double x0, double x1, double y0, double y1, const Inside& inside,
                        int n = 32) {
  int hits = 0;
  for (int b = 0; b < n; ++b)
    for (int a = 0; a < n; ++a)
      if (inside(x0 + (a + 0.5) * (x1 - x0) / n, y0 + (b + 0.5) * (y1 - y0) / n)) ++hits;
  return static_cast<double>(hits) / (static_cast<double>(n) * n);
}

// Zalesak's slotted disc in the unit square: radius 0.15 centred (0.5, 0.75), slot of width 0.05
// cut from the bottom of the disc up to y = 0.85 (length 0.25).
inline bool zalesak_inside(double x, double y) {
  const double dx = x - 0.5, dy = y - 0.75;
  if (dx * dx + dy * dy > 0.15 * 0.15) return false;
  return !(std::abs(dx) < 0.025 && y < 0.85);
}

inline bool circle_inside(double x, double y, double xc, double yc, double r) {
  return (x - xc) * (x - xc) + (y - yc) * (y - yc) <= r * r;
}

}  // namespace granflow::interface::test
