"""The plots agree with the numbers: the spectra's bars are the summary's order amplitudes, the
cycle statistics show every headline quantity, the link's revolution lies on the chain path 0..L,
the run-up's order cuts carry the summary's confidence intervals of blocks of cycles."""
import dataclasses
import math

import numpy as np
import pytest

from harness import cycle_stats
from harness.cvt import plots as cvt_plots
from harness.drive.description import elements, geometry
from harness.plots import plots
from harness.sweep import results

MESHING = 21
DRIVE = dataclasses.replace(elements(), hydraulic=False)  # the default drive's elements, its record without a chamber
RUN_IN, COUNTED = 1, 4


def synthetic_record(cycles=6, samples_per_cycle=800, seed=3):
    """A record of the timing drive's outputs over whole engine cycles: the crankshaft speed
    fluctuating, the tensioner force and the guide angle made of engine orders whose amplitudes
    change from cycle to cycle, noise on top (so that every order has a spread and an interval)."""
    rng = np.random.default_rng(seed)
    n = cycles * samples_per_cycle + 1
    t = np.linspace(0.0, cycles * 0.04, n)
    phi = 314.159 * t + 0.05 * np.sin(2.0 * math.pi * 100.0 * t)  # 3000 rpm with a 2nd-order fluctuation
    cycle = np.floor(phi / cycle_stats.ENGINE_CYCLE)
    amplitude = {k: a * (1.0 + 0.2 * rng.standard_normal(cycles + 1)) for k, a in ((2, 30.0), (6, 20.0), (8, 45.0),
                                                                                   (MESHING, 5.0))}
    force = 85.0 + sum(a[cycle.astype(int)] * np.cos(k * phi + 0.3 * k) for k, a in amplitude.items())
    return {"time": t, "crankshaft.phi": phi, "tensioner.F": force + rng.normal(0.0, 2.0, n),
            "tensionGuide.phi": 0.02 + 3e-4 * np.cos(2.0 * phi) + rng.normal(0.0, 2e-5, n),
            "chain.Ftight": 450.0 + rng.normal(0.0, 20.0, n), "chain.Fslack": 340.0 + rng.normal(0.0, 20.0, n),
            "camshaftIntake.phi": 0.5 * phi + rng.normal(0.0, 1e-4, n),
            "camshaftExhaust.phi": 0.5 * phi + rng.normal(0.0, 1e-4, n)}


def test_spectra_bars_are_the_summary_amplitudes(tmp_path):
    d = synthetic_record()
    summary = cycle_stats.summarize(cycle_stats.per_cycle(d, RUN_IN, DRIVE, COUNTED))
    spans = cycle_stats.counted_spans(d["crankshaft.phi"], RUN_IN, COUNTED)
    drawn = plots.spectra(tmp_path / "spectra.png", d, spans, DRIVE, "synthetic")
    for name, keys in cycle_stats.order_keys(list(summary)).items():
        orders, heights = drawn[name]
        for order, key in zip(list(cycle_stats.ORDERS) + [MESHING], keys):
            # the same crank-angle resampling and the same mean: equal to the last bit
            assert heights[list(orders).index(order)] == summary[key]["mean"], key
    assert drawn["tensioner.F"][1][list(drawn["tensioner.F"][0]).index(8)] == pytest.approx(45.0, rel=0.25)
    assert (tmp_path / "spectra.png").stat().st_size > 10000


def test_cycle_statistics_show_every_headline_quantity(tmp_path):
    d = synthetic_record()
    per_cycle = cycle_stats.per_cycle(d, RUN_IN, DRIVE, COUNTED)
    drawn = plots.cycle_statistics(tmp_path / "cycle_statistics.png", per_cycle, cycle_stats.summarize(per_cycle),
                                   "synthetic")
    assert sorted(drawn) == sorted(cycle_stats.headline_keys(DRIVE)) and len(drawn) == 17


def link_along_the_path(g, start, revolutions, samples=3000):
    """A record of a link travelling along the nominal chain path from arc length `start` over
    `revolutions`, its contact forces zero (as the span fidelity's)."""
    path = np.array(g["path"])
    length = g["pathLength"]
    s = np.mod(start + np.linspace(0.0, revolutions * length, samples), length)
    grid = np.linspace(0.0, length, len(path))
    zeros = np.zeros(samples)
    return {"time": np.linspace(0.0, revolutions * 0.114, samples), "link.x": np.interp(s, grid, path[:, 0]),
            "link.y": np.interp(s, grid, path[:, 1]), "link.F": 300.0 + zeros, "link.FnSprocket": zeros,
            "link.FnGuide": zeros}


@pytest.mark.parametrize("revolutions, whole", [(1.7, True), (0.6, False)])
def test_link_cycle_lies_on_the_chain_path(tmp_path, revolutions, whole):
    g = geometry()
    length = g["pathLength"]
    d = link_along_the_path(g, 0.45 * length, revolutions)
    s = plots.link_cycle(tmp_path / "link_cycle.png", d, 3000.0, "synthetic", fidelity="span")
    assert np.all((s >= 0.0) & (s <= length))
    covered = np.ptp(s)
    if whole:  # one revolution from the path's origin: all of the path, in order
        assert covered > 0.99 * length and s[0] < 0.01 * length and np.all(np.diff(s) >= 0.0)
    else:  # what the record holds, not more than one revolution
        assert covered <= length and len(s) == len(d["time"])


def test_one_revolution_starts_at_the_origin_in_either_running_direction():
    length = 2.0
    travelled = np.linspace(0.0, 5.0, 501)
    for sign in (1.0, -1.0):
        pos = np.mod(0.7 + sign * travelled, length)
        i0, i1, whole = plots.one_revolution(pos, length)
        assert whole and abs(travelled[i1] - travelled[i0] - length) < 0.011
        assert min(pos[i0], length - pos[i0]) < 0.011


def test_run_up_order_cuts_use_the_summary_interval_over_blocks_of_cycles():
    rng = np.random.default_rng(5)
    rpm = np.linspace(1000.0, 6000.0, 40)
    values = rng.normal(30.0, 3.0, 40)
    at, mean, half = results.block_intervals(rpm, values, block=8)
    assert len(at) == 5
    for j in range(5):
        block = slice(8 * j, 8 * j + 8)
        assert (mean[j], half[j]) == cycle_stats.interval(values[block])[:2]
        assert at[j] == pytest.approx(np.mean(rpm[block]))


def test_campbell_levels_in_decibels():
    assert list(results.decibels([1.0, 10.0, 0.1])) == pytest.approx([0.0, 20.0, -20.0])


def test_cvt_envelope_bounds_the_signal():
    x = np.sin(np.linspace(0.0, 60.0, 1001))
    low, mean, high = cvt_plots.envelope(x, 100)
    assert len(mean) == 10 and np.all(low <= mean) and np.all(mean <= high)
    assert low[0] == np.min(x[:100]) and high[-1] == np.max(x[900:1000])
