"""odocal-fleet report: the fleet as static HTML pages (docs/fleet.md#report): index.html with a
row per vehicle, and per vehicle its rear circumferences over the odometer (each drive's
estimate with its sigma, the smoothed line with its band, events marked), wear and events.
Plotly from Debian's python3-plotly: its script is written once beside the pages and loaded from
there, so that the pages work offline and a fleet of thousands does not carry it thousands of
times. The directory is written whole or not at all."""
import html
import os
import shutil
import sqlite3
import sys
import tempfile

import plotly.graph_objects as go
import plotly.io
import plotly.offline

from . import health, health_command

STYLE = """body { font-family: sans-serif; margin: 2em; color: #222; }
table { border-collapse: collapse; margin: 1em 0; }
td, th { border: 1px solid #ccc; padding: 0.3em 0.6em; text-align: left; vertical-align: top; }
th { background: #f2f2f2; }
.plot { margin: 1.5em 0; }
.event { color: #b00; font-weight: bold; }"""

COLOURS = {"rl": "#1f77b4", "rr": "#ff7f0e"}


def table(rows, header):
    head = "".join(f"<th>{html.escape(str(h))}</th>" for h in header)
    body = "".join("<tr>" + "".join(f"<td>{c}</td>" for c in row) + "</tr>" for row in rows)
    return f"<table><thead><tr>{head}</tr></thead><tbody>{body}</tbody></table>"


def page(title, body):
    return f"""<!DOCTYPE html>
<html lang="en"><head><meta charset="utf-8"><title>{html.escape(title)}</title>
<script type="text/javascript" src="plotly.min.js"></script>
<style>{STYLE}</style></head><body>
<h1>{html.escape(title)}</h1>
{body}
</body></html>
"""


def circumference_figure(vehicle):
    fig = go.Figure()
    for wheel, w in vehicle["wheels"].items():
        colour = COLOURS[wheel]
        km = w["odometer_km"]
        upper = [1e3 * (c + 2 * s) for c, s in zip(w["circumference_m"], w["sigma_m"])]
        lower = [1e3 * (c - 2 * s) for c, s in zip(w["circumference_m"], w["sigma_m"])]
        fig.add_trace(go.Scatter(x=km + km[::-1], y=upper + lower[::-1], fill="toself",
                                 fillcolor=colour, opacity=0.2, line={"width": 0}, mode="lines",
                                 name=f"{wheel.upper()} smoothed, 2-sigma band", hoverinfo="skip"))
        fig.add_trace(go.Scatter(x=km, y=[1e3 * c for c in w["circumference_m"]], mode="lines",
                                 line={"color": colour}, name=f"{wheel.upper()} smoothed"))
        fig.add_trace(go.Scatter(
            x=km, y=[1e3 * c for c in w["measured_m"]], mode="markers",
            marker={"color": colour, "size": 6}, name=f"{wheel.upper()} drives",
            error_y={"type": "data", "array": [1e3 * s for s in w["measured_sigma_m"]],
                     "visible": True}, text=w["start_time"]))
    for event in vehicle["events"]:
        fig.add_vline(x=event["odometer_km"], line_dash="dash", line_color="#b00",
                      annotation_text=f"{event['kind']} {event['wheel'].upper()}")
    fig.update_layout(title="Rear circumferences over the odometer",
                      xaxis_title="odometer [km]", yaxis_title="circumference [mm]", height=550)
    return fig


def vehicle_page(vehicle):
    rows = []
    for wheel, w in vehicle["wheels"].items():
        rows.append((wheel.upper(), f"{w['circumference_m'][-1]:.6f} m",
                     f"{1e3 * w['sigma_m'][-1]:.3f} mm",
                     f"{w['wear_mm_radius_per_10000_km']:.2f} ± "
                     f"{w['wear_sigma_mm_radius_per_10000_km']:.2f}", f"x{w['sigma_scale']:.2f}"))
    events = [(f'<span class="event">{html.escape(e["kind"])}</span>', e["wheel"].upper(),
               f"{e['odometer_km']:.1f}", html.escape(e["start_time"] or ""),
               f"{e['step_mm']:+.2f} ± {e['sigma_mm']:.2f}",
               html.escape(os.path.basename(e["detected_after_drive"])))
              for e in vehicle["events"]]
    plot = plotly.io.to_html(circumference_figure(vehicle), full_html=False, include_plotlyjs=False)
    body = (f'<p><a href="index.html">fleet</a> · {vehicle["drives"]} usable drives</p>'
            "<h2>Rear tyres now</h2>"
            + table(rows, ("wheel", "circumference", "1-sigma", "wear [mm radius / 10 000 km]",
                           "drive sigmas"))
            + "<h2>Events</h2>"
            + (table(events, ("event", "wheel", "odometer [km]", "first drive after", "step [mm]",
                              "found after")) if events else "<p>None.</p>")
            + f'<h2>Over the odometer</h2><div class="plot">{plot}</div>')
    return page(f"odocal fleet: {vehicle['vehicle_id']}", body)


def file_name(vehicle_id):
    """vehicle.yaml's ids are letters, digits, . _ -; a directory name may hold anything."""
    safe = "".join(ch if ch.isascii() and (ch.isalnum() or ch in "._-") else "_" for ch in vehicle_id)
    return f"vehicle-{safe[:100]}.html"


def index_page(report, failures):
    rows = []
    for v in report["vehicles"]:
        w = v["wheels"]
        kinds = ", ".join(sorted({f"{e['kind']} {e['wheel'].upper()}" for e in v["events"]}))
        rows.append((f'<a href="{html.escape(file_name(v["vehicle_id"]))}">{html.escape(v["vehicle_id"])}</a>',
                     v["drives"],
                     *(f"{w[k]['circumference_m'][-1]:.6f} ± {1e3 * w[k]['sigma_m'][-1]:.2f} mm"
                       for k in ("rl", "rr")),
                     *(f"{w[k]['wear_mm_radius_per_10000_km']:.2f}" for k in ("rl", "rr")),
                     f'<span class="event">{html.escape(kinds)}</span>' if kinds else ""))
    fig = go.Figure(go.Histogram(
        x=[1e3 * (v["wheels"]["rl"]["circumference_m"][-1] - v["wheels"]["rr"]["circumference_m"][-1])
           for v in report["vehicles"]], nbinsx=30))
    fig.update_layout(title="Left minus right rear circumference now, per vehicle",
                      xaxis_title="c_RL - c_RR [mm]", yaxis_title="vehicles", height=400)
    failure_rows = [(html.escape(f[0]), html.escape(f[1]), html.escape(f[2]), f[3])
                    for f in failures]
    body = (f"<p>{len(report['vehicles'])} vehicles, {report['method']} calibrations; events at a "
            f"false-alarm rate of {report['false_alarm_rate']:.1%} per vehicle over "
            f"{report['design_drives']} drives.</p>"
            + table(rows, ("vehicle", "drives", "c_RL now", "c_RR now",
                           "RL wear [mm radius / 10 000 km]", "RR wear", "events"))
            + f'<div class="plot">{plotly.io.to_html(fig, full_html=False, include_plotlyjs=False)}</div>'
            + "<h2>Drives that failed</h2>"
            + (table(failure_rows, ("vehicle", "drive", "error", "attempts")) if failures
               else "<p>None.</p>"))
    return page("odocal fleet", body)


def write_directory(out, files):
    """All files into a directory beside `out`, then renamed into place (an old report moved
    aside first and removed after)."""
    parent = os.path.dirname(os.path.abspath(out)) or "."
    stage = tempfile.mkdtemp(prefix=".odocal-report-", dir=parent)
    try:
        for name, text in files.items():
            with open(os.path.join(stage, name), "w") as f:
                f.write(text)
        os.chmod(stage, 0o755)
        old = None
        if os.path.exists(out):
            old = tempfile.mkdtemp(prefix=".odocal-report-old-", dir=parent)
            os.rename(out, os.path.join(old, "report"))
        os.rename(stage, out)
        if old:
            shutil.rmtree(old)
    except BaseException:
        shutil.rmtree(stage, ignore_errors=True)
        raise


def run(args):
    if os.path.exists(args.out) and not os.path.isdir(args.out):
        print(f"odocal-fleet: error: {args.out}: exists and is not a directory", file=sys.stderr)
        return 2
    if os.path.isdir(args.out) and os.listdir(args.out) and \
            not os.path.exists(os.path.join(args.out, "index.html")):
        print(f"odocal-fleet: error: {args.out}: a directory that is not an odocal-fleet report",
              file=sys.stderr)
        return 2
    model = health.HealthModel(false_alarm_rate=args.false_alarm_rate)
    try:
        report = health_command.assess(args.db, args.method, model)
        with sqlite3.connect(args.db) as db:
            failures = db.execute("SELECT vehicle_id, path, error, attempts FROM failures "
                                  "ORDER BY vehicle_id, path").fetchall()
    except (sqlite3.Error, ValueError) as error:
        print(f"odocal-fleet: error: {args.db}: {error}", file=sys.stderr)
        return 2
    files = {"plotly.min.js": plotly.offline.get_plotlyjs(),
             "index.html": index_page(report, failures)}
    for vehicle in report["vehicles"]:
        files[file_name(vehicle["vehicle_id"])] = vehicle_page(vehicle)
    try:
        write_directory(args.out, files)
    except OSError as error:
        print(f"odocal-fleet: error: {args.out}: {error.strerror}", file=sys.stderr)
        return 1
    print(f"report       {os.path.join(args.out, 'index.html')} ({len(report['vehicles'])} vehicles)")
    return 0
