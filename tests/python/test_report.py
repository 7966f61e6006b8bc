"""odocal report in a real browser: headless Chromium (Debian's chromium) loads the page made
for a simulated calibration; any JavaScript error or an empty plot fails the test. The checker
is shown to catch both on pages broken on purpose."""
import os
import re
import shutil
import subprocess

import pytest

ODOCAL = os.environ["ODOCAL_CLI"]
CHROMIUM = shutil.which("chromium")

pytestmark = pytest.mark.skipif(CHROMIUM is None, reason="Debian's chromium is not installed")


def load(page):
    """The DOM after the page's scripts ran, and the console errors."""
    run = subprocess.run([CHROMIUM, "--headless", "--no-sandbox", "--disable-gpu",
                          "--enable-logging=stderr", "--v=0", "--virtual-time-budget=10000",
                          "--dump-dom", f"file://{page}"],
                         capture_output=True, text=True, timeout=120)
    errors = [line for line in run.stderr.splitlines()
              if "CONSOLE" in line and ("Uncaught" in line or "Error" in line)]
    return run.stdout, errors


def drawn_plots(dom):
    """Plots with data drawn: a path with points inside a trace of the plot area (the legend,
    which has sample lines of its own, left out)."""
    plots = dom.split('class="plot-container')[1:]
    area = [p.split('class="legend"')[0] for p in plots]
    return sum(1 for a in area if re.search(r'class="trace[^"]*".*?<path[^>]* d="M[0-9.]', a, re.S))


def test_the_checker_catches_errors_and_empty_plots(tmp_path):
    broken = tmp_path / "broken.html"
    broken.write_text("<html><body><script>throw new Error('boom')</script></body></html>")
    assert load(broken)[1], "a thrown error must show"
    dom = ('<div class="plot-container"><g class="trace scatter"><path class="js-line" d="M1,2L3,4">'
           '</path></g></div><div class="plot-container"><g class="legend"><path d="M5,0h30">'
           '</path></g></div>')
    assert drawn_plots(dom) == 1, "a plot with only its legend is empty"


@pytest.fixture(scope="module")
def report(tmp_path_factory):
    work = tmp_path_factory.mktemp("report")
    log, result, page = work / "log", work / "result.json", work / "report.html"
    subprocess.run([ODOCAL, "simulate", "--ideal", "--laps", "1", "--wear-rl", "1.5", "--out",
                    str(log)], check=True, stdout=subprocess.DEVNULL)
    subprocess.run([ODOCAL, "calibrate", str(log), "--json", str(result)], check=True,
                   stdout=subprocess.DEVNULL)
    run = subprocess.run([ODOCAL, "report", str(result), "--log", str(log), "--out", str(page)],
                         capture_output=True, text=True)
    assert run.returncode == 0, run.stderr
    return page


def test_the_report_loads_without_errors_and_draws_every_plot(report):
    text = report.read_text()
    assert not re.search(r"<(script|link)[^>]+(src|href)=", text)  # offline: nothing fetched
    for heading in ("Result", "Input checks", "Held-out drift", "Configuration"):
        assert f"<h2>{heading}" in text
    assert "reference&#x27;s own uncertainty" in text  # beside the drifts it bounds (escaped)
    dom, errors = load(report)
    assert not errors, errors
    assert dom.count('class="plot-container') == 4  # track, drift windows, conditions, iterations
    assert drawn_plots(dom) == 4


def test_a_bad_result_file_is_an_error(tmp_path):
    bad = tmp_path / "bad.json"
    bad.write_text("{}")
    run = subprocess.run([ODOCAL, "report", str(bad), "--log", str(tmp_path), "--out",
                          str(tmp_path / "x.html")], capture_output=True, text=True)
    assert run.returncode == 2 and "not an odocal calibrate --json result" in run.stderr
    assert not (tmp_path / "x.html").exists()
