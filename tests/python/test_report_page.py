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
