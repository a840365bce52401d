#include "models/interface/plic_geometry.hpp"

#include <algorithm>
#include <cmath>

namespace granflow::interface {

namespace {

Normal2 normalise_l1(double mx, double my) {
  const double s = std::abs(mx) + std::abs(my);
  if (!(s > 0.0) || !std::isfinite(s)) return {0.0, 0.0};
  return {mx / s, my / s};
}

double sign_or_zero(double v) { return v > 0.0 ? 1.0 : (v < 0.0 ? -1.0 : 0.0); }

// The part of a rectangle on the soil side of a line, about the rectangle's centre (which keeps the
// moments free of cancellation): its area, its first moment in X, and the line's chord through the
// rectangle (length, and the integral of X along it).
struct ClippedRectangle {
  double area = 0.0;
  double moment_x = 0.0;
  double chord = 0.0;
  double chord_x = 0.0;
};

ClippedRectangle clip_rectangle(Normal2 n, double alpha, double hx, double hy) {
  ClippedRectangle out;
  const double reach = std::abs(n.nx) * hx + std::abs(n.ny) * hy;
  if (alpha <= -reach) return out;
  if (alpha >= reach) {
    out.area = 4.0 * hx * hy;
    return out;
  }
  // One Sutherland-Hodgman pass against n.X <= alpha over the corners taken anticlockwise.
  const double px[4] = {-hx, hx, hx, -hx}, py[4] = {-hy, -hy, hy, hy};
  double qx[6], qy[6], ex[2] = {0.0, 0.0}, ey[2] = {0.0, 0.0};
  int m = 0, crossings = 0;
  for (int k = 0; k < 4; ++k) {
    const int l = (k + 1) % 4;
    const double da = n.nx * px[k] + n.ny * py[k] - alpha, db = n.nx * px[l] + n.ny * py[l] - alpha;
    if (da <= 0.0) {
      qx[m] = px[k];
      qy[m++] = py[k];
    }
    if ((da < 0.0 && db > 0.0) || (da > 0.0 && db < 0.0)) {
      const double t = da / (da - db);
      qx[m] = px[k] + t * (px[l] - px[k]);
      qy[m] = py[k] + t * (py[l] - py[k]);
      if (crossings < 2) {
        ex[crossings] = qx[m];
        ey[crossings++] = qy[m];
      }
      ++m;
    }
  }
  double twice_area = 0.0, six_moment = 0.0;
  for (int k = 0; k < m; ++k) {
    const int l = (k + 1) % m;
    const double cross = qx[k] * qy[l] - qx[l] * qy[k];
    twice_area += cross;
    six_moment += (qx[k] + qx[l]) * cross;
  }
  out.area = 0.5 * twice_area;
  out.moment_x = six_moment / 6.0;
  if (crossings == 2) {
    out.chord = std::hypot(ex[1] - ex[0], ey[1] - ey[0]);
    out.chord_x = out.chord * 0.5 * (ex[0] + ex[1]);
  }
  return out;
}

}  // namespace

double unit_square_fraction(double mx, double my, double a) {
  // Reflect so that both coefficients are non-negative; the region then grows from the corner
  // (0,0) as a increases from 0 to mx + my.
  if (mx < 0.0) {
    a -= mx;
    mx = -mx;
  }
  if (my < 0.0) {
    a -= my;
    my = -my;
  }
  if (a <= 0.0) return 0.0;
  const double n1 = std::min(mx, my);
  const double n2 = std::max(mx, my);
  if (a >= n1 + n2) return 1.0;
  // Triangle / trapezoid / complement-of-triangle, each written without cancellation so that
  // tiny n1 (near axis-aligned lines) keeps full relative accuracy.
  if (a < n1) return a * a / (2.0 * n1 * n2);
  if (a <= n2) return (a - 0.5 * n1) / n2;
  const double b = n1 + n2 - a;
  return 1.0 - b * b / (2.0 * n1 * n2);
}

double line_alpha(double c, Normal2 n) {
  // Scardovelli & Zaleski (2000): invert the three branches of unit_square_fraction in the
  // reflected frame (n1 <= n2, n1 + n2 = 1), then shift back to the centred, unreflected frame.
  c = std::clamp(c, 0.0, 1.0);
  const double n1 = std::min(std::abs(n.nx), std::abs(n.ny));
  const double n2 = std::max(std::abs(n.nx), std::abs(n.ny));
  if (!(n2 > 0.0)) return 0.0;
  const double v1 = 0.5 * n1 / n2;  // fraction at which the triangle branch ends
  double a;
  if (c <= v1)
    a = std::sqrt(2.0 * c * n1 * n2);
  else if (c <= 1.0 - v1)
    a = c * n2 + 0.5 * n1;
  else
    a = n1 + n2 - std::sqrt(2.0 * n1 * n2 * (1.0 - c));
  if (n.nx < 0.0) a += n.nx;
  if (n.ny < 0.0) a += n.ny;
  return a - 0.5 * (n.nx + n.ny);
}

double cell_fraction(Normal2 n, double alpha) {
  return unit_square_fraction(n.nx, n.ny, alpha + 0.5 * (n.nx + n.ny));
}

double rectangle_fraction(Normal2 n, double alpha, double x0, double x1, double y0, double y1) {
  // Map the rectangle onto [0,1]^2: X = x0 + (x1 - x0) xi, Y = y0 + (y1 - y0) eta.
  return unit_square_fraction(n.nx * (x1 - x0), n.ny * (y1 - y0), alpha - n.nx * x0 - n.ny * y0);
}

double weighted_rectangle_fraction(Normal2 n, double alpha, double rho, double x0, double x1, double y0,
                                   double y1) {
  const double xm = 0.5 * (x0 + x1), ym = 0.5 * (y0 + y1), hx = 0.5 * (x1 - x0), hy = 0.5 * (y1 - y0);
  if (!(hx > 0.0 && hy > 0.0)) return 0.0;
  const ClippedRectangle part = clip_rectangle(n, alpha - n.nx * xm - n.ny * ym, hx, hy);
  const double weight = rho + xm;  // r / dx at the rectangle's centre
  const double f = (part.area + part.moment_x / weight) / (4.0 * hx * hy);
  return std::clamp(f, 0.0, 1.0);
}

double weighted_line_alpha(double c, Normal2 n, double rho) {
  if (c <= 0.0) return -0.5;
  if (c >= 1.0) return 0.5;
  // Newton on the weighted share (a piecewise cubic, increasing in alpha) from the planar line,
  // kept inside a bracket that bisects where a step would leave it or the chord vanishes.
  const double norm = std::hypot(n.nx, n.ny);
  double lo = -0.5, hi = 0.5, alpha = line_alpha(c, n);
  for (int k = 0; k < 60; ++k) {
    const ClippedRectangle part = clip_rectangle(n, alpha, 0.5, 0.5);
    const double r = part.area + part.moment_x / rho - c;
    if (std::abs(r) <= 1e-16) break;
    (r > 0.0 ? hi : lo) = alpha;
    const double slope = (part.chord + part.chord_x / rho) / norm;
    double next = slope > 0.0 ? alpha - r / slope : 0.5 * (lo + hi);
    if (!(next > lo && next < hi)) next = 0.5 * (lo + hi);
    if (next == alpha) break;
    alpha = next;
  }
  return alpha;
}

CellLine cell_line(const Block3x3& b, double rho) {
  double lo = b.c[0][0], hi = b.c[0][0];
  for (const auto& row : b.c)
    for (const double v : row) {
      lo = std::min(lo, v);
      hi = std::max(hi, v);
    }
  if (hi - lo < 1e-8) return {};
  const Normal2 n = myc_normal(b);
  if (n.nx == 0.0 && n.ny == 0.0) return {};
  return {true, n, rho > 0.0 ? weighted_line_alpha(b.c[1][1], n, rho) : line_alpha(b.c[1][1], n)};
}

double side_fraction(Normal2 n, double alpha, int axis, int sign) {
  // Along the side, with s in [-0.5, 0.5] the coordinate along it, the soil is where a s <= b.
  const double a = axis == 0 ? n.ny : n.nx;
  const double b = alpha - 0.5 * sign * (axis == 0 ? n.nx : n.ny);
  if (a == 0.0) return b >= 0.0 ? 1.0 : 0.0;
  const double f = a > 0.0 ? b / a + 0.5 : 0.5 - b / a;
  return std::clamp(f, 0.0, 1.0);
}

double weighted_side_fraction(Normal2 n, double alpha, int axis, int sign, double rho) {
  const double f = side_fraction(n, alpha, axis, sign);
  if (axis == 0) return f;
  // Along a side normal to y the covered length f starts at the end the soil lies towards: X = -0.5
  // where the normal points to +X, X = 0.5 where it points to -X. Its share is the integral of
  // (rho + X) over it, over rho, the side's.
  const double lo = n.nx < 0.0 ? 0.5 - f : -0.5;
  return std::clamp(f * (rho + lo + 0.5 * f) / rho, 0.0, 1.0);
}

Normal2 to_physical(Normal2 n, double dx, double dy) { return normalise_l1(n.nx / dx, n.ny / dy); }

Normal2 youngs_normal(const Block3x3& b) {
  const auto& c = b.c;
  // Distances between the centres of adjacent columns / rows.
  const double hw = 0.5 * (b.dx[0] + b.dx[1]);
  const double he = 0.5 * (b.dx[1] + b.dx[2]);
  const double hs = 0.5 * (b.dy[0] + b.dy[1]);
  const double hn = 0.5 * (b.dy[1] + b.dy[2]);
  // Gradient at each corner of the centre cell, then their mean (the 1-2-1 stencil on a uniform
  // mesh).
  const double gx = ((c[1][2] + c[2][2] - c[1][1] - c[2][1]) / he +
                     (c[0][2] + c[1][2] - c[0][1] - c[1][1]) / he +
                     (c[1][1] + c[2][1] - c[1][0] - c[2][0]) / hw +
                     (c[0][1] + c[1][1] - c[0][0] - c[1][0]) / hw);
  const double gy = ((c[2][1] + c[2][2] - c[1][1] - c[1][2]) / hn +
                     (c[2][0] + c[2][1] - c[1][0] - c[1][1]) / hn +
                     (c[1][1] + c[1][2] - c[0][1] - c[0][2]) / hs +
                     (c[1][0] + c[1][1] - c[0][0] - c[0][1]) / hs);
  // -grad c, expressed in the centre cell's scaled coordinates.
  return normalise_l1(-gx * b.dx[1], -gy * b.dy[1]);
}

Normal2 myc_normal(const Block3x3& b) {
  const auto& c = b.c;
  // Soil thickness of each column and soil width of each row (physical lengths).
  double h[3], w[3];
  for (int k = 0; k < 3; ++k) {
    h[k] = c[0][k] * b.dy[0] + c[1][k] * b.dy[1] + c[2][k] * b.dy[2];
    w[k] = c[k][0] * b.dx[0] + c[k][1] * b.dx[1] + c[k][2] * b.dx[2];
  }
  const double lx = 0.5 * b.dx[0] + b.dx[1] + 0.5 * b.dx[2];
  const double ly = 0.5 * b.dy[0] + b.dy[1] + 0.5 * b.dy[2];
  // Centred candidates in scaled coordinates, major component +-1:
  //   A (interface y = y(x)): (-dh/dx * dx/dy, sign(bottom - top)),
  //   B (interface x = x(y)): (sign(left - right), -dw/dy * dy/dx).
  // On a uniform mesh ax = (c_l - c_r)/2 and by = (c_b - c_t)/2 with c_* the row/column sums.
  const double ax = (h[0] - h[2]) / lx * (b.dx[1] / b.dy[1]);
  const double by = (w[0] - w[2]) / ly * (b.dy[1] / b.dx[1]);
  const Normal2 y = youngs_normal(b);
  if (ax == 0.0 && by == 0.0) return y;
  // The height function along the direction in which the interface is flatter is the accurate
  // one; Youngs' normal is preferred when it is steeper relative to that direction.
  if (std::abs(ax) <= std::abs(by)) {
    const double sa = sign_or_zero(w[0] - w[2]);
    if (std::abs(y.nx) > std::abs(ax) * std::abs(y.ny)) return y;
    return normalise_l1(ax, sa);
  }
  const double sb = sign_or_zero(h[0] - h[2]);
  if (std::abs(y.ny) > std::abs(by) * std::abs(y.nx)) return y;
  return normalise_l1(sb, by);
}

}  // namespace granflow::interface
