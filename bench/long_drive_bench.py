#!/usr/bin/python3
"""Long-drive benchmark (issue 21; figures in docs/batch-calibration.md, "Memory and time"):
time and peak memory of `odocal calibrate` (batch and iterative) against the log's length. Logs:
the ideal circuit at 50 Hz over 1, 3, 10, 30 and 100 laps, and the urban scenario with every
sensor at 100 Hz for 10 hours. Each command runs under /usr/bin/time. The loaded log is what
`calibrate` holds of it: 8 bytes per value of every stream but truth.csv (which it does not
read); what a calibration needs beyond it is its peak resident memory less that, per wheel
sample (an upper bound: the program and its libraries are in it too). Run from the repository
after `make build` (the 10-hour log takes a few minutes to simulate and ~600 MB):

    ODOCAL_CLI=build/apps/odocal/odocal /usr/bin/python3 bench/long_drive_bench.py \\
        --work /tmp/long-drive [--laps 1 3 10 30 100] [--urban-hours 10] [--doppler-sigma 0.05]
"""
import argparse
import json
import os
import re
import subprocess

CLI = os.environ.get("ODOCAL_CLI", "build/apps/odocal/odocal")
SOURCE = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))


def measured(*args):
    """Seconds and peak resident MiB of one odocal command: its exit status must be 0, or 3 (a
    result it refuses, whose JSON is still written)."""
    result = subprocess.run(["/usr/bin/time", "-f", "%e %M", CLI, *args],
                            capture_output=True, text=True)
    if result.returncode not in (0, 3):
        raise SystemExit(f"odocal {' '.join(args)} failed:\n{result.stderr}")
    seconds, kilobytes = result.stderr.strip().splitlines()[-1].split()
    return float(seconds), float(kilobytes) / 1024.0


def simulate(log, *args):
    if not os.path.exists(os.path.join(log, "truth.yaml")):
        subprocess.run([CLI, "simulate", "--out", log, *args], check=True,
                       stdout=subprocess.DEVNULL)


def rows_and_columns(path):
    with open(path) as f:
        columns = len(f.readline().split(","))
        return sum(1 for _ in f), columns


def loaded_log_mib(log):
    values = 0
    for name in ("wheels.csv", "gnss.csv", "imu.csv", "heading.csv"):
        if os.path.exists(os.path.join(log, name)):
            rows, columns = rows_and_columns(os.path.join(log, name))
            values += rows * columns
    return 8.0 * values / (1024.0 * 1024.0)


def urban_scenario(work, hours):
    """The built-in urban drive with every sensor at 100 Hz, repeated to `hours`."""
    base = os.path.join(work, "urban-1")
    simulate(base, "--scenario", "urban", "--laps", "1")
    text = open(os.path.join(base, "scenario.yaml")).read()  # every setting, written out
    text, count = re.subn(r"rate_hz: 50\b", "rate_hz: 100", text)
    assert count >= 4, "scenario.yaml no longer states every sensor's rate"
    path = os.path.join(work, "urban-100hz.yaml")
    open(path, "w").write(text)
    truth = open(os.path.join(base, "truth.yaml")).read()
    lap_s = float(re.search(r"duration_s: ([0-9.]+)", truth)[1])
    return path, max(1, round(hours * 3600.0 / lap_s))


def row(name, log):
    samples = rows_and_columns(os.path.join(log, "wheels.csv"))[0]
    log_mib = loaded_log_mib(log)
    figures = {"log": name, "wheel_samples": samples, "loaded_log_mib": log_mib}
    for method in ("batch", "iterative"):
        seconds, mb = measured("calibrate", log, "--method", method, "--json",
                               os.path.join(log, f"{method}.json"))
        figures[f"{method}_s"] = seconds
        figures[f"{method}_mb"] = mb
        figures[f"{method}_bytes_per_sample"] = (mb - log_mib) * 1024.0 * 1024.0 / samples
        result = json.load(open(os.path.join(log, f"{method}.json")))
        figures[f"{method}_sigma_rl_mm"] = 1e3 * result["sigma_circumference_rl_m"]
        figures[f"{method}_usable"] = result["usable"]
        figures[f"{method}_termination"] = result["termination"]
        figures[f"{method}_tyre_model"] = result.get("tyre_selection", {}).get("chosen", "")

    def outcome(method):
        chosen = figures[f"{method}_tyre_model"]
        model = f"{'plain' if chosen == 'none' else chosen}, " if chosen else ""
        usable = "usable" if figures[f"{method}_usable"] else figures[f"{method}_termination"]
        return model + usable

    print(f"| {name} | {samples} | {log_mib:.0f} MiB | {figures['batch_s']:.2f} s | "
          f"{figures['batch_mb']:.0f} MiB | {figures['batch_bytes_per_sample']:.0f} | "
          f"{outcome('batch')} | {figures['iterative_s']:.2f} s | "
          f"{figures['iterative_mb']:.0f} MiB | {figures['iterative_bytes_per_sample']:.0f} |",
          flush=True)
    return figures


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--work", required=True)
    parser.add_argument("--laps", type=int, nargs="*", default=[1, 3, 10, 30, 100])
    parser.add_argument("--urban-hours", type=float, default=10.0)
    parser.add_argument("--doppler-sigma", type=float, default=0.0,
                        help="give the urban drive a Doppler speed column with this noise, m/s "
                             "(0: none)")
    parser.add_argument("--json")
    args = parser.parse_args()
    os.makedirs(args.work, exist_ok=True)
    print("| log | wheel samples | loaded log | batch: time | peak | beyond the log, B/sample | "
          "batch: model, outcome | iterative: time | peak | beyond the log, B/sample |")
    print("|---|---|---|---|---|---|---|---|---|---|")
    rows = []
    for laps in args.laps:
        log = os.path.join(args.work, f"circuit-{laps}")
        simulate(log, "--ideal", "--laps", str(laps))
        rows.append(row(f"circuit, ideal, 50 Hz, {laps} laps", log))
    if args.urban_hours > 0:
        scenario, laps = urban_scenario(args.work, args.urban_hours)
        doppler = ["--gnss-speed-sigma", str(args.doppler_sigma)] if args.doppler_sigma else []
        suffix = f"-doppler-{args.doppler_sigma:g}" if doppler else ""
        log = os.path.join(args.work, f"urban-100hz-{laps}{suffix}")
        simulate(log, "--scenario", scenario, "--laps", str(laps), *doppler)
        name = f"urban, 100 Hz, {args.urban_hours:g} h ({laps} laps)"
        if doppler:
            name += f", Doppler {args.doppler_sigma:g} m/s"
        rows.append(row(name, log))
    if args.json:
        json.dump(rows, open(args.json, "w"), indent=1)


if __name__ == "__main__":
    main()
