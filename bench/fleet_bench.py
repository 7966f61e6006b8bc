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
                n = len(w["sigma_m"])
                single = w["sigma_scale"] * float(np.median(w["measured_sigma_m"]))
                rows["sigma_ratio"].append(w["sigma_m"][-1] / (single / math.sqrt(n)))
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


def synthetic_false_alarms(report, vehicles, drives, seed):
    """Event-free vehicles drawn with the noise the simulated fleet showed (each wheel's sigma
    times its scale): the false-alarm rate over many more vehicles than were simulated."""
    sigmas = [w["sigma_scale"] * float(np.median(w["measured_sigma_m"]))
              for v in report["vehicles"] for w in v["wheels"].values()]
    rng = np.random.default_rng(seed)
    model = health.HealthModel()
    alarms = 0
    for v in range(vehicles):
        sigma = sigmas[v % len(sigmas)]
        series = {}
        for wheel in ("rl", "rr"):
            series[wheel] = [health.Drive(odometer_km=1e4 + 7.0 * k, start_time="", path=str(k),
                                          value_m=1.95 - 0.4e-6 * 7.0 * k
                                          + sigma * rng.standard_normal(), sigma_m=sigma)
                             for k in range(drives)]
        _, events = health.vehicle_health(model, series)
        alarms += bool(events)
    return alarms


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--vehicles", type=int, default=40)
    parser.add_argument("--drives", type=int, default=12)
    parser.add_argument("--speed-vehicles", type=int, default=6,
                        help="vehicles timed with 1 and 2 workers")
    parser.add_argument("--synthetic-vehicles", type=int, default=2000)
    parser.add_argument("--seed", type=int, default=1)
    parser.add_argument("--work", required=True, help="scratch directory (replaced)")
    args = parser.parse_args()
    shutil.rmtree(args.work, ignore_errors=True)
    fleet = os.path.join(args.work, "fleet")
    start = time.perf_counter()
    assert cli.main(["simulate", "--vehicles", str(args.vehicles), "--drives", str(args.drives),
                     "--out", fleet, "--seed", str(args.seed)]) == 0
    simulate_s = time.perf_counter() - start
    subset = [os.path.join(fleet, f"car-{v:03d}") for v in range(args.speed_vehicles)]
    one = timed_run(subset, os.path.join(args.work, "one.sqlite"), 1)
    two = timed_run(subset, os.path.join(args.work, "two.sqlite"), 2)
    subset_drives = args.speed_vehicles * args.drives
    db = os.path.join(args.work, "fleet.sqlite")
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
    synthetic = synthetic_false_alarms(report, args.synthetic_vehicles, args.drives, args.seed)
    per_drive = one / subset_drives
    print(f"\nfleet: {args.vehicles} vehicles x {args.drives} drives ({truth['scenario']}, "
          f"{truth['laps']} laps each), simulated in {simulate_s:.0f} s")
    print(f"speed: {subset_drives} drives, 1 worker {one:.1f} s ({per_drive:.2f} s per drive), "
          f"2 workers {two:.1f} s: speed-up {one / two:.2f}x; the rest of the fleet {whole:.1f} s "
          f"on 2 workers; health {health_s:.1f} s")
    print(f"a 10 000-drive day at {per_drive:.2f} s per drive per worker: "
          f"{math.ceil(10_000 * per_drive / 3600 / 8)} workers for 8 hours, "
          f"{math.ceil(10_000 * per_drive / 3600 / 1)} worker-hours in all")
    print("\n| event | vehicles | found | within target | delay (to the end of the drive that found it) | named so |")
    print("|---|---|---|---|---|---|")
    for line in summarise(rows, None):
        print(line)
    clean = rows["clean_vehicles"]
    print(f"\nfalse alarms: {rows['false_vehicles']} of {clean} simulated vehicles without event; "
          f"{early} event vehicles alarmed before their event; {synthetic} of "
          f"{args.synthetic_vehicles} drawn event-free vehicles ({args.drives} drives, the "
          f"fleet's own per-drive noise): {synthetic / args.synthetic_vehicles:.2%} "
          f"(stated {health.HealthModel().false_alarm_rate:.0%} over 50 drives)")
    ratios = rows["sigma_ratio"]
    if ratios:
        print(f"smoothed sigma after N drives / (drive sigma / sqrt(N)): median "
              f"{np.median(ratios):.2f}, range {min(ratios):.2f}-{max(ratios):.2f}")


if __name__ == "__main__":
    main()
