#!/usr/bin/python3
"""Fleet benchmark (issue 19; figures in docs/fleet.md): a simulated fleet calibrated by
odocal-fleet run with 1 and 2 Dask workers (speed-up, cost per drive), then odocal-fleet health
scored against the fleet's truth: tyre-change steps found within 50 km, pressure losses flagged
within 20 minutes of driving, false alarms on vehicles without events, and the smoothed sigma
against 1/sqrt(N). Run from the repository after `make build`:

    PYTHONPATH=build/python ODOCAL_CLI=build/apps/odocal/odocal \\
        /usr/bin/python3 bench/fleet_bench.py --vehicles 40 --drives 12 --work /tmp/fleet-bench
"""
import argparse
import json
import math
import os
import shutil
import time

import numpy as np

from odocal_fleet import cli, health


def timed_run(logs, db, workers):
    start = time.perf_counter()
    assert cli.main(["run", *logs, "--db", db, "--workers", str(workers)]) == 0
    return time.perf_counter() - start


def score(truth, report):
    by_vehicle = {v["vehicle_id"]: v for v in report["vehicles"]}
    rows = {"steps": [], "pressure": [], "rotations": [], "false_vehicles": 0, "clean_vehicles": 0,
            "sigma_ratio": []}
    for vehicle in truth["vehicles"]:
        found = by_vehicle.get(vehicle["vehicle_id"], {"events": [], "wheels": {}})
        event = vehicle["event"]
        drives = vehicle["drives"]
        if event is None:
            rows["clean_vehicles"] += 1
            rows["false_vehicles"] += bool(found["events"])
            for wheel, w in found["wheels"].items():
                # Of the drives' own errors: the shared one (the body's) floors the level and
                # does not average out.
                n = len(w["sigma_m"])
                single = w["sigma_scale"] * float(np.median(w["drive_sigma_m"]))
                own = math.sqrt(max(w["sigma_m"][-1] ** 2 - w["common_sigma_m"][-1] ** 2, 0.0))
                rows["sigma_ratio"].append(own / (single / math.sqrt(n)))
            continue
        index = event["drive_index"]
        wheels = {"rl", "rr"} if event["wheel"] == "both" else {event["wheel"]}
        # (drive.yaml holds the odometer to the metre)
        early = [e for e in found["events"] if e["odometer_km"] < event["odometer_km"] - 0.01]
        hits = [e for e in found["events"] if e["wheel"] in wheels
                and e["odometer_km"] >= event["odometer_km"] - 0.01]
        detected = min(hits, key=lambda e: e["detected_at_km"]) if hits else None
        entry = {"vehicle": vehicle["vehicle_id"], "found": detected is not None,
                 "early_alarms": len(early)}
        if detected:
            end = next(i for i, d in enumerate(drives)
                       if os.path.basename(detected["detected_after_drive"]) == d["name"])
            entry["km"] = detected["detected_at_km"] + drives[end]["distance_m"] / 1000.0 \
                - event["odometer_km"]
            entry["minutes"] = sum(d["duration_s"] for d in drives[index:end + 1]) / 60.0
            entry["kind"] = detected["kind"]
        key = {"tyre change": "steps", "pressure loss": "pressure", "rotation": "rotations"}
        rows[key[event["kind"]]].append(entry)
    return rows


def summarise(rows, seconds):
    lines = []
    for name, kind, limit, unit in (("steps", "tyre change", 50.0, "km"),
                                    ("pressure", "pressure loss", 20.0, "minutes"),
                                    ("rotations", "rotation", None, "km")):
        entries = rows[name]
        if not entries:
            continue
        found = [e for e in entries if e["found"]]
        within = [e for e in found if limit is None or e[unit] <= limit]
        named = [e for e in found if e["kind"] == kind]
        values = [e[unit] for e in found]
        lines.append(f"| {kind} | {len(entries)} | {len(found)} | "
                     f"{len(within) if limit else '–'} ({'≤ %g %s' % (limit, unit) if limit else ''}) | "
                     f"{np.median(values) if values else float('nan'):.1f} {unit} median, "
                     f"{max(values) if values else float('nan'):.1f} max | {len(named)} |")
    return lines


def synthetic_vehicles(report, vehicles, drives, seed, step_at=None, step_m=0.0, km=7.3):
    """Vehicles drawn with the noise the simulated fleet showed (each wheel's own drive sigma,
    without the body's shared share, times its scale), `km` apart, optionally with a step on
    RL: detection and false-alarm rates over many more vehicles than were simulated. Returns
    (vehicles with any event, RL steps found within 50 km of their drive)."""
    sigmas = [w["sigma_scale"] * float(np.median(w["drive_sigma_m"]))
              for v in report["vehicles"] for w in v["wheels"].values()]
    rng = np.random.default_rng(seed)
    model = health.HealthModel()
    alarms = found = 0
    for v in range(vehicles):
        sigma = sigmas[v % len(sigmas)]
        series = {}
        for wheel in ("rl", "rr"):
            series[wheel] = [health.Drive(
                odometer_km=1e4 + km * k, start_time="", path=str(k),
                value_m=1.95 - 0.4e-6 * km * k + sigma * rng.standard_normal()
                + (step_m if wheel == "rl" and step_at is not None and k >= step_at else 0.0),
                sigma_m=sigma) for k in range(drives)]
        _, events = health.vehicle_health(model, series)
        alarms += bool(events)
        found += any(e.wheel == "rl" and e.drive_index >= step_at
                     and (e.detected_at_index + 1 - step_at) * km <= 50.0
                     for e in events) if step_at is not None else 0
    return alarms, found


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--vehicles", type=int, default=40)
    parser.add_argument("--drives", type=int, default=12)
    parser.add_argument("--speed-vehicles", type=int, default=6,
                        help="vehicles timed with 1 and 2 workers")
    parser.add_argument("--synthetic-vehicles", type=int, default=2000)
    parser.add_argument("--synthetic-drives", type=int, default=50,
                        help="drives of each drawn event-free vehicle (the rate is stated for 50)")
    parser.add_argument("--seed", type=int, default=1)
    parser.add_argument("--work", required=True, help="scratch directory (replaced)")
    parser.add_argument("--score-only", action="store_true",
                        help="reuse the fleet and database in --work: health and scores only")
    args = parser.parse_args()
    fleet = os.path.join(args.work, "fleet")
    db = os.path.join(args.work, "fleet.sqlite")
    subset_drives = args.speed_vehicles * args.drives
    if args.score_only:
        simulate_s = one = two = whole = float("nan")
    else:
        shutil.rmtree(args.work, ignore_errors=True)
        start = time.perf_counter()
        assert cli.main(["simulate", "--vehicles", str(args.vehicles), "--drives",
                         str(args.drives), "--out", fleet, "--seed", str(args.seed)]) == 0
        simulate_s = time.perf_counter() - start
        subset = [os.path.join(fleet, f"car-{v:03d}") for v in range(args.speed_vehicles)]
        one = timed_run(subset, os.path.join(args.work, "one.sqlite"), 1)
        two = timed_run(subset, os.path.join(args.work, "two.sqlite"), 2)
        shutil.copy(os.path.join(args.work, "two.sqlite"), db)
        whole = timed_run([fleet], db, 2)
    report_file = os.path.join(args.work, "health.json")
    start = time.perf_counter()
    assert cli.main(["health", "--db", db, "--json", report_file]) == 0
    health_s = time.perf_counter() - start
    with open(os.path.join(fleet, "fleet_truth.json")) as f:
        truth = json.load(f)
    with open(report_file) as f:
        report = json.load(f)
    rows = score(truth, report)
    early = sum(e["early_alarms"] > 0 for k in ("steps", "pressure", "rotations") for e in rows[k])
    synthetic, _ = synthetic_vehicles(report, args.synthetic_vehicles, args.synthetic_drives,
                                      args.seed)
    _, steps_found = synthetic_vehicles(report, args.synthetic_vehicles, args.synthetic_drives,
                                        args.seed + 1, step_at=args.synthetic_drives // 2,
                                        step_m=2 * math.pi * 1e-3)
    print(f"\nfleet: {args.vehicles} vehicles x {args.drives} drives ({truth['scenario']}, "
          f"{truth['laps']} laps each), simulated in {simulate_s:.0f} s")
    if not args.score_only:
        per_drive = one / subset_drives
        print(f"speed: {subset_drives} drives, 1 worker {one:.1f} s ({per_drive:.2f} s per drive), "
              f"2 workers {two:.1f} s: speed-up {one / two:.2f}x; the rest of the fleet "
              f"{whole:.1f} s on 2 workers; health {health_s:.1f} s")
        print(f"a 10 000-drive day at {per_drive:.2f} s per drive per worker: "
              f"{10_000 * per_drive / 3600:.1f} worker-hours: "
              f"{math.ceil(10_000 * per_drive / 3600 / 8)} worker(s) over 8 hours")
    print("\n| event | vehicles | found | within target | delay (to the end of the drive that found it) | named so |")
    print("|---|---|---|---|---|---|")
    for line in summarise(rows, None):
        print(line)
    clean = rows["clean_vehicles"]
    print(f"\nfalse alarms: {rows['false_vehicles']} of {clean} simulated vehicles without event; "
          f"{early} event vehicles alarmed before their event; {synthetic} of "
          f"{args.synthetic_vehicles} drawn event-free vehicles ({args.synthetic_drives} drives, the "
          f"fleet's own per-drive noise): {synthetic / args.synthetic_vehicles:.2%} "
          f"(stated {health.HealthModel().false_alarm_rate:.0%} over 50 drives)")
    print(f"1 mm radius step on RL of {args.synthetic_vehicles} drawn vehicles (the same noise, "
          f"7.3 km per drive): found within 50 km in {steps_found} "
          f"({steps_found / args.synthetic_vehicles:.1%})")
    ratios = rows["sigma_ratio"]
    if ratios:
        print(f"smoothed sigma after N drives / (drive sigma / sqrt(N)): median "
              f"{np.median(ratios):.2f}, range {min(ratios):.2f}-{max(ratios):.2f}")


if __name__ == "__main__":
    main()
