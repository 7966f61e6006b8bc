#pragma once
// The heading error that a tyre model brings into dead reckoning from the accelerometer's noise.
// The physical terms take each wheel sample's force and load from the accelerometer, so its
// white noise moves the two wheels' factors apart at every sample, and the heading sums that up:
// a random walk that no filter of the accelerometer takes out, because a filter keeps the
// noise's integral (docs/tyre-model.md, "The accelerometer's noise in dead reckoning").

#include <vector>

#include "odocal/data/log.hpp"
#include "odocal/model/tyre_model.hpp"

namespace odocal {

struct AccelerometerWalk {
  double noise_x_mps2{};  // white noise per accelerometer sample, forward and left
  double noise_y_mps2{};
  double heading_rad{};  // 1-sigma heading error at the log's end that this noise alone makes
  // The log gives the tyres' force (WheelStream::drive_force_n): the forward channel moves no
  // state where it does.
  bool forward_force_given = false;
};

// The white noise of one channel from its second differences (a slow signal cancels in them),
// by their median absolute value: robust to the few samples where the signal steps.
double white_noise_sigma(const std::vector<double>& channel);

// The walk of dead reckoning `wheels` with `model` at the driving states `states` (one per wheel
// sample, as with_tyre_model counts them), linearised about those states: each accelerometer
// sample's noise moves the states of the wheel samples whose increment averages it.
AccelerometerWalk accelerometer_heading_walk(const WheelStream& wheels, const ImuStream& imu,
                                             const std::vector<DrivingState>& states,
                                             const TyreModel& model, const VehicleBody& body,
                                             const OdometryParams& params);

}  // namespace odocal
