"""Plots engineers read (plots) and the picture of a drive (drive_picture). Every plot is drawn
with matplotlib's Agg backend: import pyplot as `from harness.plots import plt`."""
import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402,F401
