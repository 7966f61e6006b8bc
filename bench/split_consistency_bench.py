#!/usr/bin/python3
"""Split-sample consistency of the batch's circumferences (docs/batch-calibration.md, "Not seen
yet"): does a log's own scatter show a GNSS error that its residuals hide?

Each simulated log is calibrated whole and in K consecutive parts of equal duration (`calibrate
--from/--to`, the same configuration). Per rear wheel, the parts' scatter about the whole log's
estimate against their own sigmas is the Birge ratio R = sqrt(sum((c_k - c)^2 / s_k^2) / (K - 1)):
about 1 where the reported sigmas are right and the parts independent, larger where an error
common to a part's fixes (a receiver's wander) moves each part's estimate further than its sigma
says. Printed per seed and wheel: the whole log's error against truth.yaml, its sigma, the error in
sigmas (z), R, and z with the sigma widened by R where R > 1. Run from the repository after
`make build`:

    ODOCAL_CLI=build/apps/odocal/odocal /usr/bin/python3 bench/split_consistency_bench.py \\
        --seeds 10 --drive urban --ideal [--gnss-gauss-markov SIGMA_M TAU_S] [--parts 4] \\
        [--model none] [--drivetrain rear] [--json FILE]
"""
import argparse
import json
import math
import os
import shutil
import subprocess

from tyre_model_bench import scenario_file, truth_of

CLI = os.environ.get("ODOCAL_CLI", "build/apps/odocal/odocal")
WHEELS = ("circumference_rl_m", "circumference_rr_m")


def run(*args):
    return subprocess.run([CLI, *args], capture_output=True, text=True)


def calibrate(log, config, out, span=None):
    """Each rear circumference and its sigma, or None where no result was written."""
    window = ["--from", repr(span[0]), "--to", repr(span[1])] if span else []
    run("calibrate", log, "--method", "batch", "--config", config, "--json", out, *window)
    if not os.path.exists(out):
        return None
    summary = json.load(open(out))
    sigma = {p["name"]: p.get("sigma") for p in summary["parameters"]}
    return [(summary[w], sigma[w]) for w in WHEELS]


def time_span(log):
    times = [float(line.split(",", 1)[0]) for line in open(os.path.join(log, "wheels.csv"))
             if line[:1].isdigit() or line[:1] == "-"]
    return times[0], times[-1]


def birge_ratio(whole, parts):
    terms = [((c - whole) / s) ** 2 for c, s in parts if s and math.isfinite(s) and s > 0.0]
    return math.sqrt(sum(terms) / (len(terms) - 1)) if len(terms) > 1 else float("nan")


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--seeds", type=int, default=10)
    parser.add_argument("--work", default="/tmp/split-consistency")
    parser.add_argument("--drive", default="urban", choices=["urban", "circuit"])
    parser.add_argument("--drivetrain", default="rear", choices=["rear", "front"])
    parser.add_argument("--ideal", action="store_true", help="kinematic motion, constant radius")
    parser.add_argument("--gnss-gauss-markov", type=float, nargs=2, metavar=("SIGMA_M", "TAU_S"))
    parser.add_argument("--parts", type=int, default=4)
    parser.add_argument("--model", default="none", help="tyre_model of every fit")
    # No refusal for a part's sigma: the parts are short, and their sigma is what is compared.
    parser.add_argument("--max-sigma-m", type=float, default=0.05)
    parser.add_argument("--json", help="write every row here")
    args = parser.parse_args()
    if args.parts < 2:
        parser.error("--parts takes 2 or more")
    shutil.rmtree(args.work, ignore_errors=True)
    os.makedirs(args.work)
    scenario = scenario_file(args.work, args.drive, args.drivetrain, "scenario", None,
                             gnss_gauss_markov=args.gnss_gauss_markov, ideal=args.ideal)
    config = os.path.join(args.work, "calibrate.yaml")
    open(config, "w").write(f"batch:\n  tyre_model: {args.model}\n"
                            f"  max_sigma_circumference_m: {args.max_sigma_m}\n")
    print("| seed | wheel | error [mm] | σ [mm] | z | R | z with σ × max(1, R) | parts' σ [mm] |")
    print("|---|---|---|---|---|---|---|---|")
    rows = []
    for seed in range(1, args.seeds + 1):
        log = os.path.join(args.work, f"seed-{seed}")
        made = run("simulate", "--scenario", scenario, "--out", log, "--seed", str(seed),
                   "--trajectory-seed", str(seed))
        assert made.returncode == 0, made.stderr
        truth = truth_of(log)
        whole = calibrate(log, config, os.path.join(log, "whole.json"))
        begin, end = time_span(log)
        step = (end - begin) / args.parts
        parts = [calibrate(log, config, os.path.join(log, f"part-{k}.json"),
                           (begin + k * step, begin + (k + 1) * step))
                 for k in range(args.parts)]
        for w, wheel in enumerate(WHEELS):
            value, sigma = whole[w]
            part_estimates = [p[w] for p in parts if p]
            ratio = birge_ratio(value, part_estimates)
            error = value - truth[wheel]
            row = {"seed": seed, "wheel": wheel, "error_mm": 1e3 * error,
                   "sigma_mm": 1e3 * sigma, "z": error / sigma, "birge_ratio": ratio,
                   "z_widened": error / (sigma * max(1.0, ratio)),
                   "part_sigmas_mm": [1e3 * s for _, s in part_estimates]}
            rows.append(row)
            print(f"| {seed} | {wheel[-4:-2].upper()} | {row['error_mm']:+.2f} | "
                  f"{row['sigma_mm']:.2f} | {row['z']:+.1f} | {ratio:.2f} | "
                  f"{row['z_widened']:+.1f} | "
                  f"{' '.join(f'{s:.1f}' for s in row['part_sigmas_mm'])} |", flush=True)
    ratios = [r["birge_ratio"] for r in rows if math.isfinite(r["birge_ratio"])]
    print(f"\nR from {min(ratios):.2f} to {max(ratios):.2f}; beyond 3σ: "
          f"{sum(abs(r['z']) > 3 for r in rows)} of {len(rows)}, with σ widened by R: "
          f"{sum(abs(r['z_widened']) > 3 for r in rows)}")
    if args.json:
        json.dump(rows, open(args.json, "w"), indent=1)


if __name__ == "__main__":
    main()
