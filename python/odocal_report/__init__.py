"""odocal report: one calibration as a static HTML page (docs/reports.md)."""
