// Closed centrelines become drivable, exactly closing paths that stay near the given points.

#include "odocal/sim/centreline_route.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <numbers>

#include "odocal/error.hpp"
#include "odocal/io/track_reader.hpp"

namespace odocal::sim {
namespace {

constexpr double kPi = std::numbers::pi;

void expect_closed(const CentrelineRoute& route, double turns) {
  const Path path(route.segments, route.start);
  const PathPoint end = path.at(path.length_m());
  EXPECT_LT((end.pose.head<2>() - route.start.head<2>()).norm(), 1e-5);
  EXPECT_NEAR(end.pose.z() - route.start.z(), turns * 2 * kPi, 1e-9);
}

TEST(CentrelineRoute, EllipseClosesAndStaysOnIt) {
  std::vector<Eigen::Vector2d> points;
  for (int i = 0; i < 200; ++i) {
    const double a = 2 * kPi * i / 200;
    points.emplace_back(300 * std::cos(a), 150 * std::sin(a));
  }
  const CentrelineRoute route = closed_route_from_centreline(points);
  expect_closed(route, 1.0);
  EXPECT_LT(route.max_deviation_m, 0.5);
  EXPECT_NEAR(route.start.z(), kPi / 2, 0.01);
}

TEST(CentrelineRoute, ClockwiseLoopTurnsMinusTwoPi) {
  std::vector<Eigen::Vector2d> points;
  for (int i = 0; i < 100; ++i) {
    const double a = -2 * kPi * i / 100;
    points.emplace_back(100 * std::cos(a), 100 * std::sin(a));
  }
  expect_closed(closed_route_from_centreline(points), -1.0);
}

TEST(CentrelineRoute, RejectsDegenerateInput) {
  EXPECT_THROW(closed_route_from_centreline({{0, 0}, {1, 0}}), Error);
  std::vector<Eigen::Vector2d> repeated(10, Eigen::Vector2d(1.0, 1.0));
  EXPECT_THROW(closed_route_from_centreline(repeated), Error);
}

TEST(CentrelineRoute, RealHockenheimLayout) {
  const std::filesystem::path track =
      std::string(ODOCAL_SOURCE_DIR) + "/../shared/data/tracks/hockenheim/track.csv";
  if (!std::filesystem::exists(track)) GTEST_SKIP() << "shared data absent: " << track;
  const std::vector<Eigen::Vector2d> points = read_track_centreline(track);
  EXPECT_EQ(points.size(), 914u);
  const CentrelineRoute route = closed_route_from_centreline(points);
  expect_closed(route,
                std::round((Path(route.segments, route.start).at(1e9).pose.z() - route.start.z()) /
                           (2 * kPi)));
  EXPECT_NEAR(Path(route.segments, route.start).length_m(), 4569.0, 5.0);
  EXPECT_LT(route.max_deviation_m, 2.5);  // the track's half-width is ~6 m
}

}  // namespace
}  // namespace odocal::sim
