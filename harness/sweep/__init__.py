"""Speed sweeps and run-ups of a drive through ChainDrive.fmu, run as independent cases on Dask
(harness/sweep/sweep.py is the command, python -m harness sweep or python -m harness.sweep)."""
