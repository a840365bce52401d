// Energy binned by the Lode angle of the deformation that dissipated it ([YS] Fig. 17): equal bins
// centred on -30, ..., 0, ..., 30 degrees (2 degrees wide by default), so that isochoric shear
// (theta = 0) and the two triaxial limits each have a bin of their own. A value type with no solver inside; the solver adds each cell's dissipated
// energy to the bin of that cell's Lode angle.
#pragma once

#include <algorithm>
#include <cmath>
#include <vector>

namespace granflow::rheology {

class LodeHistogram {
 public:
  // At least 3 bins, made odd, so that one bin is centred on 0.
  explicit LodeHistogram(int bins = 31) : energy_(std::max(bins | 1, 3), 0.0) {}

  int bins() const { return int(energy_.size()); }
  double bin_width_deg() const { return 60.0 / (bins() - 1); }
  double centre_deg(int k) const { return -30.0 + k * bin_width_deg(); }
  double lower_edge_deg(int k) const { return centre_deg(k) - 0.5 * bin_width_deg(); }
  // Bin of a Lode angle in degrees (nearest centre); NaN counts as 0.
  int bin_of(double theta_deg) const {
    if (std::isnan(theta_deg)) return bins() / 2;
    const int k = int(std::lround((theta_deg + 30.0) / bin_width_deg()));
    return std::clamp(k, 0, bins() - 1);
  }
  void add(double theta_deg, double energy) { energy_[bin_of(theta_deg)] += energy; }
  double energy(int k) const { return energy_[k]; }
  std::vector<double>& values() { return energy_; }
  const std::vector<double>& values() const { return energy_; }
  double total() const {
    double s = 0.0;
    for (double e : energy_) s += e;
    return s;
  }

 private:
  std::vector<double> energy_;
};

}  // namespace granflow::rheology
