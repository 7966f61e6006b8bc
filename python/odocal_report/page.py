"""A calibration report as one static HTML page: the numbers and verdicts as tables, the plots
with plotly's script embedded once (offline: nothing is fetched from the network)."""
import html
import json
import math

import plotly.io
import plotly.offline


def table(rows, header):
    head = "".join(f"<th>{html.escape(str(h))}</th>" for h in header)
    body = "".join("<tr>" + "".join(f"<td>{html.escape(str(c))}</td>" for c in row) + "</tr>"
                   for row in rows)
    return f"<table><thead><tr>{head}</tr></thead><tbody>{body}</tbody></table>"


def gap_share_text(selection):
    """How much of its gap to the judging fit the plain fit carries: all of it where that fit is
    better (or cannot stand), the criteria's share where it fits the log only about as well."""
    share = selection.get("plain_gap_share")
    if share is not None and share < 1.0:
        return (f"{share:.2f} of their gap, the share that the criteria weigh (it fits the log "
                f"about as well),")
    return "their gap"


def tyre_selection_text(selection):
    """The tyre models compared: which stands, every criterion, each candidate's circumferences
    at rest and whether it is a tyre, and whose gap the plain (or the chosen) circumferences
    carry."""
    if selection.get("judges_plain"):
        chosen = "plain, as configured, judged by the tyre models"
    elif selection.get("chosen", "none") == "none":
        chosen = "plain" + (", the track width free" if selection.get("plain_track_free") else "")
    else:
        chosen = selection["chosen"]
    parts = []
    if selection.get("plain_bic") is not None:
        parts.append(f"plain BIC {selection['plain_bic']:.1f}")
    for c in selection.get("candidates", []):
        rest = ""
        if c.get("circumference_rl_m") is not None and c.get("circumference_rr_m") is not None:
            rest = f", at rest {c['circumference_rl_m']:.4f} / {c['circumference_rr_m']:.4f} m"
        bic = f"BIC {c['bic']:.1f}" if c.get("bic") is not None else "not solved"
        standing = ("" if c.get("tyre", True) else ", no tyre") + (
            ", every coefficient held" if c.get("every_coefficient_held") else "") + (
            ", judged under the GNSS noise shown" if c.get("judged_under_noise_shown") else "")
        parts.append(f"{c['model']} {bic}{standing}{rest}")
    text = f"{chosen} ({'; '.join(parts)})"
    if selection.get("plain_gap_to"):
        text += (f"; the plain circumferences carry {gap_share_text(selection)} to the "
                 f"{selection['plain_gap_to']} fit in their sigma")
    if selection.get("chosen_gap_to"):
        sigmas = selection.get("chosen_gap_sigmas")
        away = f" ({sigmas:.1f} of their combined sigma away)" if sigmas is not None else ""
        text += (f"; the {selection['chosen']} circumferences carry their gap to the "
                 f"{selection['chosen_gap_to']} fit{away} in their sigma")
    return text


def latency_detection_text(detection, result):
    """What detect_latency found (docs/batch-calibration.md, "A latency the log shows")."""
    if detection.get("by_doppler_noise"):
        text = (f"the fit without it left the Doppler speed's noise "
                f"{detection['doppler_sigma_scale']:.1f} times the configured")
    elif detection.get("by_gnss_noise"):
        text = (f"the fit without it left the GNSS fixes' residuals "
                f"{detection['gnss_sigma_scale']:.1f} times their configured noise")
    else:
        text = (f"the fit without it left the {detection['residual']} residual following the "
                f"longitudinal acceleration (rho = {detection['correlation']:.2f})")
    latency, sigma = detection.get("latency_s"), detection.get("sigma_s")
    if latency is None or sigma is None:
        return text + "; with the latency estimated the fit did not stand: kept without"
    if detection.get("significant") and not detection["taken"]:
        noise, scale, whose = (
            ("the fixes' residuals stay", detection.get("gnss_sigma_scale_with"), "a lag's alone")
            if detection.get("by_gnss_noise") else
            ("the Doppler speed's noise stays", detection.get("doppler_sigma_scale_with"),
             "a lag's"))
        return (text + f"; estimated, {1000 * latency:.1f} ms (1-sigma {1000 * sigma:.1f} ms), but "
                f"{noise} {scale:.1f} times the configured with it: not {whose}, kept without "
                "the latency")
    if not detection["taken"]:
        return (text + f"; estimated, {1000 * latency:.1f} ms (1-sigma {1000 * sigma:.1f} ms), "
                "not significant: kept without the latency")
    without = detection["circumference_without_m"]
    moved = [1000 * (result[f"circumference_{w}_m"] - without[i]) for i, w in enumerate(("rl", "rr"))]
    return (text + f"; estimated: the GNSS fixes {'lag' if latency > 0 else 'lead'} the wheels by "
            f"{1000 * abs(latency):.1f} ms (1-sigma {1000 * sigma:.1f} ms), which moves the "
            f"circumferences by {moved[0]:+.3g} / {moved[1]:+.3g} mm to these")


def heading_after_text(detection):
    """A heading bias found in the fit the others left (heading_after)."""
    after = detection["heading_after"]
    without, with_it = after["circumference_without_m"], after["circumference_with_m"]
    moved = [1000 * (with_it[i] - without[i]) for i in range(2)]
    antenna = "lever_arm_m" in detection and detection.get("taken")
    found = (("the antenna and the latency" if antenna else "the latency")
             if after.get("beside_latency") else "the antenna")
    return (f"the fit with {found} left heading.csv {math.degrees(after['seen_rad']):+.2f} "
            "deg off the fitted heading, which the fits before hid (their fixes far off the "
            "path); "
            f"estimated beside them: heading.csv reading "
            f"{math.degrees(detection['heading_bias_rad']):+.2f} deg "
            f"(1-sigma {math.degrees(detection['heading_bias_sigma_rad']):.2f}) beyond the "
            f"heading, which moves the circumferences by {moved[0]:+.3g} / {moved[1]:+.3g} mm")


def mounting_detection_text(detection, result):
    """What detect_mounting found (docs/batch-calibration.md, "The mounting the log shows")."""
    if "heading_after" not in detection:
        return first_look_text(detection, result)
    if "lever_arm_m" not in detection:
        return heading_after_text(detection)
    return first_look_text(detection, result) + "; then " + heading_after_text(detection)


def first_look_text(detection, result):
    """The mounting found by the first fit's residuals (or the fixes' noise, or beside a lag)."""
    seen, found = [], []
    signature = detection["signature"]
    if "lever_arm_m" in detection:
        ahead, left = signature.get("gnss_mean_m", [0.0, 0.0])
        doppler = (f", the Doppler speed as from {signature['doppler_left_m']:+.2f} m left"
                   if "doppler_left_m" in signature else "")
        by_noise = detection.get("by_gnss_noise")
        seen.append(f"the GNSS fixes' residuals {detection.get('gnss_sigma_scale_without', 0):.1f} "
                    "times their configured noise (their means showed no antenna)" if by_noise else
                    f"the GNSS fixes {ahead:+.2f} m ahead and {left:+.2f} m left of the fitted "
                    f"path{doppler}")
        (x, y), (sx, sy) = detection["lever_arm_m"], detection["lever_arm_sigma_m"]
        then = (f", which leaves the fixes {detection.get('gnss_sigma_scale_with', 0):.1f} times"
                if by_noise else "")
        found.append(f"the antenna {x:+.3f} m ahead (1-sigma {sx:.3f}) and {y:+.3f} m left "
                     f"(1-sigma {sy:.3f}) of the rear axle's centre{then}")
    if "heading_bias_rad" in detection and "heading_after" not in detection:
        seen.append(f"heading.csv {math.degrees(signature.get('heading_mean_rad', 0.0)):+.2f} deg "
                    "off the fitted heading")
        found.append(f"heading.csv reading {math.degrees(detection['heading_bias_rad']):+.2f} deg "
                     f"(1-sigma {math.degrees(detection['heading_bias_sigma_rad']):.2f}) beyond "
                     "the heading")
    if detection.get("found_beside_latency"):
        without, with_it = detection["circumference_without_m"], detection["circumference_with_m"]
        moved = [1000 * (with_it[i] - without[i]) for i in range(2)]
        return (f"the latency's fit alone left the GNSS fixes' residuals "
                f"{detection['gnss_sigma_scale_without']:.1f} times their configured noise; "
                "estimated beside it: " + "; ".join(found) + f"; with the latency these leave them "
                f"{detection['gnss_sigma_scale_with']:.1f} times and move the circumferences by "
                f"{moved[0]:+.3g} / {moved[1]:+.3g} mm")
    text = "the fit without them left " + "; ".join(seen)
    if not detection["fitted"]:
        return text + "; with them estimated the fit did not stand: kept without"
    if detection.get("explained_by_latency"):
        return (text + "; estimated, " + "; ".join(found) + "; but not significant with the "
                "latency estimated beside it: the lag showed as it, kept without")
    if not detection["taken"]:
        return text + "; estimated, " + "; ".join(found) + ", not significant: kept without"
    without = detection["circumference_without_m"]
    # Its own fit's: a latency found after it moves the result again (the latency row says so).
    with_it = detection.get("circumference_with_m",
                            [result["circumference_rl_m"], result["circumference_rr_m"]])
    moved = [1000 * (with_it[i] - without[i]) for i in range(2)]
    return (text + "; estimated: " + "; ".join(found) +
            f", which moves the circumferences by {moved[0]:+.3g} / {moved[1]:+.3g} mm")


def accelerometer_offset_text(result):
    """What the log's preparation measured of the accelerometer's forward offset, and its share
    of the circumferences' sigma; None where the log has no accelerometer or nothing was read."""
    preparation = result.get("preparation", {})
    drive = preparation.get("accelerometer_drive_offset")
    stops = preparation.get("accelerometer_offset")
    if drive:
        where = f"over {drive['duration_s']:.0f} s of driving (too few stops)"
        measured = drive
    elif stops:
        where = f"at {stops['stops']} stop(s)"
        measured = stops
    else:
        measured = None
    parts = []
    if measured:
        done = "removed" if measured["removed"] else "within its noise, left in"
        parts.append(f"{measured['forward_mps2']:+.3f} m/s² {where}, 1-sigma "
                     f"{measured['sigma_mps2']:.3f}: {done}")
    elif "accelerometer_driving_offset_mps2" in preparation:
        parts.append(f"not measured: it reads {preparation['accelerometer_driving_offset_mps2']:+.3f}"
                     " m/s² beyond the wheels' acceleration driving straight")
    share = result.get("forward_offset_sigma_m")
    if share:
        parts.append(f"{1000 * share[0]:.3g} / {1000 * share[1]:.3g} mm of the circumferences' "
                     f"sigma (known to ±{result['forward_offset_sigma_mps2']:.3g} m/s²)")
    return "; ".join(parts) if parts else None


def track_share_text(result):
    """The held track's share of the circumferences' sigma, where the calibration found it worth
    naming (track_share_worth_naming, the text report's rule); or, where the track was fitted
    under its prior (track_under_prior), what it shares of the sigma; or, where another method held
    it and its judge fitted it under its prior (judged_track_m), what the held one's distance from
    that track adds."""
    share = result.get("track_sigma_m")
    if not share:
        return None
    if "judged_track_m" in result:
        return (f"{1000 * share[0]:.3g} / {1000 * share[1]:.3g} mm of the circumferences' sigma: "
                f"the judge's plain fit, the track under its prior (vehicle.yaml's ±"
                f"{100 * result['track_width_uncertainty']:.3g} %), puts it at "
                f"{result['judged_track_m']:.4f} m (1-sigma {result['judged_track_sigma_m']:.2g} m),"
                f" and the held one carries its distance from it")
    if result.get("track_under_prior"):
        return (f"fitted under its prior (vehicle.yaml's ±"
                f"{100 * result['track_width_uncertainty']:.3g} %; the two-wheel model explains "
                f"the log), sharing {1000 * share[0]:.3g} / {1000 * share[1]:.3g} mm of the "
                f"circumferences' sigma")
    if not result.get("track_share_worth_naming"):
        return None
    return (f"{1000 * share[0]:.3g} / {1000 * share[1]:.3g} mm of the circumferences' sigma: the "
            f"track the wheels roll on may lie ±{100 * result['track_width_uncertainty']:.3g} % "
            f"from vehicle.yaml's, and the turns set the scale through it")


def summary_rows(result):
    def mm(value):
        return f"{1000 * value:.3f} mm" if isinstance(value, (int, float)) else "–"

    nominal = result.get("nominal", {})
    rows = [("method", result["method"]),
            ("outcome", f"{'usable' if result['usable'] else 'NOT USABLE'} ({result['termination']})"),
            ("message", result.get("message", ""))]
    for wheel in ("rl", "rr"):
        value = result.get(f"circumference_{wheel}_m")
        sigma = result.get(f"sigma_circumference_{wheel}_m")
        base = nominal.get(f"circumference_{wheel}_m")
        change = f", {1000 * (value - base):+.3f} mm from nominal" if value and base else ""
        rows.append((f"c_{wheel.upper()}", f"{value:.6f} m (1-sigma {mm(sigma)}{change})"
                     if value is not None else "–"))
    rows.append(("identifiability", result.get("identifiability", "")))
    if result.get("model_adequacy", {}).get("verdict"):
        rows.append(("model adequacy", result["model_adequacy"]["verdict"]))
    if result.get("tyre_selection"):
        rows.append(("tyre model", tyre_selection_text(result["tyre_selection"])))
    if result.get("mounting_detection"):
        rows.append(("mounting", mounting_detection_text(result["mounting_detection"], result)))
    if result.get("latency_detection"):
        rows.append(("latency", latency_detection_text(result["latency_detection"], result)))
    if result.get("misfit_sigma_scale", 1.0) > 1.0:
        rows.append(("sigma widened", f"x{result['misfit_sigma_scale']:.3g}: the odometry residuals "
                     f"are that many times as wide as their noise model (chi2/dof "
                     f"{result['model_adequacy']['chi2_per_dof']:.3g})"))
    for when in ("before", "after"):
        dr = result.get(f"dead_reckoning_{when}")
        if dr:
            rows.append((f"dead reckoning {when}", f"mean {dr['mean_position_m']:.3f} m / "
                         f"{dr['mean_heading_deg']:.3f} deg, max {dr['max_position_m']:.3f} m"))
    walk = result.get("accelerometer_walk", {})
    if walk.get("heading_deg", 0.0) > 0.0:
        rows.append(("accelerometer noise", f"{walk['noise_x_mps2']:.3g} / "
                     f"{walk['noise_y_mps2']:.3g} m/s² forward / left per sample: through the "
                     f"tyre model it alone walks the dead-reckoned heading by "
                     f"{walk['heading_deg']:.3g} deg (1-sigma at the log's end)"))
    offset = accelerometer_offset_text(result)
    if offset:
        rows.append(("accelerometer offset", offset))
    track = track_share_text(result)
    if track:
        rows.append(("track width under its prior" if result.get("track_under_prior")
                     else "track width held", track))
    for parameter in result.get("parameters", []):
        if parameter.get("estimated") and not parameter["name"].startswith("circumference"):
            rows.append((parameter["name"], f"{parameter['value']:.6g} (1-sigma "
                         f"{parameter.get('sigma')}){'' if parameter.get('identified', True) else ' — ' + parameter.get('verdict', '')}"))
    if result.get("odometry_scales"):
        s = result["odometry_scales"]
        rows.append(("odometry scales", f"speed x{s['speed_scale']:.4f} (1-sigma "
                     f"{s['sigma_speed_scale']:.4f}), yaw rate x{s['yaw_rate_scale']:.4f} "
                     f"(1-sigma {s['sigma_yaw_rate_scale']:.4f})"))
    return rows


def render(title, result, findings, drift, figures):
    plots = "".join(
        f'<div class="plot">{plotly.io.to_html(fig, full_html=False, include_plotlyjs=False)}</div>'
        for fig in figures if fig is not None)
    drift_rows = [(name, d["windows"], f"{d['median_drift_percent']:.3f}",
                   f"{d['p95_drift_percent']:.3f}", f"{d['median_end_error_m']:.2f}")
                  for name, d in (("nominal", drift["nominal"]), ("calibrated", drift["calibrated"]))]
    # What the reference's own uncertainty alone would show: a drift near it is the reference's.
    floor = drift["reference_uncertainty"]
    drift_rows.append(("the reference's own uncertainty", drift["calibrated"]["windows"],
                       f"{floor['median_drift_percent']:.3f}", "-",
                       f"{floor['median_end_error_m']:.2f}"))
    finding_rows = [(f["severity"], f["check"], f["what"], f["evidence"], f["fix"]) for f in findings]
    return f"""<!DOCTYPE html>
<html lang="en"><head><meta charset="utf-8"><title>{html.escape(title)}</title>
<script type="text/javascript">{plotly.offline.get_plotlyjs()}</script>
<style>
body {{ font-family: sans-serif; margin: 2em; color: #222; }}
table {{ border-collapse: collapse; margin: 1em 0; }}
td, th {{ border: 1px solid #ccc; padding: 0.3em 0.6em; text-align: left; vertical-align: top; }}
th {{ background: #f2f2f2; }}
.plot {{ margin: 1.5em 0; }}
</style></head><body>
<h1>{html.escape(title)}</h1>
<h2>Result</h2>
{table(summary_rows(result), ("", ""))}
<h2>Input checks (odocal doctor)</h2>
{table(finding_rows, ("severity", "check", "what", "evidence", "fix")) if finding_rows else "<p>No finding.</p>"}
<h2>Held-out drift (odocal validate)</h2>
{table(drift_rows, ("parameters", "windows", "median drift [%]", "p95 drift [%]", "median end [m]"))}
<h2>Plots</h2>
{plots}
<h2>Configuration</h2>
<pre>{html.escape(json.dumps(result.get("configuration", {}), indent=2, sort_keys=True))}</pre>
</body></html>
"""
