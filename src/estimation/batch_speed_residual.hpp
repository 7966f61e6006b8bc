#pragma once
// The GNSS Doppler speed against the wheels over one keyframe interval (docs/batch-calibration.md,
// "Doppler speed"): the distance the wheels rolled, at the parameters and the tyre model, against
// the integral of the measured speed over ground. The positions see the wheels' scale only through
// metres of noise per fix; the Doppler speed sees it within a second, while the car accelerates,
// brakes or cruises: what the slip does with the force.

#include <Eigen/Core>
#include <array>
#include <cmath>
#include <optional>
#include <vector>

#include "batch_residuals.hpp"
#include "odocal/data/log.hpp"

namespace odocal::batch {

// One fix's share of an interval's Doppler distance: its weight in the integral of the linearly
// interpolated speed, its speed, and the wheels' yaw rate and the side slip's regressor (the
// lateral specific force) there, for the antenna's lever arm.
struct DopplerShare {
  double weight_s{};
  double speed_mps{};
  double yaw_rate_radps{};
  double side_slip_regressor{};
};

// The measured side of an interval [begin, end]: every fix from the last one at or before begin
// to the first one at or after end, weighted so that the sum of weight x speed is the integral of
// the linear interpolation between fixes.
struct DopplerInterval {
  std::vector<std::size_t> fixes;  // indices into the GNSS stream
  std::vector<double> weights_s;
  double speed_change_mps{};  // interpolated at end minus at begin
  double sum_squared_weights_s2{};
};

// None where the fixes do not cover the interval (no fix on one side, or two fixes further apart
// than max_gap_s) or a fix inside it reads below min_speed_mps (a speed's magnitude: its noise
// does not average out near standstill, and reversing is not seen).
std::optional<DopplerInterval> doppler_interval(const GnssStream& gnss, double begin_s,
                                                double end_s, double max_gap_s,
                                                double min_speed_mps);

// The wheels' distance over the interval, exact in the circumferences and, about the coefficients
// it is built at, to first order in the tyre's (exact but in the slip's divisor): sum over the
// wheels of c_w / 2 (n_w + x_w . k + q_w,end - q_w,begin), n_w the logged revolutions (with the
// factor's part not linear in k), x_w their sum weighted by each increment's factor gradient, q_w
// the keyframes' count errors. The wheels roll at the side slip angle beta = k_side_slip f_y from
// the course, so the ground is longer by 1 / cos(beta): z_w, the revolutions weighted by f_y^2 / 2,
// times k^2 (to second order). The Doppler speed is the antenna's: with the lever arm l in the
// frame of the reference point's velocity (the body's turned by the side slip beta: along it
// l_v = l_x cos beta + l_y sin beta, left of it l_n = l_y cos beta - l_x sin beta) and yaw rate w,
// the antenna moves at (V - w l_n, w l_v) in that frame, so the reference point's speed is
// V = w l_n + sqrt(|v|^2 - (w l_v)^2), exactly. Left out, the side slip's w l_x beta read as a
// lever arm about k_side_slip v^2 short (some 8 cm at the urban drive's 4 m/s turns, RTK fixes
// 2 m ahead of the axle), and its residual followed v^2. A fix stamped t reports the speed at t
// - latency: the fixes are those of the interval shifted by the latency the residual is built at,
// latency_lin, and the rest of it is taken to first order: the interval's true distance is the
// integral plus (latency - latency_lin) x (speed at end - speed at begin).
struct SpeedResidual {
  std::array<double, 2> half_revolutions{};
  Eigen::Matrix<double, 2, TyreModel::kCoefficients> half_tyre_revolutions =
      Eigen::Matrix<double, 2, TyreModel::kCoefficients>::Zero();
  std::array<double, 2> half_side_slip_revolutions{};
  std::vector<DopplerShare> shares;
  double speed_change_mps{};
  double latency_lin_s{};
  double sigma_m{};

  template <typename T>
  bool operator()(const T* params, const T* lever, const T* latency, const T* count_a,
                  const T* count_b, T* residual) const {
    using std::cos;
    using std::sin;
    using std::sqrt;
    // The wheels' ground and the antenna's speed both depend on it.
    const T& side_slip = params[3 + kSideSlipCoefficient];
    T wheels(0.0);
    for (int w = 0; w < 2; ++w) {
      T revolutions =
          T(half_revolutions[static_cast<std::size_t>(w)]) + T(0.5) * (count_b[w] - count_a[w]);
      for (int j = 0; j < TyreModel::kCoefficients; ++j)
        revolutions += T(half_tyre_revolutions(w, j)) * params[3 + j];
      revolutions +=
          half_side_slip_revolutions[static_cast<std::size_t>(w)] * side_slip * side_slip;
      wheels += params[w] * revolutions;
    }
    T doppler = (latency[0] - latency_lin_s) * speed_change_mps;
    for (const DopplerShare& share : shares) {
      const T beta = side_slip * share.side_slip_regressor;
      const T cos_beta = cos(beta), sin_beta = sin(beta);
      const T along = lever[0] * cos_beta + lever[1] * sin_beta;
      const T left = lever[1] * cos_beta - lever[0] * sin_beta;
      const T across = share.yaw_rate_radps * along;
      const T squared = share.speed_mps * share.speed_mps - across * across;
      const T floor(0.25 * share.speed_mps * share.speed_mps);  // a lever arm far beyond a car's
      doppler +=
          share.weight_s * (share.yaw_rate_radps * left + sqrt(squared > floor ? squared : floor));
    }
    residual[0] = (wheels - doppler) / sigma_m;
    return true;
  }
};

}  // namespace odocal::batch
