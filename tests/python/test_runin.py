"""The run-in detection (harness/runin.py) on strokes with a known answer: a tensioner pumping up
as an exponential approach with chaotic scatter ends its run-in once the drift is below the
scatter, not before and not long after; a drift that never stops is reported; a drive without a
tensioner takes the minimum; a record read back gives the loop's answer."""
import math

import numpy as np
import pytest

from harness import cycle_stats, runin

SAMPLES = 200  # per engine cycle


def strokes(cycles, settle_cycles=3.0, jump=1.2e-3, scatter=5e-5, ripple=2.5e-4, seed=1):
    """Per-cycle stroke samples: s = 4.4 mm - jump exp(-cycle / settle_cycles) plus a ripple within
    the cycle and a chaotic cycle-to-cycle scatter of the mean."""
    rng = np.random.default_rng(seed)
    out = []
    for j in range(cycles):
        x = j + np.linspace(0.0, 1.0, SAMPLES)
        mean = 4.4e-3 - jump * np.exp(-x / settle_cycles) + scatter * rng.standard_normal()
        out.append(mean + ripple * np.sin(2.0 * np.pi * 8.0 * x))
    return out


def run_in_of(samples, minimum=4, maximum=60):
    r = runin.RunIn(minimum, maximum)
    for s in samples:
        if r.cycle(s):
            break
    return r.result


def test_a_pumping_tensioner_settles_once_its_drift_is_below_the_scatter():
    found = run_in_of(strokes(60))
    assert found.settled and found.drift <= found.tolerance
    # the drift of the cycle means between two windows of 3 cycles falls below twice the scatter's
    # standard error (2 x 5e-5 x sqrt(2/3) = 8e-5 m) where 1.2 mm exp(-j/3) (1 - exp(-1)) is that
    # small: j = 3 ln(1.2e-3 0.632 / 8e-5) = 6.7 cycles, and the later window ends 3 cycles on
    assert 7 <= found.cycles <= 14


def test_the_run_in_lasts_at_least_its_minimum():
    assert run_in_of(strokes(60, jump=0.0), minimum=9).cycles == 9


def test_a_stroke_that_keeps_drifting_is_reported_at_the_maximum():
    ramp = [np.full(SAMPLES, 1e-3 + 1e-4 * j) for j in range(40)]
    found = run_in_of(ramp, maximum=20)
    assert not found.settled and found.cycles == 20
    assert found.drift == pytest.approx(3e-4) and "had not settled after 20 engine cycles" in found.note()
    assert run_in_of(strokes(60)).note() == ""


def test_a_deterministic_stroke_settles_by_the_floor():
    """The span model's cycle means scatter little: the floor (1 % of the stroke's ripple) decides."""
    found = run_in_of(strokes(60, scatter=0.0))
    assert found.settled and found.tolerance == pytest.approx(0.01 * 5e-4, rel=0.02)


def test_without_a_tensioner_the_run_in_is_the_minimum():
    r = runin.RunIn(5, 40, watches=False)
    assert r.ended and r.result == runin.Settling(5, True)


def test_a_record_read_back_gives_the_loops_answer():
    samples = strokes(30)
    phi = np.concatenate([j * cycle_stats.ENGINE_CYCLE + np.linspace(0.0, cycle_stats.ENGINE_CYCLE, SAMPLES)[:-1]
                          for j in range(30)] + [[30 * cycle_stats.ENGINE_CYCLE]])
    stroke = np.concatenate([s[:-1] for s in samples] + [samples[-1][-1:]])
    # (the record's cycles share their boundary sample, as cycle_spans gives them)
    record = {"crankshaft.phi": phi, "tensioner.s": stroke}
    loop = runin.RunIn(4, 30)
    for i0, i1, _ in cycle_stats.cycle_spans(phi, 0):
        if loop.cycle(stroke[i0:i1]):
            break
    assert runin.detect(record, "crankshaft", 4, 30) == loop.result
    assert not math.isnan(loop.result.drift)
