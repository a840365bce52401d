#include "serial_vof_field.hpp"

#include "models/interface/material_transport.hpp"

#include <algorithm>
#include <limits>
#include <stdexcept>
#include <utility>

namespace granflow::interface {

namespace {

constexpr int g = SerialVofField::kGhosts;

// Owned widths plus `g` mirrored ghost widths on each side.
std::vector<double> with_ghost_widths(const std::vector<double>& w) {
  const int n = static_cast<int>(w.size());
  if (n < g) throw std::invalid_argument("SerialVofField: need at least 2 cells per direction");
  std::vector<double> out(static_cast<std::size_t>(n + 2 * g));
  for (int k = -g; k < n + g; ++k) {
    const int src = k < 0 ? -k - 1 : (k >= n ? 2 * n - k - 1 : k);
    out[k + g] = w[src];
  }
  return out;
}

// Face coordinates for indices -g .. n+g, the face of index 0 at `origin`.
std::vector<double> face_coordinates(const std::vector<double>& widths_with_ghosts, double origin) {
  const int n = static_cast<int>(widths_with_ghosts.size()) - 2 * g;
  std::vector<double> f(static_cast<std::size_t>(n + 2 * g + 1));
  f[g] = origin;
  for (int k = 0; k < n + g; ++k) f[k + g + 1] = f[k + g] + widths_with_ghosts[k + g];
  for (int k = -1; k >= -g; --k) f[k + g] = f[k + g + 1] - widths_with_ghosts[k + g];
  return f;
}

}  // namespace

SerialVofField::SerialVofField(int mx, int my, double lx, double ly, double x0, double y0)
    : SerialVofField(std::vector<double>(static_cast<std::size_t>(mx), lx / mx),
                     std::vector<double>(static_cast<std::size_t>(my), ly / my), x0, y0) {}

SerialVofField::SerialVofField(const std::vector<double>& dx, const std::vector<double>& dy,
                               double x0, double y0)
    : mx_(static_cast<int>(dx.size())),
      my_(static_cast<int>(dy.size())),
      dx_(with_ghost_widths(dx)),
      dy_(with_ghost_widths(dy)),
      xf_(face_coordinates(dx_, x0)),
      yf_(face_coordinates(dy_, y0)),
      c_(mx_, my_, g),
      tmp_(mx_, my_, g),
      cc_(mx_, my_, g),
      ux_(mx_, my_, g),
      uy_(mx_, my_, g) {}

void SerialVofField::fill_ghosts(GhostedArray2& a) const {
  const auto wrap = [](int k, int n) { return ((k % n) + n) % n; };
  double** r = a.rows();
  for (int j = -g; j < my_ + g; ++j) {
    const bool row_owned = j >= 0 && j < my_;
    for (int i = -g; i < mx_ + g; ++i) {
      if (row_owned && i == 0) i = mx_;  // skip owned cells
      switch (bc_) {
        case VofBoundary::Empty:
          r[j][i] = 0.0;
          break;
        case VofBoundary::ZeroGradient:
          r[j][i] = r[std::clamp(j, 0, my_ - 1)][std::clamp(i, 0, mx_ - 1)];
          break;
        case VofBoundary::Periodic:
          r[j][i] = r[wrap(j, my_)][wrap(i, mx_)];
          break;
      }
    }
  }
}

void SerialVofField::set_axisymmetric(bool on) {
  r_face_.clear();
  r_centre_.clear();
  if (!on) return;
  for (int i = -g; i < mx_ + g; ++i) {
    r_face_.push_back(x_face(i + 1));
    r_centre_.push_back(x_centre(i));
  }
}

RadialWeights SerialVofField::radial() const {
  if (r_face_.empty()) return {};
  return {r_face_.data() + g, r_centre_.data() + g};
}

double SerialVofField::volume(int i, int j) const {
  return dx()[i] * dy()[j] * (r_centre_.empty() ? 1.0 : r_centre_[i + g]);
}

void SerialVofField::set_velocity_from_stream_function(
    const std::function<double(double, double)>& psi) {
  for (int j = -g; j < my_ + g; ++j) {
    for (int i = -g; i < mx_ + g; ++i) {
      // Corner values: (i+1/2, j-1/2), (i+1/2, j+1/2), (i-1/2, j+1/2).
      const double p_se = psi(x_face(i + 1), y_face(j));
      const double p_ne = psi(x_face(i + 1), y_face(j + 1));
      const double p_nw = psi(x_face(i), y_face(j + 1));
      // Axisymmetric: the face fluxes r_f u dz and r_c v dr are the differences of psi.
      const double r_east = r_face_.empty() ? 1.0 : x_face(i + 1);
      const double r_mid = r_face_.empty() ? 1.0 : x_centre(i);
      ux_(i, j) = r_east != 0.0 ? (p_ne - p_se) / (dy()[j] * r_east) : 0.0;
      uy_(i, j) = -(p_ne - p_nw) / (dx()[i] * r_mid);
    }
  }
}

double SerialVofField::max_courant(double dt) const {
  return std::max(max_sweep_courant(0, dt, ux_.rows(), dx(), dy(), owned(), radial()),
                  max_sweep_courant(1, dt, uy_.rows(), dx(), dy(), owned()));
}

void SerialVofField::track_materials(int count) {
  materials_.clear();
  material_start_.clear();
  material_tmp_.clear();
  for (int k = 0; k < count; ++k) {
    materials_.emplace_back(mx_, my_, g);
    material_start_.emplace_back(mx_, my_, g);
    material_tmp_.emplace_back(mx_, my_, g);
  }
  face_soil_ = GhostedArray2(mx_, my_, g);
}

void SerialVofField::set_material_densities(std::vector<double> densities) {
  densities_ = std::move(densities);
  face_density_ = GhostedArray2(mx_, my_, g);
  for (auto& a : mass_through_) a = GhostedArray2(mx_, my_, g);
}

void SerialVofField::sweep(int axis, double dt, const GhostedArray2& from, GhostedArray2& to,
                           std::vector<GhostedArray2>& m_from, std::vector<GhostedArray2>& m_to) {
  const auto* velocity = axis == 0 ? ux_.rows() : uy_.rows();
  if (materials_.empty()) {
    vof_sweep(axis, dt, from.rows(), velocity, cc_.rows(), dx(), dy(), owned(), to.rows(), radial());
  } else {
    for (int j = -g; j < my_ + g; ++j)
      for (int i = -g; i < mx_ + g; ++i) face_soil_(i, j) = 0.0;
    vof_sweep(axis, dt, from.rows(), velocity, cc_.rows(), dx(), dy(), owned(), to.rows(), radial(), face_soil_.rows());
    std::vector<const double* const*> m, m0;
    std::vector<double**> m_new;
    for (std::size_t k = 0; k < materials_.size(); ++k) {
      m.push_back(m_from[k].rows());
      m0.push_back(material_start_[k].rows());
      m_new.push_back(m_to[k].rows());
    }
    const bool mass = !densities_.empty();
    material_sweep(axis, dt, from.rows(), to.rows(), int(m.size()), m.data(), m0.data(), velocity, face_soil_.rows(),
                   cc_.rows(), dx(), dy(), owned(), m_new.data(), radial(), mass ? densities_.data() : nullptr,
                   mass ? face_density_.rows() : nullptr);
    if (mass)
      for (int j = -1; j < my_; ++j)
        for (int i = -1; i < mx_; ++i)
          if (face_soil_(i, j) != 0.0) mass_through_[axis](i, j) += face_soil_(i, j) * face_density_(i, j);
    for (auto& a : m_to) fill_ghosts(a);
  }
  fill_ghosts(to);
}

void SerialVofField::step(double dt) {
  fill_ghosts(c_);
  // Held fixed over both sweeps (Weymouth & Yue): the dilatation terms then cancel exactly.
  dilatation_indicator(c_.rows(), owned(), cc_.rows());
  for (std::size_t k = 0; k < materials_.size(); ++k) {
    fill_ghosts(materials_[k]);
    for (int j = 0; j < my_; ++j)
      for (int i = 0; i < mx_; ++i) material_start_[k](i, j) = materials_[k](i, j);
  }
  // Alternating the order (Strang-like) removes the directional bias of a fixed x-y order.
  const int first = steps_ % 2 == 0 ? 0 : 1;
  const int second = 1 - first;
  sweep(first, dt, c_, tmp_, materials_, material_tmp_);
  sweep(second, dt, tmp_, c_, material_tmp_, materials_);
  ++steps_;
}

double SerialVofField::material_volume(int k) const {
  double v = 0.0;
  for (int j = 0; j < my_; ++j)
    for (int i = 0; i < mx_; ++i) v += c_(i, j) * materials_[k](i, j) * volume(i, j);
  return v;
}

double SerialVofField::total_volume() const {
  double v = 0.0;
  for (int j = 0; j < my_; ++j)
    for (int i = 0; i < mx_; ++i) v += c_(i, j) * volume(i, j);
  return v;
}

double SerialVofField::min_fraction() const {
  double m = std::numeric_limits<double>::infinity();
  for (int j = 0; j < my_; ++j)
    for (int i = 0; i < mx_; ++i) m = std::min(m, c_(i, j));
  return m;
}

double SerialVofField::max_fraction() const {
  double m = -std::numeric_limits<double>::infinity();
  for (int j = 0; j < my_; ++j)
    for (int i = 0; i < mx_; ++i) m = std::max(m, c_(i, j));
  return m;
}

}  // namespace granflow::interface
