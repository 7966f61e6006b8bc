"""odocal-fleet: calibrate a fleet's drives on Dask and keep the results in SQLite
(docs/fleet.md)."""
