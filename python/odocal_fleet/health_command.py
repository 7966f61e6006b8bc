"""odocal-fleet health: tyre health per vehicle and rear wheel from the fleet database."""
import json
import math
import os
import sqlite3
import sys
import tempfile

from . import health

WHEELS = ("rl", "rr")


def vehicle_drives(db, method):
    """{vehicle: [row]} of the usable calibrations by `method`, in driving order: by odometer
    when every drive states one, else by start time, else by path. Each row ends with the
    shares of each wheel's sigma that the vehicle's body numbers and the tyre coefficients held
    make (the batch's body_sigma_m and held_sigma_m; None where the calibration has
    none)."""
    rows = db.execute(
        """SELECT d.vehicle_id, d.path, d.start_time, d.odometer_km, d.distance_m,
                  c.circumference_rl_m, c.circumference_rr_m, c.sigma_rl_m, c.sigma_rr_m,
                  json_extract(c.result_json, '$.body_sigma_m[0]'),
                  json_extract(c.result_json, '$.body_sigma_m[1]'),
                  json_extract(c.result_json, '$.held_sigma_m[0]'),
                  json_extract(c.result_json, '$.held_sigma_m[1]')
           FROM drives d JOIN calibrations c USING (drive_key)
           WHERE c.method = ? AND c.usable = 1""", (method,)).fetchall()
    by_vehicle = {}
    for row in rows:
        by_vehicle.setdefault(row[0], []).append(row)
    for vehicle, drives in by_vehicle.items():
        if all(d[3] is not None for d in drives):
            drives.sort(key=lambda d: (d[3], d[1]))
        else:
            drives.sort(key=lambda d: (d[2] or "", d[1]))
            odometer = 0.0
            for i, d in enumerate(drives):  # no odometer: the calibrated drives' own distances
                drives[i] = d[:3] + (odometer,) + d[4:]
                odometer += (d[4] or 0.0) / 1000.0
    return by_vehicle


def has_estimate(row):
    return all(row[i] is not None for i in (5, 6, 7, 8)) and row[7] > 0 and row[8] > 0


def drive_of(row, i):
    """Wheel i's measurement of one drive. The body's share of its sigma is the same error on
    every drive of the vehicle (its body numbers, driven alike), and so is the held
    coefficients' (the car's own brake or side slip, held at a car's value wherever a
    drive cannot identify it): they leave the drive-to-drive changes that health tracks and stay in the
    level's sigma (a drive's own error is never taken as nil: at least 0.31 of its sigma)."""
    shared = math.hypot(row[9 + i] or 0.0, row[11 + i] or 0.0)
    sigma, common = row[7 + i], min(shared, 0.95 * row[7 + i])
    return health.Drive(odometer_km=row[3], start_time=row[2] or "", path=row[1],
                        value_m=row[5 + i], sigma_m=math.sqrt(sigma * sigma - common * common),
                        common_sigma_m=common)


def wheel_drives(rows):
    """{wheel: [health.Drive]} of one vehicle's rows."""
    return {wheel: [drive_of(r, i) for r in rows] for i, wheel in enumerate(WHEELS)}


def to_json(vehicle, rows, drives, wheels, events):
    out = {"vehicle_id": vehicle, "drives": len(rows), "wheels": {}, "events": []}
    for wheel, h in wheels.items():
        out["wheels"][wheel] = {
            "odometer_km": h.odometer_km.tolist(),
            "circumference_m": h.circumference_m.tolist(), "sigma_m": h.sigma_m.tolist(),
            "measured_m": [r[5 + WHEELS.index(wheel)] for r in rows],
            "measured_sigma_m": [r[7 + WHEELS.index(wheel)] for r in rows],
            # The measured sigma split: each drive's own error, and the vehicle's shared one.
            "drive_sigma_m": [d.sigma_m for d in drives[wheel]],
            "common_sigma_m": [d.common_sigma_m for d in drives[wheel]],
            "start_time": [r[2] for r in rows],
            "wear_mm_radius_per_10000_km": -1e4 * 1e3 * h.wear_rate_m_per_km / (2 * math.pi),
            "wear_sigma_mm_radius_per_10000_km": 1e4 * 1e3 * h.wear_rate_sigma_m_per_km / (2 * math.pi),
            "sigma_scale": h.sigma_scale}
    for e in events:
        out["events"].append({"kind": e.kind, "wheel": e.wheel, "drive": rows[e.drive_index][1],
                              "odometer_km": e.odometer_km, "start_time": e.start_time,
                              "step_mm": 1e3 * e.step_m, "sigma_mm": 1e3 * e.sigma_m,
                              "detected_after_drive": rows[e.detected_at_index][1],
                              "detected_at_km": e.detected_at_km})
    return out


def assess(db_path, method, model):
    if not os.path.exists(db_path):
        raise SystemExit(f"odocal-fleet: error: {db_path}: no such database")
    with sqlite3.connect(db_path) as db:
        by_vehicle = vehicle_drives(db, method)
    report = {"method": method, "false_alarm_rate": model.false_alarm_rate,
              "design_drives": model.design_drives, "vehicles": []}
    for vehicle in sorted(by_vehicle):
        rows = [r for r in by_vehicle[vehicle] if has_estimate(r)]
        if not rows:
            continue
        drives = wheel_drives(rows)
        wheels, events = health.vehicle_health(model, drives)
        report["vehicles"].append(to_json(vehicle, rows, drives, wheels, events))
    return report


def print_report(report):
    print(f"tyre health from {report['method']} calibrations; false-alarm rate "
          f"{report['false_alarm_rate']:.2%} per vehicle over {report['design_drives']} drives")
    for v in report["vehicles"]:
        print(f"{v['vehicle_id']}: {v['drives']} drives")
        for wheel, w in v["wheels"].items():
            print(f"  {wheel.upper()}  circumference {w['circumference_m'][-1]:.6f} m "
                  f"(1-sigma {1e3 * w['sigma_m'][-1]:.3f} mm) at {w['odometer_km'][-1]:.0f} km; "
                  f"wear {w['wear_mm_radius_per_10000_km']:.2f} mm of radius per 10 000 km "
                  f"(1-sigma {w['wear_sigma_mm_radius_per_10000_km']:.2f}); drive sigmas x"
                  f"{w['sigma_scale']:.2f}")
        for e in v["events"]:
            print(f"  event: {e['kind']} on {e['wheel'].upper()} at {e['odometer_km']:.0f} km "
                  f"({e['start_time'] or e['drive']}): {e['step_mm']:+.2f} mm of circumference "
                  f"(1-sigma {e['sigma_mm']:.2f}), found after {os.path.basename(e['detected_after_drive'])}")


def write_json(path, report):
    directory = os.path.dirname(os.path.abspath(path))
    with tempfile.NamedTemporaryFile("w", dir=directory, delete=False, suffix=".tmp") as f:
        json.dump(report, f, indent=1)
        temporary = f.name
    os.replace(temporary, path)


def run(args):
    model = health.HealthModel(false_alarm_rate=args.false_alarm_rate)
    try:
        report = assess(args.db, args.method, model)
    except (sqlite3.Error, ValueError) as error:
        print(f"odocal-fleet: error: {args.db}: {error}", file=sys.stderr)
        return 2
    print_report(report)
    if args.json:
        try:
            write_json(args.json, report)
        except OSError as error:
            print(f"odocal-fleet: error: {args.json}: {error.strerror}", file=sys.stderr)
            return 1
    return 0
