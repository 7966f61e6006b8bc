#include "odocal/sim/centreline_route.hpp"

#include <Eigen/LU>
#include <cmath>
#include <numbers>

#include "odocal/error.hpp"
#include "odocal/model/angle.hpp"

namespace odocal::sim {
namespace {

constexpr double kTwoPi = 2.0 * std::numbers::pi;

std::vector<PathSegment> segments_with(const std::vector<double>& length_m,
                                       const std::vector<double>& curvature_1pm) {
  std::vector<PathSegment> segments;
  const std::size_t n = length_m.size();
  for (std::size_t i = 0; i < n; ++i) {
    segments.push_back({length_m[i], curvature_1pm[i], curvature_1pm[(i + 1) % n], 1});
  }
  return segments;
}

}  // namespace

CentrelineRoute closed_route_from_centreline(const std::vector<Eigen::Vector2d>& points,
                                             int smoothing_points) {
  const std::size_t n = points.size();
  if (n < 8) throw Error("a closed centreline needs at least 8 points");
  std::vector<double> length(n), heading(n);
  for (std::size_t i = 0; i < n; ++i) {
    const Eigen::Vector2d chord = points[(i + 1) % n] - points[i];
    length[i] = chord.norm();
    if (!(length[i] > 1e-6))
      throw Error("centreline points " + std::to_string(i) + " and " + std::to_string(i + 1) +
                  " coincide");
    heading[i] = std::atan2(chord.y(), chord.x());
  }
  std::vector<double> vertex(n);
  for (std::size_t i = 0; i < n; ++i) {
    const std::size_t before = (i + n - 1) % n;
    vertex[i] =
        angle_difference(heading[i], heading[before]) / (0.5 * (length[before] + length[i]));
  }
  std::vector<double> curvature(n, 0.0);
  const int half = std::max(0, smoothing_points / 2);
  for (std::size_t i = 0; i < n; ++i) {
    for (int j = -half; j <= half; ++j) curvature[i] += vertex[(i + n + j) % n];
    curvature[i] /= 2 * half + 1;
  }

  // Heading closure: the lap must turn by exactly +-2 pi.
  double total_length = 0.0, total_turn = 0.0;
  for (std::size_t i = 0; i < n; ++i) {
    total_length += length[i];
    total_turn += length[i] * 0.5 * (curvature[i] + curvature[(i + 1) % n]);
  }
  const double turns = std::round(total_turn / kTwoPi);
  if (turns == 0.0) throw Error("the centreline does not form a loop");
  for (double& k : curvature) k += (turns * kTwoPi - total_turn) / total_length;

  // Position closure: add a cos/sin curvature harmonic over the lap (it integrates to zero, so
  // the heading closure stays), sized by Newton steps on the end-point gap.
  std::vector<double> s_at(n, 0.0);
  for (std::size_t i = 1; i < n; ++i) s_at[i] = s_at[i - 1] + length[i - 1];
  const Pose2 start(points[0].x(), points[0].y(),
                    heading[n - 1] + 0.5 * angle_difference(heading[0], heading[n - 1]));
  const auto end_gap = [&](const Eigen::Vector2d& harmonic) {
    std::vector<double> corrected = curvature;
    for (std::size_t i = 0; i < n; ++i) {
      const double phase = kTwoPi * s_at[i] / total_length;
      corrected[i] += harmonic.x() * std::cos(phase) + harmonic.y() * std::sin(phase);
    }
    const Path path(segments_with(length, corrected), start);
    return Eigen::Vector2d(path.at(path.length_m()).pose.head<2>() - start.head<2>());
  };
  Eigen::Vector2d harmonic = Eigen::Vector2d::Zero();
  for (int iteration = 0; iteration < 6; ++iteration) {
    const Eigen::Vector2d gap = end_gap(harmonic);
    if (gap.norm() < 1e-6) break;
    Eigen::Matrix2d jacobian;
    constexpr double kStep = 1e-7;
    for (int c = 0; c < 2; ++c) {
      Eigen::Vector2d shifted = harmonic;
      shifted[c] += kStep;
      jacobian.col(c) = (end_gap(shifted) - gap) / kStep;
    }
    harmonic -= jacobian.partialPivLu().solve(gap);
  }
  for (std::size_t i = 0; i < n; ++i) {
    const double phase = kTwoPi * s_at[i] / total_length;
    curvature[i] += harmonic.x() * std::cos(phase) + harmonic.y() * std::sin(phase);
  }

  CentrelineRoute route{segments_with(length, curvature), start, 0.0};
  const Path path(route.segments, start);
  for (std::size_t i = 0; i < n; ++i) {
    route.max_deviation_m =
        std::max(route.max_deviation_m, (path.at(s_at[i]).pose.head<2>() - points[i]).norm());
  }
  return route;
}

}  // namespace odocal::sim
