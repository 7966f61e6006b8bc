"""The paper's figures drawn from the CSV/JSON that `odocal experiment paper` writes.

Each function reads one piece's directory and writes one PNG; tools/paper_report.py calls them.
"""

import csv
import json

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

METHODS = ("iterative", "fixed-p", "augmented", "batch")
COLOURS = {"iterative": "tab:blue", "fixed-p": "tab:orange", "augmented": "tab:green",
           "batch": "tab:purple"}


def read_csv(path):
    with open(path, newline="") as f:
        return list(csv.DictReader(f))


def read_json(path):
    with open(path) as f:
        return json.load(f)


def column(rows, name, where=None):
    return [float(r[name]) for r in rows if where is None or where(r)]


def save(fig, path):
    fig.tight_layout()
    fig.savefig(path, dpi=100)
    plt.close(fig)


def wear_paths(table_dir, wear_rows, title, out):
    """Fig. 2: the true garage path and the dead-reckoned ones for each wear pair."""
    rows = read_csv(f"{table_dir}/paths.csv")
    fig, ax = plt.subplots(figsize=(7, 6))
    truth = [r for r in rows if r["case"] == "-1"]
    ax.plot(column(truth, "x_m"), column(truth, "y_m"), "k-", lw=2.5, label="truth")
    for index, wear in enumerate(wear_rows):
        case = [r for r in rows if r["case"] == str(index)]
        label = f"RL {float(wear['wear_rl_mm']):g} / RR {float(wear['wear_rr_mm']):g} mm"
        ax.plot(column(case, "x_m"), column(case, "y_m"), lw=1, label=label)
    ax.set_aspect("equal")
    ax.set_xlabel("x [m]")
    ax.set_ylabel("y [m]")
    ax.set_title(title)
    ax.grid(alpha=0.3)
    ax.legend(fontsize=8)
    save(fig, out)


def speed_profile(single_dir, title, out):
    """Fig. 4."""
    rows = read_csv(f"{single_dir}/speed.csv")
    fig, ax = plt.subplots(figsize=(8, 3))
    ax.plot(column(rows, "t_s"), [3.6 * v for v in column(rows, "speed_mps")], lw=0.8)
    ax.set_xlabel("time [s]")
    ax.set_ylabel("speed [km/h]")
    ax.set_title(title)
    ax.grid(alpha=0.3)
    save(fig, out)


def track_path(single_dir, title, out):
    """Fig. 5: the true path and a 1 Hz subset of the GNSS fixes."""
    path = read_csv(f"{single_dir}/path.csv")
    gnss = read_csv(f"{single_dir}/gnss.csv")
    fig, ax = plt.subplots(figsize=(7, 5))
    ax.plot(column(gnss, "x_m"), column(gnss, "y_m"), ".", ms=2, color="tab:gray",
            label="GNSS (1 Hz shown)")
    ax.plot(column(path, "x_m"), column(path, "y_m"), lw=1, label="truth")
    ax.set_aspect("equal")
    ax.set_xlabel("x [m]")
    ax.set_ylabel("y [m]")
    ax.set_title(title)
    ax.grid(alpha=0.3)
    ax.legend()
    save(fig, out)


def iteration_errors(single_dir, title, out):
    """Fig. 6: mean dead-reckoning errors per iteration; the stop rule's choice dashed red."""
    rows = read_csv(f"{single_dir}/iterations.csv")
    summary = read_json(f"{single_dir}/summary.json")
    fig, (top, bottom) = plt.subplots(2, 1, figsize=(8, 5), sharex=True)
    for method in ("iterative", "fixed-p"):
        mine = lambda r, m=method: r["method"] == m  # noqa: E731
        it = column(rows, "iteration", mine)
        style = "-o" if method == "iterative" else "--s"
        top.plot(it, column(rows, "mean_position_m", mine), style, ms=3, label=method,
                 color=COLOURS[method])
        bottom.plot(it, column(rows, "mean_heading_deg", mine), style, ms=3, label=method,
                    color=COLOURS[method])
    chosen = summary["chosen_iteration"]["iterative"]
    for ax in (top, bottom):
        ax.axvline(chosen, color="red", ls="--", lw=1, label="stop (iterative)")
        ax.grid(alpha=0.3)
    top.set_ylabel("mean position error [m]")
    bottom.set_ylabel("mean heading error [deg]")
    for ax in (top, bottom):  # fixed-P starts orders of magnitude above the iterative method
        ax.set_yscale("log")
    bottom.set_xlabel("iteration")
    top.set_title(title)
    top.legend(fontsize=8)
    save(fig, out)


def iteration_circumferences(single_dir, title, out):
    """Fig. 7: c_RL and c_RR per iteration of the iterative method against the truth."""
    rows = read_csv(f"{single_dir}/iterations.csv")
    summary = read_json(f"{single_dir}/summary.json")
    mine = lambda r: r["method"] == "iterative"  # noqa: E731
    it = column(rows, "iteration", mine)
    fig, ax = plt.subplots(figsize=(8, 3.5))
    for wheel, colour in (("rl", "tab:blue"), ("rr", "tab:red")):
        ax.plot(it, [1e3 * c for c in column(rows, f"c_{wheel}_m", mine)], "-o", ms=3,
                color=colour, label=f"c_{wheel.upper()} estimate")
        ax.axhline(1e3 * summary[f"true_circumference_{wheel}_m"], color=colour, ls=":",
                   label=f"c_{wheel.upper()} true")
    ax.axvline(summary["chosen_iteration"]["iterative"], color="red", ls="--", lw=1, label="stop")
    ax.set_xlabel("iteration")
    ax.set_ylabel("circumference [mm]")
    ax.set_title(title)
    ax.grid(alpha=0.3)
    ax.legend(fontsize=8, ncol=2)
    save(fig, out)


def augmented_series(single_dir, title, out):
    """Fig. 12: the augmented KF's circumference estimates over time."""
    rows = read_csv(f"{single_dir}/augmented.csv")
    summary = read_json(f"{single_dir}/summary.json")
    t = column(rows, "t_s")
    fig, ax = plt.subplots(figsize=(8, 3.5))
    for wheel, colour in (("rl", "tab:blue"), ("rr", "tab:red")):
        ax.plot(t, [1e3 * c for c in column(rows, f"c_{wheel}_m")], lw=0.8, color=colour,
                label=f"c_{wheel.upper()} augmented KF")
        ax.axhline(1e3 * summary[f"true_circumference_{wheel}_m"], color=colour, ls=":",
                   label=f"c_{wheel.upper()} true")
    truth = [1e3 * summary[f"true_circumference_{w}_m"] for w in ("rl", "rr")]
    ax.set_ylim(min(truth) - 8, max(truth) + 8)
    ax.set_xlabel("time [s]")
    ax.set_ylabel("circumference [mm]")
    ax.set_title(title)
    ax.grid(alpha=0.3)
    ax.legend(fontsize=8, ncol=2)
    save(fig, out)


def seed_bars(seeds, values_of, methods, ylabel, title, floor, out):
    """Grouped bars per seed and method (Figs. 8-11)."""
    fig, ax = plt.subplots(figsize=(9, 3.5))
    width = 0.8 / len(methods)
    positions = range(len(seeds))
    for i, method in enumerate(methods):
        ax.bar([p + (i - (len(methods) - 1) / 2) * width for p in positions],
               [values_of(s, method) for s in seeds], width, label=method, color=COLOURS[method])
    if floor is not None:
        ax.plot(list(positions), floor, "k_", ms=14, mew=2, label="Cramér–Rao σ")
    ax.set_xticks(list(positions))
    ax.set_xticklabels([str(s["seed"]) for s in seeds])
    ax.set_xlabel("noise seed")
    ax.set_ylabel(ylabel)
    ax.set_title(title)
    ax.grid(alpha=0.3, axis="y")
    ax.legend(fontsize=8)
    save(fig, out)


def mean_abs_error(seed, method):
    run = seed["methods"][method]
    return 0.5 * (abs(run["error_rl_mm"]) + abs(run["error_rr_mm"]))


def crlb_floor(seeds):
    return [(0.5 * (s["crlb_sigma_rl_mm"] ** 2 + s["crlb_sigma_rr_mm"] ** 2)) ** 0.5
            for s in seeds]
