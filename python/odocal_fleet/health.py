"""Tyre health across drives (docs/fleet.md#health). Per vehicle and rear wheel, each drive's
circumference estimate with its sigma is a measurement of a state [circumference, wear rate]
that moves with the distance driven: the circumference as a random walk plus the wear trend.
A Kalman filter runs forward over the drives and tests, after every drive, whether the last few
drives jumped away from what the filter predicted (a generalised likelihood-ratio test for one
step); an accepted step is an event (tyre change, rotation, pressure loss) and opens the state
again there. A Rauch-Tung-Striebel smoother then gives the circumference over the distance with
its band, and the wear rate, between events."""
import math
from dataclasses import dataclass, field
from statistics import NormalDist

import numpy as np

# Median of a chi-square with one degree of freedom: the scale a robust noise estimate needs.
CHI2_1_MEDIAN = 0.454936


@dataclass
class HealthModel:
    # Wear: 1 mm of radius per 10 000-40 000 km is 0.16-0.63 um of circumference per km.
    wear_rate_prior_m_per_km: float = -0.4e-6
    wear_rate_sigma_m_per_km: float = 0.6e-6
    # Slow changes that are not wear, per sqrt(km): 1 mm of circumference over 10 000 km.
    # Day-to-day scatter (temperature, load) is white per drive: the drive-sigma scale takes it.
    walk_m_per_sqrt_km: float = 0.01e-3
    initial_sigma_m: float = 0.03
    # A stated false-alarm rate: the probability that a vehicle without any event gets one
    # alarm over `design_drives` drives; each of the drives' `window` tests gets its share.
    false_alarm_rate: float = 0.01
    design_drives: int = 50
    window: int = 3
    # Per-drive sigmas are scaled by the scatter the drives of one wheel actually show (never
    # below 1): a calibration's sigma can miss errors that stay within one drive.
    adapt_sigma: bool = True

    # A step on the other wheel at the drive where one wheel stepped (a rotation moves both) is
    # one test, not a search: it gets this false-alarm probability.
    paired_false_alarm: float = 1e-3

    def threshold(self):
        """The chi-square(1) level of one step test."""
        return _chi2_1_level(self.false_alarm_rate / (self.design_drives * self.window))

    def paired_threshold(self):
        return _chi2_1_level(self.paired_false_alarm)


def _chi2_1_level(probability):
    z = NormalDist().inv_cdf(1.0 - probability / 2.0)
    return z * z


@dataclass
class Drive:
    odometer_km: float
    start_time: str
    path: str
    value_m: float
    sigma_m: float            # of this drive's own error: what moves from drive to drive
    common_sigma_m: float = 0.0  # of an error every drive of the vehicle shares (its body's)


@dataclass
class Event:
    wheel: str
    drive_index: int       # the first drive after the change
    odometer_km: float     # where the change happened at the latest (that drive's start)
    start_time: str
    step_m: float
    sigma_m: float
    kind: str = ""
    detected_at_index: int = 0
    detected_at_km: float = 0.0


@dataclass
class WheelHealth:
    wheel: str
    odometer_km: np.ndarray
    circumference_m: np.ndarray     # smoothed, at each drive
    sigma_m: np.ndarray
    wear_rate_m_per_km: float       # over the last stretch without event
    wear_rate_sigma_m_per_km: float
    sigma_scale: float
    events: list = field(default_factory=list)


def _transition(ds_km):
    return np.array([[1.0, ds_km], [0.0, 1.0]])


def _process_noise(model, ds_km):
    ds = max(ds_km, 0.0)
    return np.diag([model.walk_m_per_sqrt_km ** 2 * ds, 1e-4 * model.wear_rate_sigma_m_per_km ** 2 * ds])


def _prior(model, value_m):
    x = np.array([value_m, model.wear_rate_prior_m_per_km])
    P = np.diag([model.initial_sigma_m ** 2, model.wear_rate_sigma_m_per_km ** 2])
    return x, P


def _filter(model, drives, scale, openings):
    """Forward pass; `openings` are the drive indices where a change opens the state again.
    Returns the predicted and updated states and the normalised innovations."""
    n = len(drives)
    xs_pred, Ps_pred, xs, Ps, z = [], [], [], [], np.zeros(n)
    x, P = _prior(model, drives[0].value_m)
    for k, drive in enumerate(drives):
        if k > 0:
            F = _transition(drive.odometer_km - drives[k - 1].odometer_km)
            x = F @ x
            P = F @ P @ F.T + _process_noise(model, drive.odometer_km - drives[k - 1].odometer_km)
        if k in openings:
            P = P.copy()
            P[0, 0] += model.initial_sigma_m ** 2
        xs_pred.append(x.copy())
        Ps_pred.append(P.copy())
        r = (scale * drive.sigma_m) ** 2
        s = P[0, 0] + r
        innovation = drive.value_m - x[0]
        z[k] = innovation / math.sqrt(s)
        gain = P[:, 0] / s
        x = x + gain * innovation
        P = P - np.outer(gain, P[0, :])
        xs.append(x.copy())
        Ps.append(P.copy())
    return xs_pred, Ps_pred, xs, Ps, z


def _smooth(model, drives, xs_pred, Ps_pred, xs, Ps):
    n = len(drives)
    xs_s, Ps_s = [None] * n, [None] * n
    xs_s[-1], Ps_s[-1] = xs[-1], Ps[-1]
    for k in range(n - 2, -1, -1):
        F = _transition(drives[k + 1].odometer_km - drives[k].odometer_km)
        C = Ps[k] @ F.T @ np.linalg.inv(Ps_pred[k + 1])
        xs_s[k] = xs[k] + C @ (xs_s[k + 1] - xs_pred[k + 1])
        Ps_s[k] = Ps[k] + C @ (Ps_s[k + 1] - Ps_pred[k + 1]) @ C.T
    return xs_s, Ps_s


def _step_test(model, drives, scale, x, P, first, last):
    """GLR for one step common to drives first..last against the prediction (x, P) made
    before `first`: returns (statistic, step, its sigma)."""
    rows, e, r = [], [], []
    for j in range(first, last + 1):
        ds = drives[j].odometer_km - drives[first].odometer_km
        rows.append([1.0, ds])
        e.append(drives[j].value_m - (x[0] + x[1] * ds))
        r.append((scale * drives[j].sigma_m) ** 2)
    H = np.array(rows)
    S = H @ P @ H.T + np.diag(r)
    ones = np.ones(len(e))
    Si1 = np.linalg.solve(S, ones)
    information = ones @ Si1
    step = (Si1 @ np.array(e)) / information
    return step * step * information, step, 1.0 / math.sqrt(information)


def _detect(model, drives, scale, paired=frozenset(), forced=frozenset()):
    """Causal detection: after each drive, the last `window` drives tested against the filter's
    prediction from before them (at the `paired` drives, where the other wheel stepped, with the
    lower level of one test; at the `forced` drives the state is opened without a test).
    Returns the events found, each with the drive where it was found."""
    events, openings = [], set(forced)
    x, P = _prior(model, drives[0].value_m)
    predictions = []  # (x, P) predicted at each drive before its update
    for k, drive in enumerate(drives):
        if k > 0:
            ds = drive.odometer_km - drives[k - 1].odometer_km
            F = _transition(ds)
            x, P = F @ x, F @ P @ F.T + _process_noise(model, ds)
        if k in openings:
            P = P.copy()
            P[0, 0] += model.initial_sigma_m ** 2
        predictions.append((x.copy(), P.copy()))
        r = (scale * drive.sigma_m) ** 2
        s = P[0, 0] + r
        gain = P[:, 0] / s
        x = x + gain * (drive.value_m - x[0])
        P = P - np.outer(gain, P[0, :])
        last_opening = max((o for o in openings if o <= k), default=0)
        best = None
        for first in range(max(k - model.window + 1, last_opening + 1, 1), k + 1):
            statistic, step, sigma = _step_test(model, drives, scale, *predictions[first], first, k)
            threshold = model.paired_threshold() if first in paired else model.threshold()
            if statistic > threshold and (best is None or statistic > best[0]):
                best = (statistic, step, sigma, first)
        if best is not None:
            _, step, sigma, first = best
            events.append(Event(wheel="", drive_index=first, odometer_km=drives[first].odometer_km,
                                start_time=drives[first].start_time, step_m=step, sigma_m=sigma,
                                detected_at_index=k, detected_at_km=drive.odometer_km))
            openings.add(first)
            # Re-run the filter from the change with the state opened there.
            x, P = predictions[first]
            P = P.copy()
            P[0, 0] += model.initial_sigma_m ** 2
            for j in range(first, k + 1):
                if j > first:
                    ds = drives[j].odometer_km - drives[j - 1].odometer_km
                    F = _transition(ds)
                    x, P = F @ x, F @ P @ F.T + _process_noise(model, ds)
                    predictions[j] = (x.copy(), P.copy())
                r = (scale * drives[j].sigma_m) ** 2
                s = P[0, 0] + r
                gain = P[:, 0] / s
                x = x + gain * (drives[j].value_m - x[0])
                P = P - np.outer(gain, P[0, :])
    return events


def _sigma_scale(model, drives, openings):
    """How much wider the drives scatter than their sigmas say (never below 1), from the
    normalised differences of consecutive drives, leaving out those across a change: a step
    moves one difference only. Their median starts it; the mean of those within 3 sigma of it
    (over the variance of a normal cut there, 0.973) then gives an estimate nearly as efficient
    as the plain mean, without the steps."""
    if not model.adapt_sigma:
        return 1.0
    ratios = [(drives[k].value_m - drives[k - 1].value_m) ** 2
              / (drives[k].sigma_m ** 2 + drives[k - 1].sigma_m ** 2)
              for k in range(1, len(drives)) if k not in openings]
    if len(ratios) < 3:
        return 1.0
    ratios = np.array(ratios)
    variance = float(np.median(ratios)) / CHI2_1_MEDIAN
    for _ in range(3):
        kept = ratios[ratios < 9.0 * variance]
        if len(kept) < 3:
            break
        variance = float(np.mean(kept)) / 0.9733
    return max(1.0, math.sqrt(variance))


def wheel_health(model, wheel, drives, paired=frozenset(), forced=frozenset()):
    """Events and smoothed circumference of one wheel over its drives (sorted by odometer);
    `paired`: drives where the other wheel stepped; `forced`: changes known from elsewhere."""
    if not drives:
        raise ValueError(f"no usable drive for wheel {wheel}")
    # The scatter first, with no event (the median shrugs off a step), then the events and the
    # scatter again: each decides the other.
    scale = _sigma_scale(model, drives, forced)
    events = []
    for _ in range(3):
        events = _detect(model, drives, scale, paired, forced)
        new_scale = _sigma_scale(model, drives, {e.drive_index for e in events} | forced)
        if abs(new_scale - scale) < 0.02 * scale:
            scale = new_scale
            break
        scale = new_scale
    events = _detect(model, drives, scale, paired, forced)
    for event in events:
        event.wheel = wheel
    openings = {e.drive_index for e in events} | forced
    xs_pred, Ps_pred, xs, Ps, _ = _filter(model, drives, scale, openings)
    xs_s, Ps_s = _smooth(model, drives, xs_pred, Ps_pred, xs, Ps)
    return WheelHealth(
        wheel=wheel, odometer_km=np.array([d.odometer_km for d in drives]),
        circumference_m=np.array([x[0] for x in xs_s]),
        # A shared error does not average out over the drives: it floors the level's sigma.
        sigma_m=np.array([math.sqrt(P[0, 0] + d.common_sigma_m ** 2) for P, d in zip(Ps_s, drives)]),
        wear_rate_m_per_km=float(xs_s[-1][1]),
        wear_rate_sigma_m_per_km=math.sqrt(Ps_s[-1][1, 1]), sigma_scale=scale, events=events)


def vehicle_health(model, drives_by_wheel):
    """Both rear wheels of one vehicle (the same drives, in order): each wheel alone, then again
    with the other wheel's steps as paired tests; the events named (classify)."""
    alone = {w: wheel_health(model, w, d) for w, d in drives_by_wheel.items()}
    wheels = {}
    for wheel, drives in drives_by_wheel.items():
        other = [w for w in drives_by_wheel if w != wheel]
        paired = frozenset(e.drive_index for w in other for e in alone[w].events)
        wheels[wheel] = wheel_health(model, wheel, drives, paired) if paired else alone[wheel]
    for wheel, other in (("rl", "rr"), ("rr", "rl")):
        for event in list(wheels[wheel].events):
            step = _rotation_partner(model, event, drives_by_wheel[wheel], drives_by_wheel[other],
                                     wheels[other], wheels[wheel].sigma_scale)
            if step is not None:
                forced = frozenset({event.drive_index}) | {e.drive_index for e in wheels[other].events}
                found = wheel_health(model, other, drives_by_wheel[other], forced=forced)
                found.events.append(Event(
                    wheel=other, drive_index=event.drive_index, odometer_km=event.odometer_km,
                    start_time=event.start_time, step_m=step[0], sigma_m=step[1],
                    detected_at_index=event.detected_at_index, detected_at_km=event.detected_at_km))
                found.events.sort(key=lambda e: e.drive_index)
                wheels[other] = found
    return wheels, classify(wheels["rl"].events, wheels["rr"].events, wheels)


def _rotation_partner(model, event, drives, other_drives, other, scale):
    """A wheel that stepped by about the difference to the other wheel, while the other moved
    the opposite way, was swapped with it: the other wheel's step and its sigma, else None.
    (The other wheel's drives are scaled as the stepping wheel's: its own scale took the step
    it missed for noise.)"""
    j = event.drive_index
    if j < 1 or any(e.drive_index == j for e in other.events):
        return None
    before = range(max(j - model.window, 0), j)
    after = range(j, min(j + model.window, len(drives)))
    mean = lambda ds, idx: float(np.mean([ds[i].value_m for i in idx]))
    spread = lambda ds, idx: scale * float(np.mean([ds[i].sigma_m for i in idx]))
    difference = mean(other_drives, before) - mean(drives, before)
    other_step = mean(other_drives, after) - mean(other_drives, before)
    sigma = math.hypot(spread(other_drives, before) / math.sqrt(len(before)),
                       spread(other_drives, after) / math.sqrt(len(after)))
    visible = abs(difference) > 2.0 * math.hypot(event.sigma_m, sigma)
    if (visible and other_step * event.step_m < 0
            and abs(event.step_m - difference) < 3.0 * math.hypot(event.sigma_m, sigma)
            and abs(other_step + difference) < 3.0 * math.hypot(event.sigma_m, sigma)):
        return other_step, sigma
    return None


def classify(events_rl, events_rr, health):
    """Names each event: a rotation when both wheels stepped at the same drive by about the
    difference between them, a tyre change when a wheel grew, a pressure loss when one dropped."""
    by_drive = {}
    for event in events_rl + events_rr:
        by_drive.setdefault(event.drive_index, []).append(event)
    named = []
    for index in sorted(by_drive):
        group = by_drive[index]
        if len(group) == 2 and group[0].step_m * group[1].step_m < 0:
            rl = next(e for e in group if e.wheel == "rl")
            before = {w: health[w].circumference_m[index - 1] for w in ("rl", "rr")}
            swap = before["rr"] - before["rl"]
            if abs(rl.step_m - swap) < 3.0 * math.hypot(rl.sigma_m, health["rl"].sigma_m[index - 1]):
                for event in group:
                    event.kind = "rotation"
                named.extend(group)
                continue
        for event in group:  # a drop on one wheel: pressure lost, or a more worn tyre fitted
            event.kind = "tyre change" if event.step_m > 0 else "pressure loss"
        named.extend(group)
    return named
