#!/usr/bin/env python3
"""Writes examples/figure-eight: a closed-form figure-eight drive in odocal's log format.

Two tangent circles of radius R driven at constant speed (first counter-clockwise, then
clockwise), rear wheels worn below their nominal circumference. Every stream comes from the
exact geometry, independent of odocal's model code, so tests can use it as ground truth.
Usage: tools/make_figure_eight_log.py [OUT_DIR]
"""

import math
import os
import random
import sys

RADIUS_M = 20.0
SPEED_MPS = 5.0
TRACK_WIDTH_M = 1.6
NOMINAL_RADIUS_M = 0.3126
WEAR_RL_M = 0.0015
WEAR_RR_M = 0.0010
TICKS_PER_REV = 96
COUNTER_BITS = 16
RL_COUNTER_START = 65000  # the rear-left counter wraps during the drive
T0_S = 100.0
WHEEL_RATE_HZ = 50
GNSS_RATE_HZ = 10
GNSS_SIGMA_M = 1.0
HEADING_SIGMA_RAD = 0.05
ACC_SIGMA_MPS2 = 0.05
YAW_RATE_SIGMA_RADPS = 0.005
SEED = 2019


def pose_and_wheels(distance_m):
    """Pose (x, y, yaw) and rear wheel arc lengths after `distance_m` along the eight."""
    lap_m = 2.0 * math.pi * RADIUS_M
    half = TRACK_WIDTH_M / 2.0
    if distance_m <= lap_m:  # counter-clockwise around (0, R)
        angle = distance_m / RADIUS_M
        pose = (RADIUS_M * math.sin(angle), RADIUS_M * (1 - math.cos(angle)), angle)
        return pose, (RADIUS_M - half) * angle, (RADIUS_M + half) * angle, 1.0
    angle = (distance_m - lap_m) / RADIUS_M  # clockwise around (0, -R)
    pose = (RADIUS_M * math.sin(angle), -RADIUS_M * (1 - math.cos(angle)), -angle)
    first = 2.0 * math.pi
    return pose, (RADIUS_M - half) * first + (RADIUS_M + half) * angle, \
        (RADIUS_M + half) * first + (RADIUS_M - half) * angle, -1.0


def main():
    out = sys.argv[1] if len(sys.argv) > 1 else os.path.join(
        os.path.dirname(__file__), "..", "examples", "figure-eight")
    os.makedirs(out, exist_ok=True)
    rng = random.Random(SEED)
    nominal_c = 2 * math.pi * NOMINAL_RADIUS_M
    true_c_rl = 2 * math.pi * (NOMINAL_RADIUS_M - WEAR_RL_M)
    true_c_rr = 2 * math.pi * (NOMINAL_RADIUS_M - WEAR_RR_M)
    duration_s = 4 * math.pi * RADIUS_M / SPEED_MPS
    samples = int(duration_s * WHEEL_RATE_HZ) + 1
    step = WHEEL_RATE_HZ // GNSS_RATE_HZ
    modulus = 1 << COUNTER_BITS

    with open(os.path.join(out, "vehicle.yaml"), "w") as f:
        f.write(f"# Nominal values: the calibration's starting guess.\n"
                f"track_width_m: {TRACK_WIDTH_M}\n"
                f"circumference_rl_m: {nominal_c:.6f}\n"
                f"circumference_rr_m: {nominal_c:.6f}\n"
                f"ticks_per_rev: {TICKS_PER_REV}\n"
                f"counter_bits: {COUNTER_BITS}\n")
    with open(os.path.join(out, "truth.yaml"), "w") as f:
        f.write(f"# What the generator really used; estimators never read this file.\n"
                f"circumference_rl_m: {true_c_rl:.9f}\n"
                f"circumference_rr_m: {true_c_rr:.9f}\n"
                f"track_width_m: {TRACK_WIDTH_M}\n"
                f"seed: {SEED}\n")

    files = {name: open(os.path.join(out, name), "w")
             for name in ("wheels.csv", "gnss.csv", "imu.csv", "heading.csv", "truth.csv")}
    files["wheels.csv"].write("t,rl_ticks,rr_ticks\n")
    files["gnss.csv"].write("t,x,y,sigma_m\n")
    files["imu.csv"].write("t,ax,ay,wz\n")
    files["heading.csv"].write("t,heading\n")
    files["truth.csv"].write("t,x,y,heading\n")
    for k in range(samples):
        t = T0_S + k / WHEEL_RATE_HZ
        (x, y, yaw), left_m, right_m, turn = pose_and_wheels(min(k / WHEEL_RATE_HZ * SPEED_MPS,
                                                                 4 * math.pi * RADIUS_M))
        rl = (RL_COUNTER_START + math.floor(left_m / true_c_rl * TICKS_PER_REV)) % modulus
        rr = math.floor(right_m / true_c_rr * TICKS_PER_REV) % modulus
        files["wheels.csv"].write(f"{t:.3f},{rl},{rr}\n")
        files["truth.csv"].write(f"{t:.3f},{x:.6f},{y:.6f},{yaw:.9f}\n")
        files["imu.csv"].write(
            f"{t:.3f},{rng.gauss(0.0, ACC_SIGMA_MPS2):.5f},"
            f"{turn * SPEED_MPS ** 2 / RADIUS_M + rng.gauss(0.0, ACC_SIGMA_MPS2):.5f},"
            f"{turn * SPEED_MPS / RADIUS_M + rng.gauss(0.0, YAW_RATE_SIGMA_RADPS):.6f}\n")
        if k % step == 0:
            files["gnss.csv"].write(f"{t:.3f},{x + rng.gauss(0.0, GNSS_SIGMA_M):.3f},"
                                    f"{y + rng.gauss(0.0, GNSS_SIGMA_M):.3f},{GNSS_SIGMA_M}\n")
            heading = math.remainder(yaw + rng.gauss(0.0, HEADING_SIGMA_RAD), 2 * math.pi)
            files["heading.csv"].write(f"{t:.3f},{heading:.6f}\n")
    for f in files.values():
        f.close()


if __name__ == "__main__":
    main()
