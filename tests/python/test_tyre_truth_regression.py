"""tools/tyre_truth_regression.py's true factors against a closed form: a car on a circle whose
wheels roll a known fraction farther per revolution than their circumference says. A fast turn
is where a window's chord falls short of its arc, which once biased every factor."""
import importlib.util
import os

import numpy as np

SPEC = importlib.util.spec_from_file_location(
    "tyre_truth_regression",
    os.path.join(os.environ["ODOCAL_SOURCE_DIR"], "tools", "tyre_truth_regression.py"))
TOOL = importlib.util.module_from_spec(SPEC)
SPEC.loader.exec_module(TOOL)


def circle_log(radius, speed, factors, circumferences, track, seconds=10.0, rate=50.0):
    """truth.csv and wheels.csv rows (wheel angles in rad) of a counter-clockwise circle."""
    t = np.arange(0.0, seconds, 1.0 / rate)
    heading = speed / radius * t
    truth = np.column_stack([t, radius * np.sin(heading), radius * (1.0 - np.cos(heading)),
                             heading])
    angle = [2 * np.pi * (radius + side * track / 2) * heading / (c * (1.0 + f))
             for side, f, c in zip((-1.0, 1.0), factors, circumferences)]
    return truth, np.column_stack([t, angle[0], angle[1]])


def test_factors_of_a_fast_turn_are_the_wheels_own():
    circumferences, track, factors = (1.95, 1.96), 1.6, (-0.012, 0.004)
    # 50 m/s on a 100 m radius: a quarter of a radian per 0.5 s window.
    truth, wheels = circle_log(100.0, 50.0, factors, circumferences, track)
    _, _, dt, along, turn, revs_left, revs_right = TOOL.window_motion(truth, wheels, 25)
    assert np.allclose(turn, 0.25, atol=1e-9)
    assert np.allclose(along / dt, 50.0, rtol=1e-4)
    left, right = TOOL.true_factors(along, turn, revs_left, revs_right, circumferences, track)
    # The chord alone would be 2.6e-3 short (0.25^2 / 24); the sum of 0.01 rad steps is 4e-6.
    assert np.max(np.abs(left - factors[0])) < 1e-4
    assert np.max(np.abs(right - factors[1])) < 1e-4


def test_straight_driving_has_no_turn_and_the_exact_factors():
    circumferences, track, factors = (1.95, 1.96), 1.6, (0.02, -0.03)
    truth, wheels = circle_log(1e9, 20.0, factors, circumferences, track)
    _, _, _, along, turn, revs_left, revs_right = TOOL.window_motion(truth, wheels, 10)
    left, right = TOOL.true_factors(along, turn, revs_left, revs_right, circumferences, track)
    assert np.max(np.abs(turn)) < 1e-6
    assert np.allclose(left, factors[0], atol=1e-6)
    assert np.allclose(right, factors[1], atol=1e-6)
