#!/usr/bin/python3
"""Writes a logger's files "as they are" from a simulated drive, for the worked example in
docs/importing.md ("A logger as it is") and its test:

  wheels.csv  logger A, clock in ms since its boot: wheel angular rates in deg/s from sensors on
              the wheels, the right one mounted mirrored (its sign flipped); an Excel "sep=,"
              first line and a trailing comma on every line.
  nav.csv     logger B, clock in UNIX seconds: GNSS lat/lon (5 Hz fixes repeated on every 100 Hz
              row) and a body IMU in g and deg/s on the same rows; "sep=," and trailing commas.

Logger B's clock runs CLOCK_B_EPOCH_S + the simulation time + CLOCK_B_ERROR_S: the map states
the epoch (as a user knows it), `odocal import csv --sync` finds the error.

Usage: tools/make_messy_logger.py ODOCAL_BINARY OUT_DIR
"""
import csv
import math
import os
import subprocess
import sys
import tempfile

CLOCK_A_BOOT_MS = 52_000.0     # logger A had been on 52 s when the drive started
CLOCK_B_EPOCH_S = 1_700_000_000.0
CLOCK_B_ERROR_S = 0.4          # what the map does not know about logger B's clock
G = 9.80665

SCENARIO = """name: messy-logger
route:
  laps: 1
  segments:
    - {straight: 140, stop_s: 2}
    - arc: {radius_m: 10, turn_deg: 90}
    - straight: 185
    - arc: {radius_m: 10, turn_deg: 90}
    - straight: 140
    - arc: {radius_m: 10, turn_deg: -90}
    - straight: 85
    - arc: {radius_m: 10, turn_deg: 90}
    - straight: 130
    - arc: {radius_m: 10, turn_deg: 90}
    - straight: 85
    - arc: {radius_m: 10, turn_deg: -90}
    - straight: 100
    - arc: {radius_m: 10, turn_deg: 90}
driver: {max_speed_mps: 13.9, max_lateral_acc_mps2: 3, max_acc_mps2: 1.5, max_brake_mps2: 2.5}
sensors:
  gnss: {rate_hz: 5, sigma_m: 1.0, output: latlon}
  imu: {rate_hz: 100}
  heading: {rate_hz: 10}
  wheels: {rate_hz: 100, output: radps}
"""


def rows(path):
    with open(path, newline="") as f:
        return list(csv.DictReader(f))


def main():
    odocal, out = sys.argv[1], sys.argv[2]
    os.makedirs(out, exist_ok=True)
    with tempfile.TemporaryDirectory() as work:
        scenario = os.path.join(work, "scenario.yaml")
        with open(scenario, "w") as f:
            f.write(SCENARIO)
        log = os.path.join(work, "log")
        subprocess.run([odocal, "simulate", "--scenario", scenario, "--out", log], check=True,
                       stdout=subprocess.DEVNULL)
        wheels, gnss, imu = rows(f"{log}/wheels.csv"), rows(f"{log}/gnss.csv"), rows(f"{log}/imu.csv")
        with open(f"{log}/vehicle.yaml") as f:
            vehicle = f.read()
    deg = 180.0 / math.pi
    with open(os.path.join(out, "wheels.csv"), "w") as f:
        f.write("sep=,\nboot_ms,left_dps,right_dps,\n")
        for r in wheels:
            f.write(f"{float(r['t']) * 1000 + CLOCK_A_BOOT_MS:.1f},"
                    f"{float(r['rl_radps']) * deg:.5f},{-float(r['rr_radps']) * deg:.5f},\n")
    fix = 0
    with open(os.path.join(out, "nav.csv"), "w") as f:
        f.write("sep=,\nutc_s,lat,lon,acc_x_g,acc_y_g,gyro_z_dps,\n")
        for r in imu:
            t = float(r["t"])
            while fix + 1 < len(gnss) and float(gnss[fix + 1]["t"]) <= t + 1e-9:
                fix += 1
            g = gnss[fix]
            f.write(f"{t + CLOCK_B_EPOCH_S + CLOCK_B_ERROR_S:.3f},{g['lat']},{g['lon']},"
                    f"{float(r['ax']) / G:.6f},{float(r['ay']) / G:.6f},"
                    f"{float(r['wz']) * deg:.5f},\n")
    with open(os.path.join(out, "vehicle.yaml"), "w") as f:
        f.write(vehicle)


if __name__ == "__main__":
    main()
