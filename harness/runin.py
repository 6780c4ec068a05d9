"""The run-in: the engine cycles before the tensioner has settled, discarded before the counted ones.

A run starts from the kinetostatic preload. A hydraulic tensioner's chamber then pumps up (the
check valve lets more oil in than the leak lets out until the plunger stands where they balance)
and the tension guide creeps from the static to the dynamic mean of the chain forces; a
spring-damper tensioner creeps too, at the pace of its retraction damping. How long that takes
depends on the drive (the default drive: about 50 ms at 3000 rpm; a single-camshaft drive with a
slack span that long needs more). Counting cycles before it has settled biases every statistic.

The criterion watches the tensioner's stroke (output tensioner.s), one value per engine cycle: its
cycle mean m_j. After cycle j the mean of the last WINDOW cycles is compared with the mean of the
WINDOW before them; the tensioner has settled when they differ by no more than the larger of
  - TREND_SIGMAS standard errors of that difference (the cycle-to-cycle scatter of the later
    window's means, which the chaos of the link model makes; a drift smaller than it cannot be told
    from it; the earlier window's scatter may still hold the transient), and
  - FLOOR_FRACTION of the stroke's mean peak-to-peak over the last WINDOW cycles (the span model's
    cycle means scatter far less than a drift that matters),
and at least `minimum` cycles have passed. A run whose tensioner has not settled within `maximum`
cycles counts its cycles anyway, and the summary says so. Drives without a tensioner take the
minimum.
"""
import dataclasses
import math

import numpy as np

WINDOW = 3            # cycles per mean compared
TREND_SIGMAS = 2.0    # the drift allowed, in standard errors of the difference of the two means
FLOOR_FRACTION = 0.01  # the drift always allowed, of the stroke's cycle peak-to-peak
SIGNAL = "tensioner.s"


@dataclasses.dataclass
class Settling:
    """Where the run-in ended and why: `cycles` discarded; settled False when `maximum` was reached
    with the stroke still drifting (drift and tolerance of the last comparison) [m]."""
    cycles: int
    settled: bool
    drift: float = math.nan
    tolerance: float = math.nan

    def note(self):
        """The summary's line on a run-in that ended without the tensioner settled ("" otherwise)."""
        if self.settled:
            return ""
        return (f"run-in: the tensioner had not settled after {self.cycles} engine cycles (its stroke's cycle mean "
                f"still moved {self.drift * 1e6:.2f} um over {WINDOW} cycles, tolerance {self.tolerance * 1e6:.2f} um); "
                f"the counted cycles include its drift (--run-in CYCLES sets a longer run-in)")

    def json(self):
        return {"runInCycles": self.cycles, "tensionerSettled": self.settled, "strokeDrift_m": self.drift,
                "strokeTolerance_m": self.tolerance}


def drift(means, ptps):
    """(drift, tolerance) [m] of the last 2 WINDOW cycle means and peak-to-peaks (see the module text)."""
    a, b = np.asarray(means[-2 * WINDOW:-WINDOW], float), np.asarray(means[-WINDOW:], float)
    difference = abs(float(b.mean() - a.mean()))
    # (the scatter of the later window only: the earlier one may still hold the transient's trend)
    standard_error = math.sqrt(2.0 * b.var(ddof=1) / WINDOW)
    return difference, max(TREND_SIGMAS * standard_error, FLOOR_FRACTION * float(np.mean(ptps[-WINDOW:])))


class RunIn:
    """Decides the run-in cycle by cycle: feed it each engine cycle's stroke samples (cycle()) until
    it says the run-in has ended; without a tensioner it ends at `minimum`."""

    def __init__(self, minimum, maximum, watches=True):
        self.minimum, self.maximum, self.watches = minimum, max(maximum, minimum), watches
        self.means, self.ptps = [], []
        self.result = None if watches else Settling(minimum, True)

    @property
    def ended(self):
        return self.result is not None

    def cycle(self, stroke):
        """One more engine cycle's stroke samples; returns whether the run-in has ended with it."""
        if self.ended:
            return True
        self.means.append(float(np.mean(stroke)))
        self.ptps.append(float(np.ptp(stroke)))
        j = len(self.means)
        if j >= 2 * WINDOW:
            moved, tolerance = drift(self.means, self.ptps)
            if j >= self.minimum and moved <= tolerance:
                self.result = Settling(j, True, moved, tolerance)
            elif j >= self.maximum:
                self.result = Settling(j, False, moved, tolerance)
        elif j >= self.maximum:
            self.result = Settling(j, False)
        return self.ended


def detect(record, crank, minimum, maximum):
    """The Settling of a complete record (the open loop, a record read back): the run-in its
    cycles give, the cycles from the prescribed sprocket's angle `<crank>.phi`."""
    from .cycle_stats import cycle_spans
    run_in = RunIn(minimum, maximum, SIGNAL in record)
    for i0, i1, _ in cycle_spans(record[crank + ".phi"], 0):
        if run_in.cycle(record[SIGNAL][i0:i1]):
            break
    return run_in.result or Settling(len(run_in.means), False)
