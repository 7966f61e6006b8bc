#!/usr/bin/python3
"""How much of the rear wheels' true rolling factor a tyre-model regressor set explains, from a
simulated log's truth alone (no estimator involved): docs/tyre-model.md, "Checked against the
truth".

For each window of W wheel samples the ground distance of each rear wheel comes from truth.csv
(the reference point's motion along the heading, minus/plus half the track times the turn), its
revolutions from wheels.csv (written with `--wheel-output rad`), so that its factor is
f_i = distance_i / (revolutions_i c_i) with c_i the static circumference of truth.yaml. The driving
state (speed, a_x, a_y, yaw rate) is the truth's too. The factors of both wheels are fitted by
least squares with an intercept (per wheel: the error of the circumference at rest that the
terms' extrapolation leaves) to the regression terms of tyre_model: extended (the first five,
and all seven) and to the three physical terms of tyre_model: physical (their slip dividing the
circumference, as odocal's factor; and, for comparison, in the linear form), these computed with
vehicle.yaml's default body (and the log's drivetrain) from the accelerometer's specific force
in imu.csv (window means; the batch takes each wheel sample's own, as --window 1 does) as the
batch computes them; printed: what is left of the factors' differential (heading) and
mean (distance) parts, and the intercepts in millimetres. Last, the best that any rolling
circumference can dead-reckon the log: each sample's ground distance along the true heading (the
true factors exactly), without the rear axle's sideways motion (its side slip), which no
circumference carries; the mean position error over the log.

    odocal simulate --out LOG --track TRACK.csv --laps 3 --wheel-output rad [--scenario S.yaml]
    /usr/bin/python3 tools/tyre_truth_regression.py LOG [--window 25]
"""
import argparse
import re

import numpy as np


def static_circumference(log):
    text = open(f"{log}/truth.yaml").read()
    left = float(re.search(r"circumference_rl_m: ([0-9.]+)", text)[1])
    right = float(re.search(r"circumference_rr_m: ([0-9.]+)", text)[1])
    track = float(re.search(r"track_width_m: ([0-9.]+)", text)[1])
    return left, right, track


def regressors(side, a_x, a_y, v, w, load_terms):
    drive = np.where(a_x > 0, -a_x, 0.0)
    brake = np.where(a_x < 0, -a_x, 0.0)
    turn = side * a_y
    columns = [np.ones_like(v), v * v, turn, drive, brake, w * w]
    if load_terms:
        columns += [drive * turn, brake * turn]
    return np.column_stack(columns)


# vehicle.yaml's default body (odocal/model/tyre_model.hpp's VehicleBody).
BODY = {"wheelbase_m": 2.7, "rear_axle_load_share": 0.463, "cg_height_m": 0.55,
        "rear_roll_share": 0.45, "mass_kg": 1500.0, "drag_area_m2": 0.7,
        "rolling_resistance": 0.012, "friction": 1.0, "slip_curve_shape": 1.65,
        "brake_rear_share": 0.35, "all_wheel_drive_rear_share": 0.6,
        "front_cornering_stiffness": 16.0, "rear_cornering_stiffness": 19.0,
        "lateral_curve_shape": 1.3}


def drive_rear_share(log):
    """The rear axle's share of the drive, from vehicle.yaml's body.drivetrain (unstated: rear)."""
    match = re.search(r"drivetrain: (\w+)", open(f"{log}/vehicle.yaml").read())
    drivetrain = match[1] if match else "rear"
    return {"rear": 1.0, "front": 0.0, "all": BODY["all_wheel_drive_rear_share"]}[drivetrain]


def slip_curve_bend(force_over_load):
    """The magic formula's slip over its linear part (tyre_model.hpp's slip_curve_bend)."""
    x = np.clip(np.abs(force_over_load) / BODY["friction"], 1e-6, 0.99)
    c = BODY["slip_curve_shape"]
    return np.where(np.abs(force_over_load) < 1e-6, 1.0, c * np.tan(np.arcsin(x) / c) / x)


def grip_limited(force_over_load, axle_share):
    """The force over load a wheel carrying axle_share of its axle's force can transmit: at most
    its grip (tyre_model.hpp's grip_limited)."""
    if axle_share <= 0:
        return force_over_load
    limit = 0.99 * BODY["friction"] / axle_share
    return np.clip(force_over_load, -limit, limit)


def slip_angle(force_over_load, stiffness):
    """The lateral magic formula inverted (tyre_model.hpp's slip_angle_rad)."""
    c, mu = BODY["lateral_curve_shape"], BODY["friction"]
    x = np.clip(force_over_load / mu, -0.99, 0.99)
    return np.tan(np.arcsin(x) / c) * c * mu / stiffness


def cornering_drag(f_y, a_x, v, w, w_dot):
    """The front tyres' lateral force along their steer, per vehicle mass (tyre_model.hpp's
    cornering_drag_mps2)."""
    g, b = 9.81, BODY
    length = b["wheelbase_m"]
    front_arm = b["rear_axle_load_share"] * length
    rear_arm = length - front_arm
    front = rear_arm * (f_y + front_arm * w_dot) / length
    rear = front_arm * (f_y - rear_arm * w_dot) / length
    shift = b["cg_height_m"] * a_x / length
    front_load = np.maximum(g * rear_arm / length - shift, 0.1 * g * rear_arm / length)
    rear_load = np.maximum(g * front_arm / length + shift, 0.1 * g * front_arm / length)
    steer = (length * w / np.maximum(v, 1.0)
             + slip_angle(front / front_load, b["front_cornering_stiffness"])
             - slip_angle(rear / rear_load, b["rear_cornering_stiffness"]))
    return front * steer


def physical_regressors(side, f_x, f_y, v, w, track, drive_share, a_x, w_dot):
    """The physical terms: minus the wheel's load change, minus its force over load (driving,
    braking) times the slip curve's bend, per vehicle mass, as tyre_regressors computes them."""
    g, b = 9.81, BODY
    length, h = b["wheelbase_m"], b["cg_height_m"]
    static = 0.5 * g * b["rear_axle_load_share"]
    load_change = h * f_x / (2 * length) - side * b["rear_roll_share"] * h * f_y / track
    tractive = (f_x + 0.6 * b["drag_area_m2"] / b["mass_kg"] * v * v
                + b["rolling_resistance"] * g + cornering_drag(f_y, a_x, v, w, w_dot))
    force_over_load = 0.5 * tractive / np.maximum(static + load_change, 0.1 * static)
    driven = grip_limited(force_over_load, drive_share)
    braked = grip_limited(force_over_load, b["brake_rear_share"])
    driving = -driven * slip_curve_bend(drive_share * driven)
    braking = -braked * slip_curve_bend(b["brake_rear_share"] * braked)
    return np.column_stack([np.ones_like(v), -load_change, np.where(tractive > 0, driving, 0.0),
                            np.where(tractive < 0, braking, 0.0)])


def report(name, A_left, A_right, f_left, f_right, circumferences, names):
    A = np.vstack([A_left, A_right])
    b = np.concatenate([f_left, f_right])
    # One intercept per wheel: each circumference's own error.
    count = len(f_left)
    A = np.column_stack([np.r_[np.ones(count), np.zeros(count)],
                         np.r_[np.zeros(count), np.ones(count)], A[:, 1:]])
    coefficients, *_ = np.linalg.lstsq(A, b, rcond=None)
    residual = b - A @ coefficients
    left, right = residual[:count], residual[count:]
    print(f"{name}: left of the differential {np.std(left - right):.3e}, of the mean part "
          f"{np.std(0.5 * (left + right)):.3e}; circumference at rest "
          f"{1e3 * coefficients[0] * circumferences[0]:+.2f} / "
          f"{1e3 * coefficients[1] * circumferences[1]:+.2f} mm")
    print("   " + ", ".join(f"{n} {value:.3g}" for n, value in zip(names, coefficients[2:])))


def path_steps(truth):
    """Each sample step's course (its mean heading) and its ground distance along it."""
    heading = np.unwrap(truth[:, 3])
    course = 0.5 * (heading[1:] + heading[:-1])
    return course, np.diff(truth[:, 1]) * np.cos(course) + np.diff(truth[:, 2]) * np.sin(course)


def window_motion(truth, wheels, window):
    """Per window of `window` samples: its first and last sample, its duration, the reference
    point's ground distance along the heading, its turn, and each rear wheel's revolutions."""
    k = np.arange(0, len(truth) - window, window)
    n = k + window
    t, heading = truth[:, 0], np.unwrap(truth[:, 3])
    # The path's length summed sample by sample: a window's chord falls short of its arc by
    # theta^2 / 24 (0.4 per mille at 0.1 rad of turn), which on a fast circuit biased every
    # factor (-8 mm at rest on Hockenheim, rear-driven, with 0.5 s windows).
    travelled = np.concatenate([[0.0], np.cumsum(path_steps(truth)[1])])
    revs_left = (wheels[n, 1] - wheels[k, 1]) / (2 * np.pi)
    revs_right = (wheels[n, 2] - wheels[k, 2]) / (2 * np.pi)
    return (k, n, t[n] - t[k], travelled[n] - travelled[k], heading[n] - heading[k], revs_left,
            revs_right)


def true_factors(along, turn, revs_left, revs_right, circumferences, track):
    """Each rear wheel's factor c_eff / c - 1: its ground distance over its revolutions."""
    return ((along - 0.5 * track * turn) / (revs_left * circumferences[0]) - 1.0,
            (along + 0.5 * track * turn) / (revs_right * circumferences[1]) - 1.0)


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("log")
    parser.add_argument("--window", type=int, default=25, help="wheel samples per window")
    args = parser.parse_args()
    c_left, c_right, track = static_circumference(args.log)
    truth = np.loadtxt(f"{args.log}/truth.csv", delimiter=",", skiprows=1)
    wheels = np.loadtxt(f"{args.log}/wheels.csv", delimiter=",", skiprows=1)
    if truth.shape[0] != wheels.shape[0] or not np.allclose(truth[:, 0], wheels[:, 0]):
        raise SystemExit("truth.csv and wheels.csv must share their times")
    k, n, dt, along, turn, revs_left, revs_right = window_motion(truth, wheels, args.window)
    v, w = along / dt, turn / dt
    a_x, a_y = np.gradient(v, dt.mean()), v * w
    moving = (v > 3.0) & (revs_left > 0) & (revs_right > 0)
    f_left, f_right = true_factors(along[moving], turn[moving], revs_left[moving],
                                   revs_right[moving], (c_left, c_right), track)
    state = (a_x[moving], a_y[moving], v[moving], w[moving])
    print(f"{moving.sum()} windows of {args.window} samples; factor differential RMS "
          f"{np.std(f_left - f_right):.3e}, mean part RMS {np.std(0.5 * (f_left + f_right)):.3e}")
    names = "k_speed k_lateral k_drive k_brake k_turn k_drive_lateral k_brake_lateral".split()
    for load_terms in (False, True):
        count = 7 if load_terms else 5
        report(f"{count} regression terms", regressors(1.0, *state, load_terms),
               regressors(-1.0, *state, load_terms), f_left, f_right, (c_left, c_right),
               names[:count])
    imu = np.loadtxt(f"{args.log}/imu.csv", delimiter=",", skiprows=1)
    if imu.shape[0] != truth.shape[0] or not np.allclose(imu[:, 0], truth[:, 0]):
        raise SystemExit("imu.csv must share truth.csv's times")
    window_mean = lambda column: np.array([imu[a:b, column].mean() for a, b in zip(k, n)])
    f_x, f_y, gyro = window_mean(1), window_mean(2), window_mean(3)
    gyro_rate = np.gradient(gyro, dt.mean())
    physical = (f_x[moving], f_y[moving], v[moving], gyro[moving], track, drive_rear_share(args.log),
                a_x[moving], gyro_rate[moving])
    A_left, A_right = physical_regressors(1.0, *physical), physical_regressors(-1.0, *physical)
    names = ["k_load", "k_drive_slip", "k_brake_slip"]
    # The slip divides (c (1 + k_load x_load) / (1 + kappa), tyre_factor_with_gradient): with
    # 1 + f the true factor, f = delta + k_load x_load - kappa (1 + f), linear in the coefficients.
    divided_left, divided_right = A_left.copy(), A_right.copy()
    divided_left[:, 2:] *= (1.0 + f_left)[:, None]
    divided_right[:, 2:] *= (1.0 + f_right)[:, None]
    report("3 physical terms", divided_left, divided_right, f_left, f_right, (c_left, c_right),
           names)
    report("3 physical terms, slip linear (c (1 - kappa), odocal before 2026-11-30)", A_left,
           A_right, f_left, f_right, (c_left, c_right), names)
    x, y = truth[:, 1], truth[:, 2]
    course, along_step = path_steps(truth)
    reckoned_x = x[0] + np.concatenate([[0.0], np.cumsum(along_step * np.cos(course))])
    reckoned_y = y[0] + np.concatenate([[0.0], np.cumsum(along_step * np.sin(course))])
    print(f"dead reckoning with the true factors, without the side slip: mean position error "
          f"{np.mean(np.hypot(reckoned_x - x, reckoned_y - y)):.1f} m over "
          f"{np.sum(np.abs(along_step)) / 1e3:.1f} km")


if __name__ == "__main__":
    main()
