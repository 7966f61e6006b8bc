#!/usr/bin/python3
"""Writes a realistic car drive in odocal's log format from physics written apart from odocal's
simulator, so that a figure odocal's simulator gives can be checked on a drive it did not make.

A seeded random road (straights, clothoid-entered turns of 20-400 m radius both ways, stops
with a dwell) driven gently: at most --max-speed, --max-lateral and the longitudinal limits,
the speed profile smoothed to a finite jerk. The car's rear wheels roll with an effective radius
that the driving state moves, each effect switchable:
  - vertical load (--load-mm-per-kn): the rolling radius shrinks per kN above the wheel's static
    load; load moves with the forward (m a_x h / L) and lateral (m a_y h / t, the rear axle's
    share of it) transfer;
  - slip (--slip-stiffness, per unit of slip and unit of load): the wheel's longitudinal force
    over its load, divided by the stiffness, is the slip; the force is the drive's (rear-driven
    only; inertia, drag and rolling resistance) or the brakes' (their rear share);
  - speed growth (--speed-growth-s2pm2): the radius grows by that fraction per (m/s)^2.
Everything is integrated on a 1 kHz grid: truth.csv is the rear axle's pose, truth.yaml the
static circumferences (at rest, static load). Sensors: wheel ticks at 50 Hz, IMU at the rear axle
at 100 Hz (white noise, a gyro bias), GNSS at the rear axle at 10 Hz (white noise, optional
Doppler speed). vehicle.yaml states the nominal tyres, the body and the drivetrain.

Usage: tools/independent_drive.py OUT_DIR [--seed N] [--drivetrain front|rear] [...] (--help)
"""
import argparse
import math
import os

import numpy as np

GRAVITY_MPS2 = 9.81
AIR_DENSITY_KGPM3 = 1.2
NOMINAL_RADIUS_M = 0.3126
TICKS_PER_REV = 96
COUNTER_BITS = 16
T0_S = 1000.0
FINE_HZ = 1000
WHEEL_HZ, IMU_HZ, GNSS_HZ = 50, 100, 10
ROUTE_STEP_M = 0.25
BODY = {"mass_kg": 1500.0, "cg_height_m": 0.55, "rear_axle_load_share": 0.46,
        "rear_roll_share": 0.45, "drag_area_m2": 0.7, "rolling_resistance": 0.012,
        "brake_rear_share": 0.35}
WHEELBASE_M, TRACK_M = 2.7, 1.6


def road_curvature(rng, length_m, stop_share):
    """Curvature (1/m) every ROUTE_STEP_M along a random road, and the indices of its stops."""
    pieces, stops, total = [(60.0, 0.0, 0.0)], [], 60.0  # (length, curvature from, to)
    while total < length_m:
        straight = rng.uniform(100.0, 600.0)
        pieces.append((straight, 0.0, 0.0))
        total += straight
        if rng.random() < stop_share:
            stops.append(total)
        radius = math.exp(rng.uniform(math.log(20.0), math.log(400.0)))
        angle = math.radians(rng.uniform(20.0, 120.0))
        curvature = rng.choice([-1.0, 1.0]) / radius
        ramp = min(40.0, 0.4 * angle * radius)  # each clothoid turns by curvature * ramp / 2
        arc = angle * radius - ramp
        pieces += [(ramp, 0.0, curvature), (arc, curvature, curvature), (ramp, curvature, 0.0)]
        total += 2 * ramp + arc
    pieces.append((60.0, 0.0, 0.0))
    steps = [np.linspace(a, b, max(1, round(n / ROUTE_STEP_M)), endpoint=False)
             for n, a, b in pieces]
    curvature = np.concatenate(steps + [np.zeros(1)])
    stop_indices = [round(s / ROUTE_STEP_M) for s in stops]
    return curvature, stop_indices


def speed_profile(curvature, stops, args):
    """Speed (m/s) at each road step: the lateral and speed limits, stops, and the longitudinal
    limits taken forward (acceleration) and backward (braking)."""
    limit = np.minimum(args.max_speed, np.sqrt(args.max_lateral / np.maximum(np.abs(curvature),
                                                                             1e-9)))
    limit[0] = limit[-1] = 0.0
    limit[stops] = 0.0
    speed = limit.copy()
    for i in range(1, len(speed)):
        speed[i] = min(speed[i], math.sqrt(speed[i - 1] ** 2 + 2 * args.max_accel * ROUTE_STEP_M))
    for i in range(len(speed) - 2, -1, -1):
        speed[i] = min(speed[i], math.sqrt(speed[i + 1] ** 2 + 2 * args.max_brake * ROUTE_STEP_M))
    return speed


def drive_in_time(rng, speed, stops):
    """The 1 kHz time grid: speed over time (a dwell at the start and at each stop), smoothed to
    a finite jerk. Within a road step the acceleration is constant: its time is the step over
    the mean of its end speeds."""
    cell_s = 2 * ROUTE_STEP_M / np.maximum(speed[:-1] + speed[1:], 1e-9)
    node_t = np.concatenate([[0.0], np.cumsum(cell_s)])
    rests = [0] + stops
    dwell = np.zeros(len(node_t))
    dwell[rests] = rng.uniform(5.0, 30.0, len(rests))
    arrive = node_t + np.concatenate([[0.0], np.cumsum(dwell)[:-1]])
    times = np.concatenate([arrive, arrive[rests] + dwell[rests]])
    speeds = np.concatenate([speed, np.zeros(len(rests))])
    order = np.argsort(times, kind="stable")
    fine_t = np.arange(0.0, times[-1 - len(rests)] + 5.0, 1.0 / FINE_HZ)
    fine_v = np.interp(fine_t, times[order], speeds[order])
    kernel = np.ones(FINE_HZ // 2) / (FINE_HZ // 2)  # two 0.5 s boxcars: a triangle of 1 s
    fine_v = np.convolve(np.convolve(fine_v, kernel, "same"), kernel, "same")
    return fine_t, np.maximum(fine_v, 0.0)


def integrate(values, dt):
    return np.concatenate([[0.0], np.cumsum(0.5 * (values[1:] + values[:-1]) * dt)])


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("out")
    parser.add_argument("--seed", type=int, default=1)
    parser.add_argument("--distance-km", type=float, default=10.0)
    parser.add_argument("--max-speed", type=float, default=25.0, help="m/s")
    parser.add_argument("--max-lateral", type=float, default=2.5, help="m/s^2")
    parser.add_argument("--max-accel", type=float, default=1.5, help="m/s^2")
    parser.add_argument("--max-brake", type=float, default=2.0, help="m/s^2")
    parser.add_argument("--stop-share", type=float, default=0.25,
                        help="share of straights that end in a stop (5-30 s)")
    parser.add_argument("--drivetrain", choices=["front", "rear"], default="front")
    parser.add_argument("--load-mm-per-kn", type=float, default=0.0)
    parser.add_argument("--slip-stiffness", type=float, default=0.0, help="0: no slip")
    parser.add_argument("--speed-growth-s2pm2", type=float, default=0.0)
    parser.add_argument("--wear-rl-mm", type=float, default=1.5, help="radius")
    parser.add_argument("--wear-rr-mm", type=float, default=1.0, help="radius")
    parser.add_argument("--gnss-sigma", type=float, default=1.0, help="m, white")
    parser.add_argument("--doppler-sigma", type=float, help="m/s; absent: no speed column")
    parser.add_argument("--acc-sigma", type=float, default=0.05, help="m/s^2")
    parser.add_argument("--gyro-sigma", type=float, default=0.002, help="rad/s")
    parser.add_argument("--gyro-bias", type=float, default=0.0, help="rad/s")
    parser.add_argument("--unstated-body", action="store_true", help="vehicle.yaml without body")
    args = parser.parse_args()
    route_rng = np.random.default_rng(args.seed)
    noise_rng = np.random.default_rng(10_000 + args.seed)

    curvature, stops = road_curvature(route_rng, 1e3 * args.distance_km, args.stop_share)
    road_s = ROUTE_STEP_M * np.arange(len(curvature))
    t, v = drive_in_time(route_rng, speed_profile(curvature, stops, args), stops)
    dt = 1.0 / FINE_HZ
    s = integrate(v, dt)
    yaw_rate = v * np.interp(s, road_s, curvature)
    yaw = integrate(yaw_rate, dt)
    x, y = integrate(v * np.cos(yaw), dt), integrate(v * np.sin(yaw), dt)
    a_x, a_y = np.gradient(v, dt), v * yaw_rate

    mass, h = BODY["mass_kg"], BODY["cg_height_m"]
    static_n = 0.5 * mass * GRAVITY_MPS2 * BODY["rear_axle_load_share"]
    forward_n = 0.5 * mass * a_x * h / WHEELBASE_M
    lateral_n = mass * a_y * h / TRACK_M * BODY["rear_roll_share"]
    loads = [static_n + forward_n - lateral_n, static_n + forward_n + lateral_n]  # left, right
    resistance = (0.5 * AIR_DENSITY_KGPM3 * BODY["drag_area_m2"] * v ** 2 +
                  BODY["rolling_resistance"] * mass * GRAVITY_MPS2) * (v > 0.05)
    force = mass * a_x + resistance  # the tyres' total forward force
    rear_share = np.where(force > 0, 1.0 if args.drivetrain == "rear" else 0.0,
                          BODY["brake_rear_share"])
    radii = [NOMINAL_RADIUS_M - 1e-3 * args.wear_rl_mm, NOMINAL_RADIUS_M - 1e-3 * args.wear_rr_mm]
    ticks, rolled = [], []
    for side, (radius, load) in enumerate(zip(radii, loads)):
        ground = v + (side - 0.5) * TRACK_M * yaw_rate
        slip = (0.5 * rear_share * force / (args.slip_stiffness * load)
                if args.slip_stiffness > 0 else 0.0)
        rolling = (radius * (1 + args.speed_growth_s2pm2 * v ** 2)
                   - 1e-6 * args.load_mm_per_kn * (load - static_n))
        angle = integrate(ground * (1 + slip) / rolling, dt)
        rolled.append(2 * math.pi * integrate(np.abs(ground), dt)[-1] / angle[-1])
        start = int(noise_rng.integers(0, 1 << COUNTER_BITS))
        ticks.append((start + np.floor(angle * TICKS_PER_REV / (2 * math.pi)).astype(np.int64))
                     % (1 << COUNTER_BITS))
    write_log(args, noise_rng, t, x, y, yaw, v, a_x, a_y, yaw_rate, ticks, radii, rolled)


def write_log(args, rng, t, x, y, yaw, v, a_x, a_y, yaw_rate, ticks, radii, rolled):
    os.makedirs(args.out, exist_ok=True)
    nominal_c = 2 * math.pi * NOMINAL_RADIUS_M
    body = "".join(f"  {key}: {value}\n" for key, value in BODY.items())
    with open(os.path.join(args.out, "vehicle.yaml"), "w") as f:
        f.write(f"track_width_m: {TRACK_M}\nwheelbase_m: {WHEELBASE_M}\n"
                f"circumference_rl_m: {nominal_c:.6f}\ncircumference_rr_m: {nominal_c:.6f}\n"
                f"ticks_per_rev: {TICKS_PER_REV}\ncounter_bits: {COUNTER_BITS}\n"
                f"imu_x_m: 0.0\ngnss_x_m: 0.0\n")
        if not args.unstated_body:
            f.write(f"body:\n{body}  drivetrain: {args.drivetrain}\n")
    with open(os.path.join(args.out, "truth.yaml"), "w") as f:
        f.write("# The static circumferences (at rest, static load); estimators never read it.\n"
                f"circumference_rl_m: {2 * math.pi * radii[0]:.9f}\n"
                f"circumference_rr_m: {2 * math.pi * radii[1]:.9f}\n"
                "# Each wheel's ground distance over its revolutions: what this drive rolled on.\n"
                f"rolled_circumference_rl_m: {rolled[0]:.9f}\n"
                f"rolled_circumference_rr_m: {rolled[1]:.9f}\n"
                f"track_width_m: {TRACK_M}\nseed: {args.seed}\n"
                f"distance_m: {np.sum(v) / FINE_HZ:.1f}\n")
    time_s = T0_S + t

    def rows(rate):
        return np.arange(0, len(t), FINE_HZ // rate)

    wheel = rows(WHEEL_HZ)
    np.savetxt(os.path.join(args.out, "wheels.csv"),
               np.column_stack([time_s[wheel], ticks[0][wheel], ticks[1][wheel]]),
               fmt=["%.3f", "%d", "%d"], delimiter=",", header="t,rl_ticks,rr_ticks", comments="")
    np.savetxt(os.path.join(args.out, "truth.csv"),
               np.column_stack([time_s[wheel], x[wheel], y[wheel],
                                np.remainder(yaw[wheel] + math.pi, 2 * math.pi) - math.pi]),
               fmt=["%.3f", "%.4f", "%.4f", "%.7f"], delimiter=",", header="t,x,y,heading",
               comments="")
    imu = rows(IMU_HZ)
    n = len(imu)
    np.savetxt(os.path.join(args.out, "imu.csv"),
               np.column_stack([time_s[imu], a_x[imu] + rng.normal(0, args.acc_sigma, n),
                                a_y[imu] + rng.normal(0, args.acc_sigma, n),
                                yaw_rate[imu] + args.gyro_bias +
                                rng.normal(0, args.gyro_sigma, n)]),
               fmt=["%.3f", "%.5f", "%.5f", "%.6f"], delimiter=",", header="t,ax,ay,wz",
               comments="")
    fix = rows(GNSS_HZ)
    n = len(fix)
    columns = [time_s[fix], x[fix] + rng.normal(0, args.gnss_sigma, n),
               y[fix] + rng.normal(0, args.gnss_sigma, n), np.full(n, args.gnss_sigma)]
    header, fmt = "t,x,y,sigma_m", ["%.3f", "%.3f", "%.3f", "%g"]
    if args.doppler_sigma is not None:
        columns.append(np.abs(v[fix] + rng.normal(0, args.doppler_sigma, n)))
        header, fmt = header + ",speed_mps", fmt + ["%.3f"]
    np.savetxt(os.path.join(args.out, "gnss.csv"), np.column_stack(columns), fmt=fmt,
               delimiter=",", header=header, comments="")


if __name__ == "__main__":
    main()
