"""Plots engineers read (plots) and the picture of a drive (drive_picture). Every plot is drawn
with matplotlib's Agg backend: import pyplot as `from harness.plots import plt`.

matplotlib (with pyplot half a second and more) is imported at the first use of plt, not with the
package: a command that only reads its options, or refuses them, answers without it."""
import importlib


class _Pyplot:
    """matplotlib.pyplot on the Agg backend, imported at the first attribute asked for."""

    def __getattr__(self, name):
        matplotlib = importlib.import_module("matplotlib")
        matplotlib.use("Agg")
        return getattr(importlib.import_module("matplotlib.pyplot"), name)


plt = _Pyplot()
