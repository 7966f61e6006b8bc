#pragma once
// The driving state at every wheel sample (speed, lateral and longitudinal acceleration), the
// regressors of the tyre model (odocal/model/tyre_model.hpp), and the wheel stream with the
// model applied. Measured from the log itself: speed from the wheels at the given parameters,
// the turn rate from the gyro where imu.csv has it (the wheels' own turn is what a tyre model
// corrects) else from the wheels; smoothed over a short window so that encoder steps do not
// become accelerations. The accelerometer's specific force, which the physical terms' force and
// load come from, is its mean over each wheel sample's own increment.

#include <vector>

#include "odocal/data/fitted_wheels.hpp"
#include "odocal/data/log.hpp"
#include "odocal/model/tyre_model.hpp"

namespace odocal {

// The states' speeds and yaw rate are means over +-this, s.
inline constexpr double kDrivingStateHalfWindowS = 0.25;

// Where a gyro measures, the yaw acceleration is the difference of its means over +-this either
// side, s: a fishtail's yaw swings within half a second, and over +-0.25 s its acceleration
// comes out at a third; shorter still, the gyro's noise grows (docs/tyre-model.md, "The front
// tyres' steer").
inline constexpr double kYawAccelerationHalfWindowS = 0.05;

// One state per wheel sample. half_window_s: speeds and the yaw rate are means over
// +-half_window_s, and the wheels' accelerations differences of those over the same spacing (the
// window shrinks at the ends and across chain breaks, whose increments are zero).
std::vector<DrivingState> driving_states(const Log& log, const OdometryParams& params,
                                         double half_window_s = kDrivingStateHalfWindowS);
// The same from a wheel stream and the gyro (null: none).
std::vector<DrivingState> driving_states(const FittedWheels& wheels, const ImuStream* imu,
                                         const OdometryParams& params,
                                         double half_window_s = kDrivingStateHalfWindowS);
// The same from the wheels as `model` counts them at the states `counted_at` (one per wheel
// sample): driving_states(with_tyre_model(wheels, counted_at, model), ...) without the copy of
// the stream (a slipping wheel overstates its speed by its slip).
std::vector<DrivingState> driving_states(const FittedWheels& wheels, const ImuStream* imu,
                                         const OdometryParams& params,
                                         const std::vector<DrivingState>& counted_at,
                                         const TyreModel& model, const VehicleBody& body,
                                         double half_window_s = kDrivingStateHalfWindowS);

// The same in place: `states` (one per wheel sample, as the model counted them) become the
// states of the wheels as `model` counts them there, without a second copy of the states. On
// `threads` threads (0: one per core), with the same result as on one.
void measure_driving_states_again(const FittedWheels& wheels, const ImuStream* imu,
                                  const OdometryParams& params, const TyreModel& model,
                                  const VehicleBody& body, std::vector<DrivingState>& states,
                                  double half_window_s = kDrivingStateHalfWindowS, int threads = 1);

// The wheel stream whose rear increments carry the model's factors (c_i,eff / c_i), and its
// side slip per sample where the model has one: dead reckoning it with c_i is dead reckoning
// with the condition-dependent circumference and the axle's side slip.
WheelStream with_tyre_model(const WheelStream& wheels, const std::vector<DrivingState>& states,
                            const TyreModel& model, const VehicleBody& body);

// Both at once, for a log and a calibrated vehicle (the log's body): the states at the given
// parameters, from the wheels as the model counts them (a slipping wheel overstates its speed by
// its slip).
WheelStream with_tyre_model(const Log& log, const OdometryParams& params, const TyreModel& model);

}  // namespace odocal
