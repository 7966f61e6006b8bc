// The report's caution about a tyre's centrifugal growth, sized at the drive's distance-weighted
// mean v^2 against the circumferences' sigma: left out of the physical terms' circumferences at
// rest, and in the plain model's, which the drive rolled on.

#include <gtest/gtest.h>

#include <string>

#include "odocal/estimation/batch_calibration.hpp"
#include "odocal/model/tyre_car_prior.hpp"

namespace odocal {
namespace {

// A usable physical fit of 2 m circumferences at a sigma of sigma_mm, over 1000 m driven at a
// distance-weighted mean v^2 of 400 (m/s)^2.
BatchSummary physical_fit(double sigma_mm) {
  BatchSummary s;
  s.estimate = s.nominal = OdometryParams{2.0, 2.0, 1.6};
  s.tyre_model.k_load_s2pm = 2e-3;
  s.covariance = Eigen::Matrix2d::Identity() * (sigma_mm * 1e-3) * (sigma_mm * 1e-3);
  s.coverage.distance_m = 1000.0;
  s.coverage.distance_speed_squared_m3ps2 = 1000.0 * 400.0;
  return s;
}

std::string growth_line(const BatchSummary& s) {
  const std::string report = s.full_report();
  const auto at = report.find("\ngrowth ");
  return at == std::string::npos ? "" : report.substr(at + 1, report.find('\n', at + 1) - at - 1);
}

TEST(CalibrationReport, APhysicalFitNamesTheGrowthItLeavesOutWhereItMatters) {
  // 3e-6 * 400 * 2 m = 2.4 mm below, 4.8 times a sigma of 0.5 mm.
  ASSERT_DOUBLE_EQ(kCarGrowthPerSpeedSquaredS2pm2, 3e-6);
  const std::string line = growth_line(physical_fit(0.5));
  EXPECT_NE(line.find("mean v^2 of 400 (m/s)^2"), std::string::npos) << line;
  EXPECT_NE(line.find("2.4 mm below these (4.8 times their sigma"), std::string::npos) << line;
  // Within half its sigma it is not worth a line; nor for the plain model, whose circumferences
  // are the ones the drive rolled on, growth included; nor for a result that is not usable.
  EXPECT_EQ(growth_line(physical_fit(5.0)), "");
  BatchSummary plain = physical_fit(0.5);
  plain.tyre_model = TyreModel{};
  EXPECT_EQ(growth_line(plain), "");
  // The plain model's circumferences are the ones the drive rolled on: its `rolling` line says
  // that the growth is in them, above a garage's.
  EXPECT_NE(plain.full_report().find("mean v^2 of 400 (m/s)^2 is in them too, some 2.4 mm above"),
            std::string::npos)
      << plain.full_report();
  BatchSummary refused = physical_fit(0.5);
  refused.termination = Termination::kNotIdentifiable;
  EXPECT_EQ(growth_line(refused), "");
}

}  // namespace
}  // namespace odocal
