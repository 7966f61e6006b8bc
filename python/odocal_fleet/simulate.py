"""odocal-fleet simulate: a fleet of simulated vehicles whose rear tyres wear, get changed or
rotated and lose pressure at known times, each drive an odocal log in VEHICLE/DRIVE/ with its
vehicle_id and drive.yaml (start time, odometer), and the truth beside them in
fleet_truth.json (docs/fleet.md#simulate)."""
import datetime
import json
import os
import subprocess
import sys
import tempfile
from concurrent.futures import ProcessPoolExecutor

import numpy as np

EVENT_KINDS = ("tyre change", "rotation", "pressure loss")


def odocal_cli():
    """The odocal command beside this package (installed or in a build tree), else on PATH."""
    if os.environ.get("ODOCAL_CLI"):
        return os.environ["ODOCAL_CLI"]
    here = os.path.dirname(os.path.abspath(__file__))
    for candidate in (os.path.join(here, "..", "..", "..", "bin", "odocal"),
                      os.path.join(here, "..", "..", "apps", "odocal", "odocal")):
        if os.access(candidate, os.X_OK):
            return os.path.abspath(candidate)
    return "odocal"


def plan_vehicle(index, args):
    """One vehicle's drives: tyre state per drive and its events, all from the seed."""
    rng = np.random.default_rng([args.seed, index])
    vehicle = f"car-{index:03d}"
    wear = {"rl": rng.uniform(0.0, 2.0), "rr": rng.uniform(0.0, 2.0)}  # mm of radius
    wear_per_km = {w: 1.0 / rng.uniform(10_000.0, 40_000.0) for w in ("rl", "rr")}
    pressure = {"rl": 1.0, "rr": 1.0}
    odometer_km = rng.uniform(5_000.0, 50_000.0)
    start = datetime.datetime(2026, 1, 5, 7, 0, tzinfo=datetime.timezone.utc)
    event = None
    if rng.uniform() < args.event_share and args.drives >= 6:
        event = {"kind": EVENT_KINDS[int(rng.integers(len(EVENT_KINDS)))],
                 "wheel": ("rl", "rr")[int(rng.integers(2))],
                 "drive_index": int(rng.integers(args.drives // 3, args.drives - 2))}
    drives = []
    for d in range(args.drives):
        if event and d == event["drive_index"]:
            wheel = event["wheel"]
            before = dict(wear)
            if event["kind"] == "tyre change":  # a fresher tyre replaces a worn one
                wear[wheel] -= args.step_mm
            elif event["kind"] == "rotation":
                wear["rl"], wear["rr"] = wear["rr"], wear["rl"]
                event["wheel"] = "both"
            else:
                pressure[wheel] = args.pressure
            event.update(odometer_km=odometer_km, start_time=start.isoformat(),
                         wear_before_mm=before, wear_after_mm=dict(wear), pressure=dict(pressure))
        drives.append({"name": f"drive-{d:03d}", "seed": args.seed * 1_000_003 + index * 1000 + d,
                       "wear_mm": dict(wear), "pressure": dict(pressure),
                       "odometer_km": odometer_km, "start_time": start.isoformat()})
        # The next drive starts after this one and some driving that was not logged.
        odometer_km += args.laps * args.lap_km + rng.uniform(0.0, args.gap_km)
        for w in wear:
            wear[w] += wear_per_km[w] * (args.laps * args.lap_km)
        start += datetime.timedelta(hours=float(rng.uniform(3.0, 21.0)))
    return {"vehicle_id": vehicle, "wear_rate_mm_per_10000_km": {w: 1e4 * r for w, r in wear_per_km.items()},
            "event": event, "drives": drives}


def simulate_drive(args_tuple):
    cli, out, vehicle, drive, scenario, laps, ideal, doppler_sigma = args_tuple
    command = [cli, "simulate", "--scenario", scenario, "--laps", str(laps), "--out", out,
               "--seed", str(drive["seed"]), "--trajectory-seed", str(drive["seed"]),
               "--vehicle-id", vehicle,
               "--wear-rl", f"{drive['wear_mm']['rl']:.6f}", "--wear-rr", f"{drive['wear_mm']['rr']:.6f}",
               "--pressure-rl", f"{drive['pressure']['rl']:.4f}",
               "--pressure-rr", f"{drive['pressure']['rr']:.4f}"] + (["--ideal"] if ideal else [])
    if doppler_sigma is not None:
        command += ["--gnss-speed-sigma", f"{doppler_sigma:g}"]
    done = subprocess.run(command, capture_output=True, text=True)
    if done.returncode != 0:
        raise RuntimeError(f"{' '.join(command)}: {done.stderr.strip()}")
    with open(os.path.join(out, "drive.yaml"), "w") as f:
        f.write(f"start_time: {drive['start_time']}\nodometer_km: {drive['odometer_km']:.3f}\n")
    truth = {}
    with open(os.path.join(out, "truth.yaml")) as f:
        for line in f:
            if ":" in line and not line.startswith("#"):
                key, value = line.split(":", 1)
                truth[key.strip()] = value.strip()
    return {"circumference_rl_m": float(truth["circumference_rl_m"]),
            "circumference_rr_m": float(truth["circumference_rr_m"]),
            "distance_m": float(truth["distance_m"]), "duration_s": float(truth["duration_s"])}


def lap_km(cli, scenario, ideal):
    """The scenario's lap length, from one simulated lap (odometers advance by it)."""
    with tempfile.TemporaryDirectory() as scratch:
        out = os.path.join(scratch, "lap")
        done = subprocess.run([cli, "simulate", "--scenario", scenario, "--laps", "1", "--out", out]
                              + (["--ideal"] if ideal else []), capture_output=True, text=True)
        if done.returncode != 0:
            raise SystemExit(f"odocal-fleet: error: {done.stderr.strip()}")
        with open(os.path.join(out, "truth.yaml")) as f:
            for line in f:
                if line.startswith("distance_m:"):
                    return float(line.split(":")[1]) / 1000.0
    raise SystemExit("odocal-fleet: error: the simulator wrote no distance")


def simulate(args):
    if os.path.exists(args.out) and os.listdir(args.out):
        print(f"odocal-fleet: error: {args.out}: exists and is not empty", file=sys.stderr)
        return 2
    cli = odocal_cli()
    args.lap_km = lap_km(cli, args.scenario, args.ideal)
    plans = [plan_vehicle(v, args) for v in range(args.vehicles)]
    # A receiver's Doppler speed, as automotive receivers report it: without it, the tyre model
    # cannot tell a driven rear wheel's slip from its circumference (docs/fleet.md, "odocal-fleet
    # simulate").
    doppler = None if args.no_doppler else args.doppler_sigma
    jobs = [(cli, os.path.join(args.out, p["vehicle_id"], d["name"]), p["vehicle_id"], d,
             args.scenario, args.laps, args.ideal, doppler) for p in plans for d in p["drives"]]
    with ProcessPoolExecutor(max_workers=max(args.workers, 1)) as pool:
        truths = list(pool.map(simulate_drive, jobs, chunksize=4))
    it = iter(truths)
    for plan in plans:
        for drive in plan["drives"]:
            drive.update(next(it))
    truth = {"scenario": args.scenario, "laps": args.laps, "ideal": args.ideal, "seed": args.seed,
             "doppler_sigma_mps": doppler,
             "vehicles": plans}
    with open(os.path.join(args.out, "fleet_truth.json"), "w") as f:
        json.dump(truth, f, indent=1)
    events = sum(p["event"] is not None for p in plans)
    print(f"odocal-fleet: {args.vehicles} vehicles x {args.drives} drives in {args.out} "
          f"({events} with an event; the truth in fleet_truth.json)")
    return 0
