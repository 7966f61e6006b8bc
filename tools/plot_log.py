#!/usr/bin/python3
"""Plots a log's true path and speed profile (the paper's Figs. 5 and 4) from truth.csv.

Usage: tools/plot_log.py LOG_DIR OUT_PREFIX [--title TEXT]
Writes OUT_PREFIX-path.png and OUT_PREFIX-speed.png. Needs Debian's python3-matplotlib.
"""

import argparse
import csv
import math

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402


def read_truth(log_dir):
    with open(f"{log_dir}/truth.csv", newline="") as f:
        rows = [(float(r["t"]), float(r["x"]), float(r["y"])) for r in csv.DictReader(f)]
    return [r[0] for r in rows], [r[1] for r in rows], [r[2] for r in rows]


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("log_dir")
    parser.add_argument("out_prefix")
    parser.add_argument("--title", default="")
    args = parser.parse_args()
    t, x, y = read_truth(args.log_dir)

    fig, ax = plt.subplots(figsize=(7, 5))
    ax.plot(x, y, lw=1)
    ax.plot(x[0], y[0], "go", label="start")
    ax.set_aspect("equal")
    ax.set_xlabel("x east [m]")
    ax.set_ylabel("y north [m]")
    ax.set_title(f"{args.title} path")
    ax.legend()
    ax.grid(alpha=0.3)
    fig.tight_layout()
    fig.savefig(f"{args.out_prefix}-path.png", dpi=110)

    speed_kmh = [0.0] + [math.hypot(x[k] - x[k - 1], y[k] - y[k - 1]) / (t[k] - t[k - 1]) * 3.6
                         for k in range(1, len(t))]
    fig, ax = plt.subplots(figsize=(7, 3.2))
    ax.plot(t, speed_kmh, lw=0.8)
    ax.set_xlabel("time [s]")
    ax.set_ylabel("speed [km/h]")
    ax.set_title(f"{args.title} speed profile")
    ax.grid(alpha=0.3)
    fig.tight_layout()
    fig.savefig(f"{args.out_prefix}-speed.png", dpi=110)


if __name__ == "__main__":
    main()
