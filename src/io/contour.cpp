#include "io/contour.hpp"

namespace granflow {

std::vector<Segment> iso_line(const Grid& g, const std::vector<double>& f, double level,
                              const std::function<bool(int, int)>& keep) {
  std::vector<Segment> out;
  const int nx = g.nx(), ny = g.ny();
  auto at = [&](int i, int j) { return f[size_t(j) * nx + i] - level; };
  for (int j = 0; j + 1 < ny; ++j)
    for (int i = 0; i + 1 < nx; ++i) {
      if (keep && !keep(i, j)) continue;
      // Corners counter-clockwise: (i,j) (i+1,j) (i+1,j+1) (i,j+1).
      const double x[4] = {g.xc(i), g.xc(i + 1), g.xc(i + 1), g.xc(i)};
      const double y[4] = {g.yc(j), g.yc(j), g.yc(j + 1), g.yc(j + 1)};
      const double v[4] = {at(i, j), at(i + 1, j), at(i + 1, j + 1), at(i, j + 1)};
      double px[4], py[4];
      int n = 0;
      for (int e = 0; e < 4; ++e) {
        const int a = e, b = (e + 1) % 4;
        if ((v[a] < 0.0) != (v[b] < 0.0)) {
          const double t = v[a] / (v[a] - v[b]);
          px[n] = x[a] + t * (x[b] - x[a]);
          py[n] = y[a] + t * (y[b] - y[a]);
          ++n;
        }
      }
      if (n == 2) {
        out.push_back({px[0], py[0], px[1], py[1]});
      } else if (n == 4) {
        // Saddle: corners 0 and 2 on one side, 1 and 3 on the other; crossing k lies on the edge from
        // corner k to k + 1. The centre's side joins its diagonal: with corner 0's, the lines cut off
        // corners 1 (edges 0 and 1) and 3 (edges 2 and 3), else corners 0 and 2.
        const double centre = 0.25 * (v[0] + v[1] + v[2] + v[3]);
        if ((centre < 0.0) == (v[0] < 0.0)) {
          out.push_back({px[0], py[0], px[1], py[1]});
          out.push_back({px[2], py[2], px[3], py[3]});
        } else {
          out.push_back({px[3], py[3], px[0], py[0]});
          out.push_back({px[1], py[1], px[2], py[2]});
        }
      }
    }
  return out;
}

}  // namespace granflow
