"""The odocal Python module against the same truths as the C++ tests: a simulated drive with
known wear, the shipped figure-eight example, odocal's own error messages."""
import gc
import math
import os

import numpy as np
import pytest

import odocal

SOURCE = os.environ.get("ODOCAL_SOURCE_DIR", os.path.join(os.path.dirname(__file__), "..", ".."))
EXAMPLE = os.path.join(SOURCE, "examples", "figure-eight")
NOMINAL = 2 * math.pi * 0.3126


@pytest.fixture(scope="module")
def worn():
    # One ideal lap of the circuit, rear tyres worn 1.5 / 1.0 mm of radius.
    return odocal.simulate("circuit", ideal=True, laps=1, wear_rl_mm=1.5, wear_rr_mm=1.0)


def test_streams_are_views_without_copies(worn):
    t = worn.wheels.t_s
    assert isinstance(t, np.ndarray) and t.dtype == np.float64
    assert not t.flags.owndata and not t.flags.writeable
    assert np.shares_memory(t, worn.wheels.t_s)  # the same C++ vector each time
    assert len(t) == len(worn.wheels) > 10_000
    assert np.all(np.diff(t) > 0)
    assert len(worn.gnss.x_m) == len(worn.gnss)
    assert worn.imu is not None and len(worn.imu.wz_radps) == len(worn.imu)


def test_the_drive_force_column_is_a_view_where_the_log_has_it(worn, tmp_path):
    assert len(worn.wheels.drive_force_n) == 0  # no column: empty
    circuit = open(os.path.join(SOURCE, "config", "scenarios", "circuit.yaml")).read()
    scenario = tmp_path / "forced.yaml"
    scenario.write_text(circuit.replace("drive_force_sigma_n: -1", "drive_force_sigma_n: 100"))
    forced = odocal.simulate(str(scenario), laps=1)
    force = forced.wheels.drive_force_n
    assert len(force) == len(forced.wheels) and not force.flags.owndata
    # The car accelerates out of its first standing second and brakes into the hairpin.
    assert force.max() > 1000 and force.min() < -1000


def test_an_array_keeps_its_log_alive():
    rev = odocal.simulate("circuit", ideal=True, laps=1).wheels.rev_rl
    gc.collect()
    assert math.isfinite(float(rev.sum())) and rev.sum() > 100


@pytest.mark.parametrize("method", ["iterative", "fixed-p", "augmented", "batch"])
def test_every_method_finds_the_wear(worn, method):
    result = odocal.calibrate(worn, method=method)
    assert result.method == method
    assert result.usable, result.full_report()
    truth = (2 * math.pi * (0.3126 - 0.0015), 2 * math.pi * (0.3126 - 0.0010))
    for estimate, sigma, true in ((result.circumference_rl_m, result.sigma_rl_m, truth[0]),
                                  (result.circumference_rr_m, result.sigma_rr_m, truth[1])):
        assert abs(estimate - true) < max(5 * sigma, 0.002), result.full_report()
    assert result.covariance.shape == (2, 2)
    as_json = result.to_dict()
    assert as_json["usable"] is True and as_json["method"] == method
    # Worn tyres: the estimate dead-reckons better than the nominal, no caution goes with it.
    assert result.note == "" and as_json["note"] == ""
    # Every method says whether the two-wheel model explains the (ideal) log.
    assert as_json["model_adequacy"]["explains"] is True, as_json["model_adequacy"]["verdict"]
    assert as_json["model_adequacy"]["verdict"].startswith("the two-wheel model explains this log")


def test_options_are_the_config_files_keys(worn):
    result = odocal.calibrate(worn, method="batch", options={"batch": {"estimate_track_width": True}})
    names = [p["name"] for p in result.to_dict()["parameters"] if p["estimated"]]
    assert "track_width_m" in names
    with pytest.raises(odocal.InputError, match="colour"):
        odocal.calibrate(worn, options={"colour": "red"})
    with pytest.raises(ValueError, match="unknown method"):
        odocal.calibrate(worn, method="magic")


def test_tyre_model_options_and_coefficients(worn):
    plain = odocal.calibrate(worn, method="batch")
    regression = {"k_speed_s2pm2", "k_lateral_s2pm", "k_drive_s2pm", "k_brake_s2pm",
                  "k_turn_s2prad2", "k_drive_lateral_s4pm2", "k_brake_lateral_s4pm2"}
    physical = {"k_load_s2pm", "k_drive_slip", "k_brake_slip", "k_side_slip_s2pm"}
    assert set(plain.tyre_model) == regression | physical
    assert all(k == 0.0 for k in plain.tyre_model.values())
    for choice, family in (("extended", regression), ("physical", physical)):
        fitted = odocal.calibrate(worn, method="batch", options={"batch": {"tyre_model": choice}})
        tyre = {p["name"]: p for p in fitted.to_dict()["parameters"] if p["name"].startswith("tyre_")}
        assert len(tyre) == 11
        assert {"k" + name[4:] for name, p in tyre.items() if p["estimated"]} == family
        for name, p in tyre.items():
            assert fitted.tyre_model["k" + name[4:]] == p["value"]
            if not p["estimated"]:
                assert p["value"] == 0.0
        if choice == "extended":
            # Every coefficient is either identified or held at zero with a verdict that says why.
            for p in tyre.values():
                assert not p["estimated"] or p["identified"] or (
                    p["value"] == 0.0 and "held at zero" in p["verdict"]), p
    with pytest.raises(odocal.InputError, match="tyre_model"):
        odocal.calibrate(worn, method="batch", options={"batch": {"tyre_model": "magic"}})


def test_doctor_validate_and_dead_reckon(worn):
    assert odocal.doctor(EXAMPLE) == [] or all(f["severity"] != "blocking" for f in odocal.doctor(EXAMPLE))
    assert all(f["severity"] != "blocking" for f in odocal.doctor(worn))
    result = odocal.calibrate(worn)
    drift = odocal.validate(worn, result, window_s=60)
    assert drift["calibrated"]["windows"] > 0
    assert drift["calibrated"]["median_drift_percent"] < drift["nominal"]["median_drift_percent"]
    # What the reference's own uncertainty alone would show, and each window's share of it.
    floor = drift["reference_uncertainty"]
    assert 0 < floor["median_end_error_m"] < drift["nominal"]["median_end_error_m"]
    assert all(w["reference_rms_m"] > 0 for w in drift["windows"])
    # The tick counts as they are: the same windows, dead-reckoned with their quantisation.
    raw = odocal.validate(worn, result, window_s=60, tick_smoothing_s=0)
    assert raw["calibrated"]["windows"] == drift["calibrated"]["windows"]
    assert raw["calibrated"]["median_end_error_m"] != drift["calibrated"]["median_end_error_m"]
    track = odocal.dead_reckon(worn, result)
    assert len(track["x_m"]) == len(worn.wheels)
    assert np.all(np.isfinite(track["yaw_rad"]))


def _end_gap(a, b):
    return math.hypot(a["x_m"][-1] - b["x_m"][-1], a["y_m"][-1] - b["y_m"][-1])


def test_dead_reckoning_takes_the_accelerometer_as_the_calibration_did(tmp_path):
    # A tyre model takes ax for drive force, fitted on the log as every command prepares it (its
    # forward offset taken out). The shipped example with a tyre model in its vehicle.yaml, once
    # as logged and once with ax 1 m/s^2 low (a phone pitched by 6 deg): prepared, the two dead
    # reckonings end 0.26 m apart, where the offset the drive measures leaves them (its
    # +0.08 m/s^2 within its noise is left in the one and taken out with the 1 from the other);
    # as logged, 1.69 m apart.
    logs = []
    for name, added in (("as-logged", 0.0), ("pitched", -1.0)):
        directory = tmp_path / name
        directory.mkdir()
        for f in os.listdir(EXAMPLE):
            text = open(os.path.join(EXAMPLE, f)).read()
            if f == "vehicle.yaml":
                text += "tyre_model: {k_load_s2pm: 0.0019, k_drive_slip: 0.05, k_brake_slip: 0.0175}\n"
            if f == "imu.csv":
                rows = text.splitlines()
                cells = [row.split(",") for row in rows[1:]]
                text = "\n".join([rows[0]] + [",".join([c[0], f"{float(c[1]) + added:.5f}"] + c[2:])
                                               for c in cells]) + "\n"
            (directory / f).write_text(text)
        logs.append(odocal.read_log(str(directory)))
    prepared = [odocal.dead_reckon(log) for log in logs]
    raw = [odocal.dead_reckon(log, prepare=False) for log in logs]
    assert "forward offset removed" in prepared[1]["prepared"]
    assert "forward offset within its noise" in prepared[0]["prepared"]
    assert _end_gap(*raw) > 1.5
    assert _end_gap(*prepared) < 0.2 * _end_gap(*raw)


def test_the_sensors_places_are_vehicle_yamls(tmp_path):
    log = odocal.read_log(EXAMPLE)
    assert log.vehicle.gnss_x_m is None and log.vehicle.gnss_y_m is None
    directory = tmp_path / "mounted"
    directory.mkdir()
    for f in os.listdir(EXAMPLE):
        text = open(os.path.join(EXAMPLE, f)).read()
        if f == "vehicle.yaml":
            text += "gnss_x_m: 1.5\ngnss_y_m: -0.4\nimu_x_m: 0.7\n"
        (directory / f).write_text(text)
    mounted = odocal.read_log(str(directory))
    assert (mounted.vehicle.gnss_x_m, mounted.vehicle.gnss_y_m) == (1.5, -0.4)
    assert (mounted.vehicle.imu_x_m, mounted.vehicle.imu_y_m) == (0.7, 0.0)


def test_the_batch_finds_an_antenna_and_validate_takes_it(tmp_path):
    # The urban drive with a Doppler column and its antenna 0.5 m left of the axle, unstated.
    scenario = tmp_path / "urban-antenna.yaml"
    scenario.write_text(open(os.path.join(SOURCE, "config", "scenarios", "urban.yaml")).read()
                        + "sensors:\n  gnss:\n    speed_sigma_mps: 0.05\n    lever_arm_y_m: 0.5\n")
    log = odocal.simulate(str(scenario))
    batch = odocal.calibrate(log, "batch")
    assert batch.antenna_m is not None
    assert batch.antenna_m[1] == pytest.approx(0.5, abs=0.05)
    assert odocal.calibrate(log, "iterative").antenna_m is None
    # The reference through the found antenna is not the one through the axle.
    numbers = (batch.circumference_rl_m, batch.circumference_rr_m, batch.track_width_m)
    through_antenna = odocal.validate(log, batch)["windows"]
    through_axle = odocal.validate(log, numbers)["windows"]
    assert [w["calibrated_end_error_m"] for w in through_antenna] != \
        [w["calibrated_end_error_m"] for w in through_axle]


def test_read_log_and_its_errors():
    log = odocal.read_log(EXAMPLE)
    assert log.vehicle.track_width_m == pytest.approx(1.6)
    assert len(log.wheels) > 0 and log.heading is not None
    with pytest.raises(odocal.InputError, match="nonexistent"):
        odocal.read_log("/nonexistent-log")
