// The surface tension's pure pieces (models/interface/surface_tension.hpp): the unit normal, the
// curvature from face normals, the face force and the capillary step. The force on the mesh is checked
// against Laplace's law and Rayleigh's drop in tests/verification/test_surface_tension.cpp.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "models/interface/surface_tension.hpp"

namespace granflow::interface {
namespace {

TEST(SurfaceTensionModel, UnitNormalComponent) {
  EXPECT_DOUBLE_EQ(unit_normal_component(3.0, 4.0, 0.0), 0.6);
  EXPECT_DOUBLE_EQ(unit_normal_component(-2.0, 0.0, 0.0), -1.0);
  EXPECT_DOUBLE_EQ(unit_normal_component(1.0, 2.0, 2.0), 1.0 / 3.0);
  EXPECT_EQ(unit_normal_component(0.0, 0.0, 0.0), 0.0);  // no gradient, no normal
}

// -div(n) of the inward normal of a disc, by the faces of a square cell of side h centred at distance r
// from the disc's centre on the x axis: the exact normals at the face centres give 1/r to O(h^2).
TEST(SurfaceTensionModel, CellCurvatureOfADisc) {
  const double r = 1.0;
  for (double h : {0.1, 0.05}) {
    // n = -(x, y)/|(x, y)| (towards the centre, up the gradient of c); outward flux over the four faces.
    auto nx = [](double x, double y) { return -x / std::hypot(x, y); };
    auto ny = [](double x, double y) { return -y / std::hypot(x, y); };
    const double flux = (nx(r + h / 2, 0) - nx(r - h / 2, 0)) * h + (ny(r, h / 2) - ny(r, -h / 2)) * h;
    const double kappa = cell_curvature(flux, h * h);
    EXPECT_NEAR(kappa, 1.0 / r, 0.01 * h / 0.1) << "h = " << h;
  }
}

TEST(SurfaceTensionModel, FaceCurvatureWeighsTheCells) {
  EXPECT_DOUBLE_EQ(face_curvature(10.0, 1.0, 20.0, 3.0), 17.5);
  EXPECT_DOUBLE_EQ(face_curvature(10.0, 0.0, 20.0, 2.0), 20.0);  // a cell without a gradient has no say
  EXPECT_EQ(face_curvature(10.0, 0.0, 20.0, 0.0), 0.0);
}

// Across a face into the soil (c from 0 to 1) a drop's curvature pushes towards the soil: sigma kappa / d.
TEST(SurfaceTensionModel, FaceForcePointsIntoTheConvexSide) {
  const double f = surface_tension_face_force(0.072, 250.0, 0.0, 1.0, 1e-3);
  EXPECT_DOUBLE_EQ(f, 0.072 * 250.0 / 1e-3);
  EXPECT_DOUBLE_EQ(surface_tension_face_force(0.072, 250.0, 1.0, 0.0, 1e-3), -f);
  // Summed over the interface's cells along the normal, the force is the Laplace jump sigma kappa.
  const double d = 1e-3;
  const double c[] = {0.0, 0.2, 0.7, 1.0};
  double jump = 0.0;
  for (int k = 0; k < 3; ++k) jump += surface_tension_face_force(0.072, 250.0, c[k], c[k + 1], d) * d;
  EXPECT_NEAR(jump, 0.072 * 250.0, 1e-12);
}

TEST(SurfaceTensionModel, CapillaryTimeStep) {
  // Water in air, h = 0.5 mm: sqrt(500.5 * 1.25e-10 / (2 pi 0.072)).
  EXPECT_NEAR(capillary_time_step(1000.0, 1.0, 5e-4, 0.072), 3.7188e-4, 1e-8);
  // dt ~ h^(3/2): a mesh twice as fine, a step 2.83 times shorter.
  EXPECT_NEAR(capillary_time_step(1000.0, 1.0, 5e-4, 0.072) / capillary_time_step(1000.0, 1.0, 2.5e-4, 0.072),
              2.0 * std::numbers::sqrt2, 1e-12);
  EXPECT_TRUE(std::isinf(capillary_time_step(1000.0, 1.0, 5e-4, 0.0)));
}

// A wall's ghost at the contact angle: a right angle mirrors; below it the soil's side continues into the
// wall (the ghost holds more soil than the cell), above it the air's; clipped to [0, 1]. Between the
// first cell and its ghost the gradient across the wall is -cot(theta) times that along it.
TEST(SurfaceTensionModel, ContactAngleGhost) {
  const double h = 1e-3, along = 200.0;  // 1/m
  EXPECT_DOUBLE_EQ(contact_angle_ghost(0.4, along, h, 1, 0.0), 0.4);
  const double cot60 = 1.0 / std::tan(std::numbers::pi / 3);
  EXPECT_NEAR(contact_angle_ghost(0.4, along, h, 1, cot60), 0.4 + h * along * cot60, 1e-15);
  EXPECT_NEAR(contact_angle_ghost(0.4, along, h, 2, -cot60), 0.4 - 2 * h * along * cot60, 1e-15);
  EXPECT_EQ(contact_angle_ghost(0.9, along, h, 2, cot60), 1.0);
  EXPECT_EQ(contact_angle_ghost(0.1, along, h, 2, -cot60), 0.0);
  // The normal the ghost gives at the wall: across / along = -cot(theta), i.e. theta from the wall.
  const double across = -(contact_angle_ghost(0.4, along, h, 1, cot60) - 0.4) / h;  // d c / d n_w
  EXPECT_NEAR(std::atan2(along, -across) * 180 / std::numbers::pi, 60.0, 1e-9);
}

TEST(SurfaceTensionModel, SmoothingWeightsSumToOne) {
  EXPECT_DOUBLE_EQ(smoothing_weight(-1) + smoothing_weight(0) + smoothing_weight(1), 1.0);
}

}  // namespace
}  // namespace granflow::interface
