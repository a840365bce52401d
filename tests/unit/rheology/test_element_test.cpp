// [YS] Table 1 (element test, phi = 36.5 deg) reproduced to its printed digits.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <sstream>
#include <stdexcept>
#include <string>

#include "models/rheology/element_test.hpp"

namespace granflow::rheology {
namespace {

struct PrintedRow {
  Deformation deformation;
  double theta_deg;
  YieldSurface model;
  double eta_norm_d_over_p;  // printed with 3 decimals
  double norm_tdev_over_p;   // printed with 3 decimals
  double relative;           // printed with 2 decimals
};

// [YS] Table 1. One entry contradicts its own row: for MN in triaxial compression the table
// prints eta ||D|| / p = 0.380 but ||T_dev|| / p = 0.756, although ||T_dev|| = 2 eta ||D||
// (Eq. 16) forces 0.760. The exact Matsuoka-Nakai value is 0.3798 / 0.7596, and the same row's
// ||T|| / p = 0.862 and its relative 1.20 also follow from 0.760, not from 0.756. So 0.756 is
// the misprint; we match the self-consistent 0.760. Its printed relative 1.27 = 0.756 / 0.595
// inherits the misprint: the consistent value is 0.7596 / 0.5948 = 1.277, i.e. 1.28 (the "up
// to 28 %" of [YS] Sec. 5).
constexpr PrintedRow kTable1[] = {
    {Deformation::triaxial_compression, -30.0, YieldSurface::drucker_prager, 0.297, 0.595, 1.00},
    {Deformation::triaxial_compression, -30.0, YieldSurface::mohr_coulomb, 0.428, 0.857, 1.44},
    {Deformation::triaxial_compression, -30.0, YieldSurface::matsuoka_nakai, 0.380, 0.760, 1.28},
    {Deformation::isochoric_shear, 0.0, YieldSurface::drucker_prager, 0.297, 0.595, 1.00},
    {Deformation::isochoric_shear, 0.0, YieldSurface::mohr_coulomb, 0.297, 0.595, 1.00},
    {Deformation::isochoric_shear, 0.0, YieldSurface::matsuoka_nakai, 0.297, 0.595, 1.00},
    {Deformation::triaxial_extension, 30.0, YieldSurface::drucker_prager, 0.297, 0.595, 1.00},
    {Deformation::triaxial_extension, 30.0, YieldSurface::mohr_coulomb, 0.287, 0.573, 0.96},
    {Deformation::triaxial_extension, 30.0, YieldSurface::matsuoka_nakai, 0.264, 0.528, 0.89},
};

// Half a unit in the last printed digit, plus round-off.
constexpr double kHalfThirdDecimal = 0.0005 + 1e-12;
constexpr double kHalfSecondDecimal = 0.005 + 1e-12;

TEST(RheologyElementTest, ReproducesTable1AtPrintedPrecision) {
  const auto rows = element_test(36.5);
  ASSERT_EQ(rows.size(), std::size(kTable1));
  for (std::size_t i = 0; i < rows.size(); ++i) {
    SCOPED_TRACE(std::string(abbreviation(kTable1[i].deformation)) + " " +
                 std::string(abbreviation(kTable1[i].model)));
    EXPECT_EQ(rows[i].deformation, kTable1[i].deformation);
    EXPECT_EQ(rows[i].model, kTable1[i].model);
    EXPECT_NEAR(rows[i].lode_angle_deg, kTable1[i].theta_deg, 1e-9);
    EXPECT_NEAR(rows[i].eta_norm_d_over_p, kTable1[i].eta_norm_d_over_p, kHalfThirdDecimal);
    EXPECT_NEAR(rows[i].norm_tdev_over_p, kTable1[i].norm_tdev_over_p, kHalfThirdDecimal);
    EXPECT_NEAR(rows[i].relative, kTable1[i].relative, kHalfSecondDecimal);
  }
}

TEST(RheologyElementTest, MatsuokaNakaiCompressionMatchesSelfConsistentValueNotMisprint) {
  const auto rows = element_test(36.5);
  const ElementTestRow& mn_txc = rows[2];
  ASSERT_EQ(mn_txc.model, YieldSurface::matsuoka_nakai);
  ASSERT_EQ(mn_txc.deformation, Deformation::triaxial_compression);
  EXPECT_NEAR(mn_txc.eta_norm_d_over_p, 0.37980, 5e-5);
  EXPECT_NEAR(mn_txc.norm_tdev_over_p, 0.75960, 5e-5);
  EXPECT_GT(std::abs(mn_txc.norm_tdev_over_p - 0.756), 0.003);  // the printed 0.756 is off
  EXPECT_NEAR(mn_txc.relative, 1.2771, 5e-4);
}

TEST(RheologyElementTest, ExactValuesAtPhi36_5) {
  // Closed forms: DP ||T_dev||/p = sin(phi); MC at theta = -+30: 2 sqrt3 sin(phi) / (3 -+ sin(phi)).
  const double s = std::sin(36.5 * std::numbers::pi / 180.0);
  const auto rows = element_test(36.5);
  EXPECT_NEAR(rows[0].norm_tdev_over_p, s, 1e-14);
  EXPECT_NEAR(rows[1].norm_tdev_over_p, 2.0 * std::numbers::sqrt3 * s / (3.0 - s), 1e-14);
  EXPECT_NEAR(rows[7].norm_tdev_over_p, 2.0 * std::numbers::sqrt3 * s / (3.0 + s), 1e-14);
}

TEST(RheologyElementTest, CsvHasExactHeaderAndNineRows) {
  const std::string csv = format_element_test(36.5, true);
  std::istringstream in(csv);
  std::string line;
  std::getline(in, line);
  EXPECT_EQ(line, "deformation,theta_deg,model,eta_norm_D_over_p,norm_Tdev_over_p,relative");
  int count = 0;
  while (std::getline(in, line)) {
    ++count;
    EXPECT_EQ(std::count(line.begin(), line.end(), ','), 5) << line;
  }
  EXPECT_EQ(count, 9);
  EXPECT_NE(csv.find("TXC,-30.000000,MC,0.428352,0.856705,1.440269"), std::string::npos) << csv;
  EXPECT_NE(csv.find("SHR,0.000000,MN,0.297411,0.594823,1.000000"), std::string::npos) << csv;
  EXPECT_EQ(csv.find("-0.000000"), std::string::npos);
}

TEST(RheologyElementTest, TextTableListsEveryRow) {
  const std::string text = format_element_test(36.5, false);
  EXPECT_NE(text.find("phi = 36.5"), std::string::npos);
  for (const char* needle : {"TXC", "SHR", "TXE", "0.428", "0.380", "0.760", "0.264", "1.440"}) {
    EXPECT_NE(text.find(needle), std::string::npos) << needle << "\n" << text;
  }
}

TEST(RheologyElementTest, OtherFrictionAngleStillCalibratedInShear) {
  for (const auto& row : element_test(25.0)) {
    if (row.deformation == Deformation::isochoric_shear) {
      EXPECT_NEAR(row.relative, 1.0, 1e-14);
    }
  }
}

TEST(RheologyElementTest, RejectsFrictionAngleOutsideOpenInterval) {
  EXPECT_THROW(element_test(0.0), std::invalid_argument);
  EXPECT_THROW(element_test(90.0), std::invalid_argument);
  EXPECT_THROW(format_element_test(-3.0, true), std::invalid_argument);
  EXPECT_THROW(element_test(std::numeric_limits<double>::quiet_NaN()), std::invalid_argument);
}

}  // namespace
}  // namespace granflow::rheology
