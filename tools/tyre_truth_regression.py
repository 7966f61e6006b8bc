#!/usr/bin/python3
"""How much of the rear wheels' true rolling factor a tyre-model regressor set explains, from a
simulated log's truth alone (no estimator involved): docs/tyre-model.md, "Checked against the
truth".

For each window of W wheel samples the ground distance of each rear wheel comes from truth.csv
(the reference point's motion along the heading, minus/plus half the track times the turn), its
revolutions from wheels.csv (written with `--wheel-output rad`), so that its factor is
f_i = distance_i / (revolutions_i c_i) with c_i the static circumference of truth.yaml. The driving
state (speed, a_x, a_y, yaw rate) is the truth's too. The factors of both wheels are fitted by
least squares with an intercept to the regressors of the plain 5-coefficient model and of the
7-coefficient model (the slip's load terms added); printed: what is left of the factors'
differential (heading) and mean (distance) parts.

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
    k = np.arange(0, len(truth) - args.window, args.window)
    n = k + args.window
    t, x, y = truth[:, 0], truth[:, 1], truth[:, 2]
    heading = np.unwrap(truth[:, 3])
    dt = t[n] - t[k]
    mid = 0.5 * (heading[n] + heading[k])
    along = (x[n] - x[k]) * np.cos(mid) + (y[n] - y[k]) * np.sin(mid)
    turn = heading[n] - heading[k]
    revs_left = (wheels[n, 1] - wheels[k, 1]) / (2 * np.pi)
    revs_right = (wheels[n, 2] - wheels[k, 2]) / (2 * np.pi)
    v, w = along / dt, turn / dt
    a_x, a_y = np.gradient(v, dt.mean()), v * w
    moving = (v > 3.0) & (revs_left > 0) & (revs_right > 0)
    f_left = (along - 0.5 * track * turn)[moving] / (revs_left[moving] * c_left) - 1.0
    f_right = (along + 0.5 * track * turn)[moving] / (revs_right[moving] * c_right) - 1.0
    state = (a_x[moving], a_y[moving], v[moving], w[moving])
    print(f"{moving.sum()} windows of {args.window} samples; factor differential RMS "
          f"{np.std(f_left - f_right):.3e}, mean part RMS {np.std(0.5 * (f_left + f_right)):.3e}")
    for load_terms in (False, True):
        A = np.vstack([regressors(1.0, *state, load_terms), regressors(-1.0, *state, load_terms)])
        b = np.concatenate([f_left, f_right])
        coefficients, *_ = np.linalg.lstsq(A, b, rcond=None)
        residual = b - A @ coefficients
        left, right = residual[:moving.sum()], residual[moving.sum():]
        names = "k_speed k_lateral k_drive k_brake k_turn".split()
        names += ["k_drive_lateral", "k_brake_lateral"] if load_terms else []
        print(f"{len(names)} coefficients: left of the differential {np.std(left - right):.3e}, "
              f"of the mean part {np.std(0.5 * (left + right)):.3e}; intercept "
              f"{coefficients[0]:+.2e}")
        print("   " + ", ".join(f"{name} {value:.3g}" for name, value in zip(names, coefficients[1:])))


if __name__ == "__main__":
    main()
