"""The report page's result table: what it shows of a calibration's JSON."""

from odocal_report.page import summary_rows


def test_a_widened_sigma_is_shown_with_its_cause():
    result = {"method": "batch", "usable": False, "termination": "not_identifiable",
              "circumference_rl_m": 1.97, "circumference_rr_m": 1.98,
              "model_adequacy": {"verdict": "does not explain", "chi2_per_dof": 81.25},
              "misfit_sigma_scale": 9.01}
    rows = dict(summary_rows(result))
    assert rows["sigma widened"].startswith("x9.01:")
    assert "chi2/dof 81.2" in rows["sigma widened"]
    result["misfit_sigma_scale"] = 1.0
    assert "sigma widened" not in dict(summary_rows(result))


def test_the_accelerometer_walk_is_shown_where_a_tyre_model_has_one():
    result = {"method": "batch", "usable": True, "termination": "converged",
              "circumference_rl_m": 1.97, "circumference_rr_m": 1.98,
              "accelerometer_walk": {"noise_x_mps2": 0.208, "noise_y_mps2": 0.199,
                                     "heading_deg": 2.0725}}
    rows = dict(summary_rows(result))
    assert rows["accelerometer noise"].startswith("0.208 / 0.199 m/s²")
    assert "by 2.07 deg" in rows["accelerometer noise"]
    result["accelerometer_walk"]["heading_deg"] = 0.0  # the plain model
    assert "accelerometer noise" not in dict(summary_rows(result))
