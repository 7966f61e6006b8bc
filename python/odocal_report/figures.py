"""The plots of a calibration report, as plotly figures built from the result JSON and the log
(via the odocal module): the dead-reckoned track with nominal and calibrated parameters against
GNSS, the held-out drift windows against speed and lateral acceleration, the iterations."""
import numpy as np
import plotly.graph_objects as go


def aligned_track(log, params, align_s=60.0):
    """Dead reckoning with `params`, rotated and shifted onto the GNSS track over the first
    `align_s` seconds (least squares, as `odocal deadreckon` aligns its window)."""
    import odocal

    track = odocal.dead_reckon(log, params)
    t, x, y = track["t_s"], track["x_m"], track["y_m"]
    g_t, g_x, g_y = log.gnss.t_s, log.gnss.x_m, log.gnss.y_m
    use = (g_t >= t[0]) & (g_t <= min(t[0] + align_s, t[-1]))
    if use.sum() < 3:
        use = (g_t >= t[0]) & (g_t <= t[-1])
    a = np.column_stack([np.interp(g_t[use], t, x), np.interp(g_t[use], t, y)])
    b = np.column_stack([g_x[use], g_y[use]])
    a_mean, b_mean = a.mean(axis=0), b.mean(axis=0)
    u, _, vt = np.linalg.svd((a - a_mean).T @ (b - b_mean))
    rotation = (u @ vt).T
    if np.linalg.det(rotation) < 0:
        vt[-1] *= -1
        rotation = (u @ vt).T
    points = (np.column_stack([x, y]) - a_mean) @ rotation.T + b_mean
    return t, points[:, 0], points[:, 1]


MAX_POINTS = 4000  # per trace: SVG stays light, a 13 km circuit keeps metre-level detail


def thin(*columns):
    step = max(1, len(columns[0]) // MAX_POINTS)
    return [np.asarray(c)[::step] for c in columns]


def track_figure(log, nominal, calibrated):
    fig = go.Figure()
    gnss_x, gnss_y = thin(log.gnss.x_m, log.gnss.y_m)
    fig.add_trace(go.Scatter(x=gnss_x, y=gnss_y,
                               mode="markers", name="GNSS", marker={"size": 3, "color": "#999"}))
    for name, params, colour in (("nominal", nominal, "#d62728"), ("calibrated", calibrated, "#1f77b4")):
        _, x, y = aligned_track(log, params)
        x, y = thin(x, y)
        fig.add_trace(go.Scatter(x=x, y=y, mode="lines", name=f"dead reckoning, {name}",
                                   line={"color": colour}))
    fig.update_layout(title="Dead reckoning against GNSS (aligned over the first 60 s)",
                      xaxis_title="east [m]", yaxis_title="north [m]",
                      yaxis={"scaleanchor": "x", "scaleratio": 1}, height=600)
    return fig


def window_conditions(log, windows, window_s):
    """Mean speed and mean |lateral acceleration| over each drift window."""
    t, rl, rr = (np.asarray(log.wheels.t_s), np.asarray(log.wheels.rev_rl),
                 np.asarray(log.wheels.rev_rr))
    c = 0.5 * (log.vehicle.circumference_rl_m + log.vehicle.circumference_rr_m)
    speeds, lateral = [], []
    for w in windows:
        inside = (t > w["start_s"]) & (t <= w["start_s"] + window_s)
        speeds.append(float(0.5 * (rl[inside] + rr[inside]).sum() * c / window_s))
        if log.imu is not None:
            it = np.asarray(log.imu.t_s)
            use = (it > w["start_s"]) & (it <= w["start_s"] + window_s)
            lateral.append(float(np.abs(np.asarray(log.imu.ay_mps2)[use]).mean()) if use.any() else np.nan)
        else:
            lateral.append(np.nan)
    return np.array(speeds), np.array(lateral)


def drift_figures(log, drift, window_s):
    windows = drift["windows"]
    start = np.array([w["start_s"] for w in windows])
    distance = np.array([w["distance_m"] for w in windows])
    nominal = 100 * np.array([w["nominal_end_error_m"] for w in windows]) / distance
    calibrated = 100 * np.array([w["calibrated_end_error_m"] for w in windows]) / distance
    over_time = go.Figure()
    over_time.add_trace(go.Bar(x=start, y=nominal, name="nominal", marker_color="#d62728"))
    over_time.add_trace(go.Bar(x=start, y=calibrated, name="calibrated", marker_color="#1f77b4"))
    over_time.update_layout(title=f"Held-out drift per {window_s:.0f} s window",
                            xaxis_title="window start [s]", yaxis_title="drift [% of distance]",
                            barmode="group", height=400)
    speed, lateral = window_conditions(log, windows, window_s)
    conditions = go.Figure()
    conditions.add_trace(go.Scatter(x=speed, y=calibrated, mode="markers", name="against speed"))
    if np.isfinite(lateral).any():
        conditions.add_trace(go.Scatter(x=lateral, y=calibrated, mode="markers", xaxis="x2",
                                        name="against |lateral acceleration|"))
        conditions.update_layout(xaxis2={"title": "mean |lateral acceleration| [m/s²]",
                                         "overlaying": "x", "side": "top"})
    conditions.update_layout(title="Calibrated drift against the driving in each window",
                             xaxis_title="mean speed [m/s]", yaxis_title="drift [% of distance]",
                             height=400)
    return [over_time, conditions]


def iterations_figure(result):
    iterations = result.get("iterations") or []
    if not iterations:
        return None
    n = [it["iteration"] for it in iterations]
    fig = go.Figure()
    for key, name in (("circumference_rl_m", "c_RL"), ("circumference_rr_m", "c_RR")):
        fig.add_trace(go.Scatter(x=n, y=[1000 * it[key] for it in iterations], name=f"{name} [mm]"))
    fig.add_trace(go.Scatter(x=n, y=[it["score"] for it in iterations], name="score", yaxis="y2"))
    fig.update_layout(title="Iterations (layers 2-3)", xaxis_title="iteration",
                      yaxis_title="circumference [mm]",
                      yaxis2={"title": "whole-log score", "overlaying": "y", "side": "right"},
                      height=400)
    return fig
