"""Tyre health across drives: the smoother and the step detector against series with a known
truth (drawn from the stated noise), then odocal-fleet simulate -> run -> health end to end."""
import json
import math
import os
import re
import shutil
import sqlite3

import numpy as np
import pytest

from odocal_fleet import cli, health, health_command
from test_report import drawn_plots, load

CHROMIUM = shutil.which("chromium")

SIGMA = 0.5e-3  # a drive's circumference sigma, as the batch gives on a 6 km urban drive


def series(rng, n, step_at=None, step_m=0.0, wear_m_per_km=-0.4e-6, km_per_drive=20.0,
           sigma=SIGMA, start=1.95):
    drives, truth = [], []
    for k in range(n):
        odometer = 10_000.0 + km_per_drive * k
        value = start + wear_m_per_km * (odometer - 10_000.0)
        if step_at is not None and k >= step_at:
            value += step_m
        truth.append(value)
        drives.append(health.Drive(odometer_km=odometer, start_time=f"drive {k}", path=f"d{k}",
                                   value_m=value + sigma * rng.standard_normal(), sigma_m=sigma))
    return drives, np.array(truth)


def test_no_event_on_unchanged_tyres_at_the_stated_rate():
    model = health.HealthModel()
    rng = np.random.default_rng(1)
    vehicles, alarms, covered, points = 300, 0, 0, 0
    for _ in range(vehicles):
        drives, truth = series(rng, model.design_drives)
        result = health.wheel_health(model, "rl", drives)
        alarms += bool(result.events)
        covered += int(np.sum(np.abs(result.circumference_m - truth) < 2.0 * result.sigma_m))
        points += len(truth)
    assert alarms / vehicles <= 3 * model.false_alarm_rate  # 1 % stated; 3 on 300 is 2 sigma out
    assert covered / points > 0.9  # the 2-sigma band holds the truth (95 % nominal)


def test_a_one_millimetre_radius_step_is_found_at_its_drive():
    model = health.HealthModel()
    rng = np.random.default_rng(2)
    step = 2 * math.pi * 1e-3  # 1 mm of radius
    for sign in (1.0, -1.0):
        for _ in range(20):
            drives, _ = series(rng, 30, step_at=12, step_m=sign * step)
            result = health.wheel_health(model, "rl", drives)
            assert [e.drive_index for e in result.events] == [12]
            event = result.events[0]
            assert event.detected_at_index <= 13
            assert abs(event.step_m - sign * step) < 4 * event.sigma_m


def test_the_bodys_shared_error_is_kept_out_of_the_changes_and_in_the_level():
    """Drives whose sigma is mostly the body's share (as under tyre_model auto: 0.9 of 0.95 mm),
    the body's error drawn once per vehicle: a 0.45 mm radius loss (a 25 % pressure loss) is
    found by its own drive (20 of 20; with the total sigma taken as each drive's own, none),
    and the level's 2-sigma band still holds the truth, the shared error included. The shared
    error is split between the body's share and the held tyre coefficients' (0.6 and 0.8 of it:
    both are the car's, the same on every drive), which add in squares."""
    model = health.HealthModel()
    rng = np.random.default_rng(5)
    own, common = 0.3e-3, 0.9e-3
    total = math.hypot(own, common)
    step = -2 * math.pi * 0.45e-3
    found_at_once, covered, points = 0, 0, 0
    for _ in range(20):
        drives, truth = series(rng, 24, step_at=12, step_m=step, sigma=own)
        offset = common * rng.standard_normal()
        rows = [("car", d.path, d.start_time, d.odometer_km, None, d.value_m + offset,
                 d.value_m + offset, total, total, 0.6 * common, 0.6 * common, 0.8 * common,
                 0.8 * common) for d in drives]
        wheels, events = health.vehicle_health(model, health_command.wheel_drives(rows))
        rl = [e for e in events if e.wheel == "rl"]
        assert [e.drive_index for e in rl] == [12]
        found_at_once += rl[0].detected_at_index == 12
        assert min(wheels["rl"].sigma_m) >= common
        covered += int(np.sum(np.abs(wheels["rl"].circumference_m - truth) < 2 * wheels["rl"].sigma_m))
        points += len(truth)
    assert found_at_once >= 18
    assert covered / points > 0.8  # one shared draw per vehicle: 20 draws, not 480


def test_sigma_shrinks_as_one_over_sqrt_n_while_the_tyre_is_unchanged():
    model = health.HealthModel(walk_m_per_sqrt_km=0.0, adapt_sigma=False)
    rng = np.random.default_rng(3)
    drives, _ = series(rng, 64, wear_m_per_km=0.0, km_per_drive=0.0)
    sigmas = [health.wheel_health(model, "rl", drives[:n]).sigma_m[-1] for n in (4, 16, 64)]
    assert sigmas[0] / sigmas[1] == pytest.approx(2.0, rel=0.15)
    assert sigmas[1] / sigmas[2] == pytest.approx(2.0, rel=0.15)


def test_overconfident_drive_sigmas_are_scaled_to_the_scatter():
    model = health.HealthModel()
    rng = np.random.default_rng(4)
    drives, _ = series(rng, 40, sigma=3 * SIGMA)
    for d in drives:
        d.sigma_m = SIGMA  # the drives claim a third of their real scatter
    result = health.wheel_health(model, "rl", drives)
    assert result.sigma_scale == pytest.approx(3.0, rel=0.3)
    assert not result.events


def test_rotation_and_pressure_loss_are_named():
    model = health.HealthModel()
    rng = np.random.default_rng(5)
    rl, _ = series(rng, 20, start=1.950, step_at=8, step_m=+6e-3)
    rr, _ = series(rng, 20, start=1.956, step_at=8, step_m=-6e-3)
    _, events = health.vehicle_health(model, {"rl": rl, "rr": rr})
    assert sorted((e.wheel, e.kind, e.drive_index) for e in events) == \
        [("rl", "rotation", 8), ("rr", "rotation", 8)]
    rl, _ = series(rng, 20, step_at=10, step_m=-3e-3)
    rr, _ = series(rng, 20)
    _, events = health.vehicle_health(model, {"rl": rl, "rr": rr})
    assert [(e.wheel, e.kind, e.drive_index) for e in events] == [("rl", "pressure loss", 10)]


@pytest.fixture(scope="module")
def simulated_fleet(tmp_path_factory):
    """Three vehicles, each with an event, calibrated: (fleet directory, database)."""
    work = tmp_path_factory.mktemp("fleet")
    out, db = work / "fleet", work / "fleet.sqlite"
    assert cli.main(["simulate", "--vehicles", "3", "--drives", "7", "--out", str(out),
                     "--seed", "11", "--event-share", "1", "--laps", "2"]) == 0
    assert cli.main(["run", str(out), "--db", str(db), "--workers", "0"]) == 0
    return out, db


def test_simulated_fleet_events_found_at_their_drives(simulated_fleet, tmp_path):
    out, db = simulated_fleet
    truth = json.loads((out / "fleet_truth.json").read_text())
    drive = out / "car-000" / "drive-000"
    assert "vehicle_id: car-000" in (drive / "vehicle.yaml").read_text()
    assert "odometer_km:" in (drive / "drive.yaml").read_text()
    assert (drive / "gnss.csv").read_text().splitlines()[0].endswith(",speed_mps")
    with sqlite3.connect(db) as connection:
        assert connection.execute("SELECT count(*) FROM drives WHERE odometer_km IS NOT NULL "
                                  "AND start_time IS NOT NULL").fetchone() == (21,)
        calibrated = connection.execute(
            "SELECT d.path, c.circumference_rl_m, c.sigma_rl_m, c.circumference_rr_m, "
            "c.sigma_rr_m FROM calibrations c JOIN drives d USING (drive_key) "
            "WHERE c.usable = 1").fetchall()
    # Every drive usable under the batch's default (tyre_model: auto, the Doppler speed beside
    # the fixes), its circumferences at rest within 3 sigma of the truth.
    assert len(calibrated) == 21
    true_drives = {os.path.join(v["vehicle_id"], d["name"]): d
                   for v in truth["vehicles"] for d in v["drives"]}
    for path, rl, sigma_rl, rr, sigma_rr in calibrated:
        true_drive = true_drives[os.path.relpath(path, out)]
        assert abs(rl - true_drive["circumference_rl_m"]) < 3 * sigma_rl, path
        assert abs(rr - true_drive["circumference_rr_m"]) < 3 * sigma_rr, path
    report_file = tmp_path / "health.json"
    assert cli.main(["health", "--db", str(db), "--json", str(report_file)]) == 0
    report = {v["vehicle_id"]: v for v in json.loads(report_file.read_text())["vehicles"]}
    for vehicle in truth["vehicles"]:
        event = vehicle["event"]
        found = report[vehicle["vehicle_id"]]["events"]
        assert found, f"{vehicle['vehicle_id']}: {event['kind']} not found"
        at = {os.path.basename(e["drive"]) for e in found}
        assert at == {f"drive-{event['drive_index']:03d}"}
        wheels = {e["wheel"] for e in found}
        assert wheels == ({"rl", "rr"} if event["wheel"] == "both" else {event["wheel"]})


def test_a_rear_driven_drive_without_a_doppler_column_is_refused_not_guessed(tmp_path):
    out, db = tmp_path / "fleet", tmp_path / "fleet.sqlite"
    assert cli.main(["simulate", "--vehicles", "1", "--drives", "1", "--out", str(out),
                     "--laps", "2", "--no-doppler"]) == 0
    assert json.loads((out / "fleet_truth.json").read_text())["doppler_sigma_mps"] is None
    gnss = out / "car-000" / "drive-000" / "gnss.csv"
    assert "speed_mps" not in gnss.read_text().splitlines()[0]
    assert cli.main(["run", str(out), "--db", str(db), "--workers", "0"]) == 0
    with sqlite3.connect(db) as connection:
        usable, termination, message = connection.execute(
            "SELECT usable, termination, message FROM calibrations").fetchone()
    assert (usable, termination) == (0, "not_identifiable")
    assert "extrapolation" in message, message


@pytest.mark.skipif(CHROMIUM is None, reason="Debian's chromium is not installed")
def test_fleet_report_loads_in_a_browser_with_every_plot_drawn(simulated_fleet, tmp_path):
    _, db = simulated_fleet
    out = tmp_path / "report"
    assert cli.main(["report", "--db", str(db), "--out", str(out)]) == 0
    pages = sorted(p.name for p in out.glob("vehicle-*.html"))
    assert pages == ["vehicle-car-000.html", "vehicle-car-001.html", "vehicle-car-002.html"]
    index = (out / "index.html").read_text()
    for page in [out / "index.html"] + [out / p for p in pages]:
        text = page.read_text()
        assert not re.search(r"(src|href)=\"(https?:)?//", text)  # offline: nothing fetched
        assert page == out / "index.html" or f'href="{page.name}"' in index
        dom, errors = load(page)
        assert not errors, (page, errors)
        assert dom.count('class="plot-container') == 1 and drawn_plots(dom) == 1, page
    assert "pressure loss" in index or "tyre change" in index or "rotation" in index
    # Written again over itself: replaced whole; into a directory that is not a report: refused.
    assert cli.main(["report", "--db", str(db), "--out", str(out)]) == 0
    other = tmp_path / "other"
    other.mkdir()
    (other / "notes.txt").write_text("mine")
    assert cli.main(["report", "--db", str(db), "--out", str(other)]) == 2
    assert sorted(p.name for p in other.iterdir()) == ["notes.txt"]
