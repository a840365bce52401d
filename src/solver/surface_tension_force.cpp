// The stencils of the surface tension's face source (solver/surface_tension_force.hpp): the smoothing
// of c, the curvature from the normals on the cells' faces, and the force on each face.
#include "solver/surface_tension_force.hpp"

#include <array>
#include <cmath>
#include <numbers>

#include "mesh/face_loop.hpp"
#include "mesh/obstacles.hpp"
#include "mesh/side_ghosts.hpp"
#include "models/interface/surface_tension.hpp"
#include "solver/cell_faces.hpp"

namespace granflow {

SurfaceTensionForce::SurfaceTensionForce(const Grid& grid, double sigma, double contact_angle_deg,
                                         const BoundarySet& boundaries, const Field* blocked)
    : grid_(grid),
      sigma_(sigma),
      cot_theta_(contact_angle_deg == 90.0 ? 0.0 : 1.0 / std::tan(contact_angle_deg * std::numbers::pi / 180.0)),
      boundaries_(boundaries),
      blocked_(blocked) {
  for (auto& f : smoothed_) f = std::make_unique<Field>(grid);
  curvature_ = std::make_unique<Field>(grid);
  gradient_magnitude_ = std::make_unique<Field>(grid);
  curvature_->set(0.0);
  gradient_magnitude_->set(0.0);
}

double SurfaceTensionForce::time_step_limit(double density_a, double density_b) const {
  return interface::capillary_time_step(density_a, density_b, grid_.min_spacing(), sigma_);
}

double SurfaceTensionForce::surface_energy() const {
  const auto& b = grid_.owned();
  double sum = 0.0;
  {
    const ConstFieldArray g(grid_.field_dm(), gradient_magnitude_->global());  // 0 in blocked cells
    for (int k = b.zs; k < b.ze(); ++k)
      for (int j = b.ys; j < b.ye(); ++j)
        for (int i = b.xs; i < b.xe(); ++i) sum += g.volume()[k][j][i] * grid_.volume(i, j, k);
  }
  MPI_Allreduce(MPI_IN_PLACE, &sum, 1, MPI_DOUBLE, MPI_SUM, grid_.comm());
  return sigma_ * sum;
}

// Ghosts beyond a wall side at the contact angle, from the first cell's c~ and its gradient along the
// wall (interface::contact_angle_ghost); beyond the other sides and in the obstacles, mirror images of
// the cells inside.
void SurfaceTensionForce::fill_ghosts(Field& f) const {
  FieldArray a = local_array(grid_, f);
  double*** s = a.volume();
  mirror_into_blocked(grid_, blocked_, s, 1.0);
  const int dim = grid_.dimension();
  // The local array's extent: the gradient along a wall is taken within it (one-sided at its ends, in
  // the corners' ghosts).
  const CellBox e = grid_.with_ghosts();
  const int first_index[3] = {e.xs, e.ys, e.zs}, end_index[3] = {e.xe(), e.ye(), e.ze()};
  fill_side_ghosts(grid_, s, [&](Side side, double inner, double first, const int* at) {
    if (cot_theta_ == 0.0 || boundary(boundaries_, side).kind != BoundaryKind::wall) return inner;
    const int axis = normal_axis(side);
    const int n_axis = axis == 0 ? grid_.nx() : axis == 1 ? grid_.ny() : grid_.nz();
    int cell[3] = {at[0], at[1], at[2]};  // the first cell inside, m layers from the ghost
    const bool low = at[axis] < 0;
    const int m = low ? -at[axis] : at[axis] - (n_axis - 1);
    cell[axis] = low ? 0 : n_axis - 1;
    double along2 = 0.0;  // the gradient along the wall, by central differences
    for (int t = 0; t < dim; ++t) {
      if (t == axis) continue;
      int hi[3] = {cell[0], cell[1], cell[2]}, lo[3] = {cell[0], cell[1], cell[2]};
      hi[t] = std::min(hi[t] + 1, end_index[t] - 1);
      lo[t] = std::max(lo[t] - 1, first_index[t]);
      if (hi[t] == lo[t]) continue;
      const double span = grid_.centre(t, hi[t]) - grid_.centre(t, lo[t]);
      const double g = (s[hi[2]][hi[1]][hi[0]] - s[lo[2]][lo[1]][lo[0]]) / span;
      along2 += g * g;
    }
    return interface::contact_angle_ghost(first, std::sqrt(along2), grid_.width(axis, cell[axis]), m, cot_theta_);
  });
}

void SurfaceTensionForce::smooth(const Field& from, Field& to) const {
  const auto& b = grid_.owned();
  const bool layers = grid_.dimension() == 3;
  const int reach_z = layers ? 1 : 0;
  {
    const ConstFieldArray in = local_read(grid_, from);
    FieldArray out(grid_.field_dm(), to.global());
    const VolumeView c = in.volume();
    for (int k = b.zs; k < b.ze(); ++k)
      for (int j = b.ys; j < b.ye(); ++j)
        for (int i = b.xs; i < b.xe(); ++i) {
          double sum = 0.0;
          for (int dk = -reach_z; dk <= reach_z; ++dk) {
            const double wz = layers ? interface::smoothing_weight(dk) : 1.0;
            for (int dj = -1; dj <= 1; ++dj)
              for (int di = -1; di <= 1; ++di)
                sum +=
                    wz * interface::smoothing_weight(dj) * interface::smoothing_weight(di) * c[k + dk][j + dj][i + di];
          }
          out.volume()[k][j][i] = sum;
        }
  }
  zero_blocked_cells(grid_, blocked_, to);  // a blocked cell's global value is 0, its local one the mirror
  to.scatter_to_local();
  fill_ghosts(to);
}

// kappa = -div(n) over each owned cell's faces, n = grad(c~)/|grad(c~)| on the face: the difference
// across it along its normal, the mean of its two cells' central differences across. A side's face
// takes its ghost (the mirror's gives no normal component; a wall's, the contact angle's); an obstacle's
// wall has none. The weight of a cell is |grad(c~)| there.
void SurfaceTensionForce::compute_curvature(const Field& smoothed) {
  const auto& b = grid_.owned();
  const int dim = grid_.dimension();
  {
    const ConstFieldArray s_array = local_read(grid_, smoothed);
    const VolumeView s = s_array.volume();
    const BlockedView mask(grid_, blocked_);
    FieldArray kappa(grid_.field_dm(), curvature_->global()), weight(grid_.field_dm(), gradient_magnitude_->global());
    // The central difference of c~ along `axis` at cell (i, j, k) (ghosts included).
    auto central = [&](int axis, int i, int j, int k) {
      const int di = axis == 0, dj = axis == 1, dk = axis == 2;
      const double span = grid_.centre(axis, index_along(axis, i + di, j + dj, k + dk)) -
                          grid_.centre(axis, index_along(axis, i - di, j - dj, k - dk));
      return (s[k + dk][j + dj][i + di] - s[k - dk][j - dj][i - di]) / span;
    };
    for (int k = b.zs; k < b.ze(); ++k)
      for (int j = b.ys; j < b.ye(); ++j)
        for (int i = b.xs; i < b.xe(); ++i) {
          if (is_blocked(mask.data(), i, j, k)) {
            kappa.volume()[k][j][i] = weight.volume()[k][j][i] = 0.0;
            continue;
          }
          double own[3] = {0.0, 0.0, 0.0};  // the cell's central differences
          for (int axis = 0; axis < dim; ++axis) own[axis] = central(axis, i, j, k);
          double outward = 0.0;
          for (int axis = 0; axis < dim; ++axis) {
            for (int sign : {-1, 1}) {
              const int in = i + sign * (axis == 0), jn = j + sign * (axis == 1), kn = k + sign * (axis == 2);
              if (is_blocked(mask.data(), in, jn, kn)) continue;
              const double d = std::abs(grid_.centre(axis, index_along(axis, in, jn, kn)) -
                                        grid_.centre(axis, index_along(axis, i, j, k)));
              const double along = sign * (s[kn][jn][in] - s[k][j][i]) / d;  // + axis component
              std::array<double, 2> across{0.0, 0.0};
              int m = 0;
              for (int other = 0; other < dim; ++other)
                if (other != axis) across[m++] = 0.5 * (own[other] + central(other, in, jn, kn));
              const double n_along = interface::unit_normal_component(along, across[0], across[1]);
              outward += sign * n_along * grid_.face_area(axis, i, j, k, sign);
            }
          }
          kappa.volume()[k][j][i] = interface::cell_curvature(outward, grid_.volume(i, j, k));
          weight.volume()[k][j][i] = std::sqrt(own[0] * own[0] + own[1] * own[1] + own[2] * own[2]);
        }
  }
  curvature_->scatter_to_local();
  gradient_magnitude_->scatter_to_local();
}

void SurfaceTensionForce::fill(const Field& soil_fraction, FlowSolver& flow) {
  smoothed_[0]->copy_from(soil_fraction);
  fill_ghosts(*smoothed_[0]);
  for (int pass = 0; pass < smoothing_passes; ++pass) smooth(*smoothed_[pass % 2], *smoothed_[(pass + 1) % 2]);
  compute_curvature(*smoothed_[smoothing_passes % 2]);

  flow.enable_face_source();
  const ConstFieldArray c_array = local_read(grid_, soil_fraction), kappa_array = local_read(grid_, *curvature_),
                        gradient_magnitude_array = local_read(grid_, *gradient_magnitude_);
  const VolumeView c = c_array.volume(), kappa = kappa_array.volume(), weight = gradient_magnitude_array.volume();
  const BlockedView mask(grid_, blocked_);
  std::array<Field*, 3> faces{};
  for (int a = 0; a < grid_.dimension(); ++a) faces[a] = &flow.face_source(a);
  fill_owned_faces_any(
      grid_, faces,
      [&](int axis, int i, int j, int k) {
        const int in = i + (axis == 0), jn = j + (axis == 1), kn = k + (axis == 2);
        const double d =
            grid_.centre(axis, index_along(axis, in, jn, kn)) - grid_.centre(axis, index_along(axis, i, j, k));
        const double kappa_f =
            interface::face_curvature(kappa[k][j][i], weight[k][j][i], kappa[kn][jn][in], weight[kn][jn][in]);
        return interface::surface_tension_face_force(sigma_, kappa_f, c[k][j][i], c[kn][jn][in], d);
      },
      [](int, int, int, int, int) { return 0.0; }, mask.data());
}

}  // namespace granflow
