#pragma once
// The block of cells a rank owns, in global cell indices: [xs, xs+xm) x [ys, ys+ym) x [zs, zs+zm).
// A planar or axisymmetric mesh has one layer along z (zs = 0, zm = 1).
namespace granflow {
struct CellBox {
  int xs = 0, ys = 0, xm = 0, ym = 0;
  int zs = 0, zm = 1;
  int xe() const { return xs + xm; }
  int ye() const { return ys + ym; }
  int ze() const { return zs + zm; }
  bool holds(int i, int j, int k) const { return i >= xs && i < xe() && j >= ys && j < ye() && k >= zs && k < ze(); }
};
}  // namespace granflow
