#!/usr/bin/python3
"""odocal's batch on drives it did not simulate (figures in docs/tyre-model.md, "On drives
odocal did not simulate"): tools/independent_drive.py writes each case's drive over N seeds,
`odocal calibrate --method batch` calibrates it with its defaults (tyre_model: auto), and each
result is scored against the drive's static circumferences.

Per case and GNSS noise: how many calibrations were usable (exit 0; exit 3 is a refusal; in
brackets how many `odocal doctor` blocked, which are calibrated again with --force and scored as
such, never as usable), the mean |error| of both rear circumferences against those at rest, how
many lie inside 3 reported sigma of what the result claims (a tyre model's circumferences at
rest; the plain model's are those the drive rolled on, its ground distance over its
revolutions), the usable results outside that (a confident wrong answer: the figure that must
stay 0), the mean sigma, the tyre models auto chose, and the whole-log dead reckoning's mean
position error against truth (`odocal deadreckon`) with the calibrated vehicle.yaml and with the
true static circumferences held constant. Run from the repository after `make build`:

    ODOCAL_CLI=build/apps/odocal/odocal /usr/bin/python3 bench/independent_drive_bench.py \\
        --seeds 10 --work /tmp/independent-bench [--cases ideal load ...] [--gnss-sigmas 1 6]
        [--json FILE]
"""
import argparse
import json
import os
import re
import shutil
import subprocess

# The tyre model bench's tallies (this script's directory is on the path when it runs).
from tyre_model_bench import fits_chosen, mean

CLI = os.environ.get("ODOCAL_CLI", "build/apps/odocal/odocal")
SOURCE = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
GENERATOR = os.path.join(SOURCE, "tools", "independent_drive.py")

# Each case: tools/independent_drive.py's options. A slip stiffness of 20 per unit load and 0.4 mm
# of radius per kN are a passenger tyre's, 12 and 0.8 a soft one's; 2e-6 per (m/s)^2 of speed
# growth is 0.125 % at 25 m/s (the Magic Formula grows the free radius by q_V1 (R0 W / V0)^2).
CASES = {
    "ideal": [],
    "load": ["--load-mm-per-kn", "0.4"],
    "soft-load": ["--load-mm-per-kn", "0.8"],
    "slip-rear": ["--drivetrain", "rear", "--slip-stiffness", "20"],
    "soft-slip-load-rear": ["--drivetrain", "rear", "--slip-stiffness", "12",
                            "--load-mm-per-kn", "0.8"],
    "slip-load-front": ["--slip-stiffness", "20", "--load-mm-per-kn", "0.4"],
    "growth-front": ["--speed-growth-s2pm2", "2e-6"],
    "all-front": ["--slip-stiffness", "20", "--load-mm-per-kn", "0.4",
                  "--speed-growth-s2pm2", "2e-6", "--gyro-bias", "0.003"],
    "all-front-doppler": ["--slip-stiffness", "20", "--load-mm-per-kn", "0.4",
                          "--speed-growth-s2pm2", "2e-6", "--gyro-bias", "0.003",
                          "--doppler-sigma", "0.05"],
}


def truth_of(log):
    values = {}
    for line in open(os.path.join(log, "truth.yaml")):
        key, _, value = line.partition(":")
        if key.startswith("circumference_r") or key.startswith("rolled_circumference_r"):
            values[key] = float(value)
    return values


def mean_position_error(log, vehicle, *extra):
    """odocal deadreckon's mean position error against truth.csv with another vehicle.yaml."""
    view = log + "-dr"
    os.makedirs(view, exist_ok=True)
    for name in ("wheels.csv", "gnss.csv", "imu.csv", "truth.csv"):
        if not os.path.exists(os.path.join(view, name)):
            os.symlink(os.path.join(log, name), os.path.join(view, name))
    shutil.copy(vehicle, os.path.join(view, "vehicle.yaml"))
    done = subprocess.run([CLI, "deadreckon", view, *extra], capture_output=True, text=True)
    assert done.returncode == 0, done.stderr
    return float(re.search(r"position\s+mean ([0-9.]+) m", done.stdout).group(1))


def calibrate(log):
    result, vehicle = os.path.join(log, "result.json"), os.path.join(log, "calibrated.yaml")
    command = [CLI, "calibrate", log, "--method", "batch", "--json", result, "--vehicle-out",
               vehicle]
    done = subprocess.run(command, capture_output=True, text=True)
    assert done.returncode in (0, 3), done.stderr
    # A log the doctor blocks (no result written) is counted as blocked and calibrated again
    # with --force, so that what the estimator would have said is scored too.
    blocked = not os.path.exists(result)
    if blocked:
        done = subprocess.run(command + ["--force"], capture_output=True, text=True)
        assert done.returncode in (0, 3), done.stderr
    summary = json.load(open(result))
    truth = truth_of(log)
    wheels = ("circumference_rl_m", "circumference_rr_m")
    chosen = summary.get("tyre_selection", {}).get("chosen", "none")
    # The plain model's circumferences are those the drive rolled on (its report's `rolling`
    # line), a tyre model's those at rest: each is held to what it claims.
    claimed = [truth[("rolled_" if chosen == "none" else "") + w] for w in wheels]
    row = {"usable": done.returncode == 0 and not blocked, "chosen": chosen, "blocked": blocked,
           "errors": [summary[w] - truth[w] for w in wheels],
           "claim_errors": [summary[w] - c for w, c in zip(wheels, claimed)],
           "sigmas": [summary[f"sigma_{w}"] for w in wheels]}
    static = ["--circumference-rl", str(truth[wheels[0]]), "--circumference-rr",
              str(truth[wheels[1]]), "--plain"]
    row["dr_static_m"] = mean_position_error(log, os.path.join(log, "vehicle.yaml"), *static)
    if done.returncode == 0:
        row["dr_calibrated_m"] = mean_position_error(log, vehicle)
    return row


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--seeds", type=int, default=10)
    parser.add_argument("--work", default="/tmp/independent-bench")
    parser.add_argument("--cases", nargs="*", default=list(CASES), choices=list(CASES))
    parser.add_argument("--gnss-sigmas", type=float, nargs="*", default=[1.0, 6.0])
    parser.add_argument("--json", help="write every row here")
    args = parser.parse_args()
    shutil.rmtree(args.work, ignore_errors=True)
    os.makedirs(args.work)
    print("| case | GNSS σ [m] | usable (doctor blocked) | mean \\|error\\| at rest [mm] "
          "| claim inside 3σ "
          "| usable, claim outside 3σ | mean σ [mm] | auto chose | DR mean [m]: calibrated "
          "| true static |")
    print("|---|---|---|---|---|---|---|---|---|---|")
    table = []
    for case in args.cases:
        for gnss_sigma in args.gnss_sigmas:
            rows = []
            for seed in range(1, args.seeds + 1):
                log = os.path.join(args.work, f"{case}-{gnss_sigma:g}-{seed}")
                subprocess.run(["/usr/bin/python3", GENERATOR, log, "--seed", str(seed),
                                "--gnss-sigma", str(gnss_sigma), *CASES[case]], check=True)
                rows.append(calibrate(log))
            pairs = [(e, s) for r in rows for e, s in zip(r["errors"], r["sigmas"])]
            claims = [(e, s) for r in rows for e, s in zip(r["claim_errors"], r["sigmas"])]
            wrong = [r for r in rows if r["usable"] and
                     any(abs(e) > 3 * s for e, s in zip(r["claim_errors"], r["sigmas"]))]
            figures = {"case": case, "gnss_sigma_m": gnss_sigma,
                       "usable": sum(r["usable"] for r in rows), "runs": rows,
                       "mean_abs_error_mm": 1e3 * mean([abs(e) for e, _ in pairs]),
                       "inside_3_sigma": sum(abs(e) <= 3 * s for e, s in claims),
                       "scored": len(pairs), "usable_outside_3_sigma": len(wrong),
                       "mean_sigma_mm": 1e3 * mean([s for _, s in pairs]),
                       "dr_calibrated_m": mean([r["dr_calibrated_m"] for r in rows
                                                if "dr_calibrated_m" in r]),
                       "dr_static_m": mean([r["dr_static_m"] for r in rows])}
            table.append(figures)
            blocked = sum(r["blocked"] for r in rows)
            print(f"| {case} | {gnss_sigma:g} | {figures['usable']}/{len(rows)} ({blocked}) | "
                  f"{figures['mean_abs_error_mm']:.2f} | "
                  f"{figures['inside_3_sigma']}/{figures['scored']} | "
                  f"{figures['usable_outside_3_sigma']} | {figures['mean_sigma_mm']:.2f} | "
                  f"{fits_chosen(rows)} | "
                  f"{figures['dr_calibrated_m']:.1f} | {figures['dr_static_m']:.1f} |",
                  flush=True)
    if args.json:
        json.dump(table, open(args.json, "w"), indent=1)


if __name__ == "__main__":
    main()
