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


def test_the_held_tracks_share_is_shown_where_it_is_worth_naming():
    result = {"method": "batch", "usable": False, "termination": "not_identifiable",
              "circumference_rl_m": 1.95, "circumference_rr_m": 1.95,
              "sigma_circumference_rl_m": 0.0120, "sigma_circumference_rr_m": 0.0124,
              "track_sigma_m": [0.0118, 0.0122], "track_width_uncertainty": 0.01,
              "track_share_worth_naming": True}
    text = dict(summary_rows(result))["track width held"]
    assert text.startswith("11.8 / 12.2 mm of the circumferences' sigma")
    assert "±1 % from vehicle.yaml's" in text
    result["track_sigma_m"] = [5.6e-7, 5.0e-7]  # comma2k19's: fixes and Doppler pin the scale
    result["track_share_worth_naming"] = False
    assert "track width held" not in dict(summary_rows(result))
    del result["track_sigma_m"]
    assert "track width held" not in dict(summary_rows(result))


def test_a_track_under_its_prior_is_named_as_fitted_not_held():
    result = {"method": "batch", "usable": True, "termination": "converged",
              "circumference_rl_m": 1.95, "circumference_rr_m": 1.95,
              "sigma_circumference_rl_m": 0.000086, "sigma_circumference_rr_m": 0.000086,
              "track_sigma_m": [0.0000103, 0.0000106], "track_width_uncertainty": 0.01,
              "track_share_worth_naming": True, "track_under_prior": True}
    rows = dict(summary_rows(result))
    assert "track width held" not in rows
    text = rows["track width under its prior"]
    assert "vehicle.yaml's ±1 %" in text
    assert "sharing 0.0103 / 0.0106 mm" in text


def test_a_held_track_that_the_judge_fitted_under_its_prior_names_the_track_found():
    result = {"method": "iterative", "usable": True, "termination": "converged",
              "circumference_rl_m": 1.95, "circumference_rr_m": 1.95,
              "sigma_circumference_rl_m": 0.00086, "sigma_circumference_rr_m": 0.00086,
              "track_sigma_m": [0.000405, 0.000409], "track_width_uncertainty": 0.01,
              "track_share_worth_naming": True, "track_under_prior": False,
              "judged_track_m": 1.59991, "judged_track_sigma_m": 0.00144}
    text = dict(summary_rows(result))["track width held"]
    assert text.startswith("0.405 / 0.409 mm of the circumferences' sigma")
    assert "puts it at 1.5999 m (1-sigma 0.0014 m)" in text


def test_the_accelerometers_forward_offset_is_shown_as_measured_at_stops_or_over_the_drive():
    result = {"method": "batch", "usable": True, "termination": "converged",
              "circumference_rl_m": 2.299, "circumference_rr_m": 2.300,
              "forward_offset_sigma_m": [0.000194, 0.000198], "forward_offset_sigma_mps2": 0.0425,
              "preparation": {"accelerometer_drive_offset": {
                  "forward_mps2": -0.702, "sigma_mps2": 0.0425, "duration_s": 59.0,
                  "distance_m": 1000.0, "removed": True}}}
    text = dict(summary_rows(result))["accelerometer offset"]
    assert text.startswith("-0.702 m/s² over 59 s of driving (too few stops), 1-sigma 0.043: removed")
    assert "0.194 / 0.198 mm of the circumferences' sigma" in text
    result["preparation"] = {"accelerometer_offset": {"forward_mps2": 0.002, "sigma_mps2": 0.0068,
                                                      "stops": 6, "standing_s": 38.7,
                                                      "removed": False}}
    text = dict(summary_rows(result))["accelerometer offset"]
    assert text.startswith("+0.002 m/s² at 6 stop(s), 1-sigma 0.007: within its noise, left in")
    result["preparation"] = {"accelerometer_driving_offset_mps2": -0.105}
    assert "not measured: it reads -0.105" in dict(summary_rows(result))["accelerometer offset"]
    del result["forward_offset_sigma_m"]
    result["preparation"] = {}
    assert "accelerometer offset" not in dict(summary_rows(result))


def test_the_tyre_models_compared_are_shown_with_whose_gap_the_plain_fit_carries():
    selection = {"plain_bic": 35476.7, "free_track_bic": 35457.4, "plain_track_free": True,
                 "chosen": "none", "judges_plain": False, "plain_gap_to": "physical",
                 "candidates": [{"model": "physical", "bic": 34668.3, "tyre": False,
                                 "circumference_rl_m": 1.98909, "circumference_rr_m": 1.98907},
                                {"model": "extended", "bic": 35448.5, "tyre": False,
                                 "circumference_rl_m": None, "circumference_rr_m": None}]}
    result = {"method": "batch", "usable": False, "termination": "not_identifiable",
              "circumference_rl_m": 1.896, "circumference_rr_m": 1.896,
              "tyre_selection": selection}
    text = dict(summary_rows(result))["tyre model"]
    assert text.startswith("plain, the track width free (plain BIC 35476.7;")
    assert "physical BIC 34668.3, no tyre, at rest 1.9891 / 1.9891 m" in text
    assert "extended BIC 35448.5, no tyre)" in text
    assert text.endswith("carry their gap to the physical fit in their sigma")
    selection.update(chosen="physical", plain_gap_to="", plain_track_free=False)
    selection["candidates"][0]["tyre"] = True
    text = dict(summary_rows(result))["tyre model"]
    assert text.startswith("physical (plain BIC 35476.7; physical BIC 34668.3, at rest")
    assert "gap" not in text
    # The physical terms carrying their gap to the regression terms, their witness.
    selection.update(chosen_gap_to="extended", chosen_gap_sigmas=5.96)
    text = dict(summary_rows(result))["tyre model"]
    assert text.endswith("the physical circumferences carry their gap to the extended fit "
                         "(6.0 of their combined sigma away) in their sigma")
    # A tyre fit that held every coefficient, whose gap the plain fit carries.
    selection.update(chosen="none", chosen_gap_to="", plain_gap_to="physical")
    selection["candidates"][0]["every_coefficient_held"] = True
    text = dict(summary_rows(result))["tyre model"]
    assert "physical BIC 34668.3, every coefficient held, at rest" in text
    assert text.endswith("carry their gap to the physical fit in their sigma")
    # A tyre fit a little worse than the plain fit with the track free: the criteria's share.
    selection["candidates"][0].update(every_coefficient_held=False, tyre=True, bic=35459.0)
    selection["plain_gap_share"] = 0.4727
    text = dict(summary_rows(result))["tyre model"]
    assert text.endswith("carry 0.47 of their gap, the share that the criteria weigh (it fits "
                         "the log about as well), to the physical fit in their sigma")
    selection["plain_gap_share"] = 1.0  # a better fit: all of it
    assert dict(summary_rows(result))["tyre model"].endswith(
        "carry their gap to the physical fit in their sigma")
    # A tyre fit that wandered under the configured noise, judging by its fit under the noise shown.
    selection["candidates"][0]["judged_under_noise_shown"] = True
    assert "physical BIC 35459.0, judged under the GNSS noise shown, at rest" in dict(
        summary_rows(result))["tyre model"]
    del result["tyre_selection"]
    assert "tyre model" not in dict(summary_rows(result))


def test_a_latency_found_is_shown_with_what_it_moved():
    result = {"method": "batch", "usable": True, "termination": "converged",
              "circumference_rl_m": 2.29606, "circumference_rr_m": 2.29719,
              "latency_detection": {"residual": "Doppler speed", "correlation": -0.891,
                                    "latency_s": 0.1018, "sigma_s": 0.0043, "taken": True,
                                    "circumference_without_m": [2.28917, 2.29038]}}
    text = dict(summary_rows(result))["latency"]
    assert text.startswith("the fit without it left the Doppler speed residual following")
    assert "(rho = -0.89)" in text
    assert "the GNSS fixes lag the wheels by 101.8 ms (1-sigma 4.3 ms)" in text
    assert text.endswith("by +6.89 / +6.81 mm to these")
    result["latency_detection"].update(by_doppler_noise=True, doppler_sigma_scale=5.52)
    assert dict(summary_rows(result))["latency"].startswith(
        "the fit without it left the Doppler speed's noise 5.5 times the configured; estimated")
    result["latency_detection"].update(taken=False, significant=True,
                                       doppler_sigma_scale_with=14.04)
    assert dict(summary_rows(result))["latency"].endswith(
        "but the Doppler speed's noise stays 14.0 times the configured with it: not a lag's, "
        "kept without the latency")
    result["latency_detection"].update(by_doppler_noise=False, by_gnss_noise=True,
                                       gnss_sigma_scale=47.6, gnss_sigma_scale_with=3.14)
    text = dict(summary_rows(result))["latency"]
    assert text.startswith("the fit without it left the GNSS fixes' residuals 47.6 times their "
                           "configured noise; estimated")
    assert text.endswith("but the fixes' residuals stay 3.1 times the configured with it: not a "
                         "lag's alone, kept without the latency")
    result["latency_detection"].update(by_gnss_noise=False, significant=False)
    result["latency_detection"].update(taken=False, latency_s=-0.0012, sigma_s=0.001)
    assert dict(summary_rows(result))["latency"].endswith(
        "-1.2 ms (1-sigma 1.0 ms), not significant: kept without the latency")
    del result["latency_detection"]
    assert "latency" not in dict(summary_rows(result))


def test_a_mounting_found_is_shown_with_what_it_moved():
    result = {"method": "batch", "usable": True, "termination": "converged",
              "circumference_rl_m": 1.964206, "circumference_rr_m": 1.964200,
              "mounting_detection": {
                  "signature": {"gnss_mean_m": [-0.004, 0.208], "doppler_left_m": 0.49},
                  "lever_arm_m": [0.057, 0.501], "lever_arm_sigma_m": [0.048, 0.005],
                  "fitted": True, "taken": True,
                  "circumference_without_m": [1.959226, 1.959220]}}
    text = dict(summary_rows(result))["mounting"]
    assert text.startswith("the fit without them left the GNSS fixes -0.00 m ahead and +0.21 m "
                           "left of the fitted path, the Doppler speed as from +0.49 m left")
    assert "the antenna +0.057 m ahead (1-sigma 0.048) and +0.501 m left (1-sigma 0.005)" in text
    assert text.endswith("by +4.98 / +4.98 mm")
    # A latency found after it moved the result again: the row says what the mounting moved.
    result["mounting_detection"]["circumference_with_m"] = [1.961226, 1.961220]
    assert dict(summary_rows(result))["mounting"].endswith("by +2 / +2 mm")
    del result["mounting_detection"]["circumference_with_m"]
    result["mounting_detection"].update(taken=False, explained_by_latency=True)
    assert dict(summary_rows(result))["mounting"].endswith("the lag showed as it, kept without")
    result["mounting_detection"].update(taken=True, explained_by_latency=False)
    detection = result["mounting_detection"]
    detection.update(heading_bias_rad=0.0503, heading_bias_sigma_rad=0.0013, taken=False)
    detection["signature"]["heading_mean_rad"] = 0.0438
    text = dict(summary_rows(result))["mounting"]
    assert "; heading.csv +2.51 deg off the fitted heading" in text
    assert "heading.csv reading +2.88 deg (1-sigma 0.07) beyond the heading" in text
    assert text.endswith("not significant: kept without")
    detection["fitted"] = False
    assert dict(summary_rows(result))["mounting"].endswith("did not stand: kept without")
    del result["mounting_detection"]
    assert "mounting" not in dict(summary_rows(result))


def test_a_lever_arm_found_by_the_fixes_noise_says_so():
    result = {"method": "batch", "usable": True, "termination": "converged",
              "circumference_rl_m": 1.964103, "circumference_rr_m": 1.964123,
              "mounting_detection": {
                  "signature": {"gnss_mean_m": [0.01, -0.02]},
                  "lever_arm_m": [-0.232, -0.480], "lever_arm_sigma_m": [0.007, 0.001],
                  "fitted": True, "taken": True, "by_gnss_noise": True,
                  "gnss_sigma_scale_without": 1.38, "gnss_sigma_scale_with": 1.01,
                  "circumference_without_m": [1.957477, 1.957489],
                  "circumference_with_m": [1.964118, 1.964129]}}
    text = dict(summary_rows(result))["mounting"]
    assert text.startswith("the fit without them left the GNSS fixes' residuals 1.4 times their "
                           "configured noise (their means showed no antenna)")
    assert "of the rear axle's centre, which leaves the fixes 1.0 times" in text
    assert text.endswith("by +6.64 / +6.64 mm")
    # Beside a latency whose fit alone left the fixes wide: both found, the row says so.
    detection = result["mounting_detection"]
    detection.update(by_gnss_noise=False, found_beside_latency=True, gnss_sigma_scale_without=1.4)
    text = dict(summary_rows(result))["mounting"]
    assert text.startswith("the latency's fit alone left the GNSS fixes' residuals 1.4 times")
    assert "estimated beside it: the antenna -0.232 m ahead" in text
    assert text.endswith("with the latency these leave them 1.0 times and move the "
                         "circumferences by +6.64 / +6.64 mm")


def test_a_heading_found_after_the_others_says_so():
    after = {"beside_latency": True, "seen_rad": 0.0673, "seen_standard_error_rad": 0.0013,
             "circumference_without_m": [1.964038, 1.964104],
             "circumference_with_m": [1.964048, 1.964110]}
    result = {"method": "batch", "usable": True, "termination": "converged",
              "circumference_rl_m": 1.964048, "circumference_rr_m": 1.964110,
              "mounting_detection": {
                  "signature": {"heading_mean_rad": 0.0056},
                  "lever_arm_m": [2.807, 0.578], "lever_arm_sigma_m": [0.007, 0.002],
                  "heading_bias_rad": 0.0711, "heading_bias_sigma_rad": 0.0012,
                  "fitted": True, "taken": True, "found_beside_latency": True,
                  "gnss_sigma_scale_without": 3.9, "gnss_sigma_scale_with": 1.1,
                  "circumference_without_m": [1.954568, 1.954590],
                  "circumference_with_m": [1.964038, 1.964104], "heading_after": after}}
    text = dict(summary_rows(result))["mounting"]
    # The antenna's part as found beside the lag, without the heading the first look did not show.
    assert text.startswith("the latency's fit alone left the GNSS fixes' residuals 3.9 times")
    assert "; then the fit with the antenna and the latency left heading.csv +3.86 deg off" in text
    assert "heading.csv reading +4.07 deg (1-sigma 0.07)" in text
    assert text.count("heading.csv reading") == 1
    assert text.endswith("which moves the circumferences by +0.01 / +0.006 mm")
    # Found after a latency alone: the row is the heading's only.
    del result["mounting_detection"]["lever_arm_m"]
    text = dict(summary_rows(result))["mounting"]
    assert text.startswith("the fit with the latency left heading.csv +3.86 deg")
