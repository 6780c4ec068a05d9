"""Cycle statistics (harness/cycle_stats.py): whole engine cycles after the run-in, order
amplitudes by crank-angle resampling, and confidence intervals that cover as often as they claim."""
import dataclasses
import math

import numpy as np

from harness import cycle_stats, paths
from harness.drive.description import elements

CYCLE = cycle_stats.ENGINE_CYCLE


def test_spans_are_the_whole_cycles_after_the_run_in():
    phi = np.linspace(0.0, 5.5 * CYCLE, 5501)  # 5.5 cycles, 1000 samples per cycle
    spans = cycle_stats.cycle_spans(phi, run_in_cycles=2)
    assert [s[2] for s in spans] == [2 * CYCLE, 3 * CYCLE, 4 * CYCLE]  # the half cycle at the end is dropped
    for i0, i1, phi0 in spans:
        assert math.isclose(phi[i0], phi0) and math.isclose(phi[i1 - 1], phi0 + CYCLE)


def test_order_amplitudes_of_a_speed_varying_record():
    # a record sampled uniformly in time while the crankshaft speed varies: orders are per
    # crankshaft revolution, so resampling in crank angle must recover them exactly
    t = np.linspace(0.0, 0.04, 4001)
    phi = 314.16 * t + 0.3 * np.sin(2.0 * math.pi * 50.0 * t)
    x = 3.0 * np.cos(2.0 * phi) + 0.5 * np.sin(8.0 * phi + 0.4) + 7.0
    amps = cycle_stats.order_amplitudes(phi, x, 0.0, [2, 4, 8])
    assert abs(amps[0] - 3.0) < 1e-3 and amps[1] < 1e-3 and abs(amps[2] - 0.5) < 1e-3


def test_interval_covers_the_true_mean_as_often_as_it_claims():
    rng = np.random.default_rng(7)
    trials, n, covered = 4000, 12, 0
    for _ in range(trials):
        mean, half, cycles = cycle_stats.interval(rng.normal(5.0, 2.0, n))
        covered += abs(mean - 5.0) <= half
        assert 1.0 < cycles <= n
    # binomial standard deviation of the coverage over 4000 trials: 0.34 %. Slightly conservative
    # for independent cycles: a chance positive lag-1 correlation narrows n_eff (measured 96.1 %)
    assert 0.94 <= covered / trials <= 0.97


def test_correlated_cycles_widen_the_interval():
    # an AR(1) sequence with r1 = 0.6 carries fewer independent cycles than its length; the
    # interval must cover the true mean about as often as claimed, not as if the cycles were independent
    rng = np.random.default_rng(11)
    trials, n, covered = 2000, 60, 0
    for _ in range(trials):
        e = rng.normal(0.0, 1.0, n)
        x = np.empty(n)
        x[0] = e[0] / math.sqrt(1.0 - 0.36)
        for i in range(1, n):
            x[i] = 0.6 * x[i - 1] + e[i]
        mean, half, _ = cycle_stats.interval(x)
        covered += abs(mean) <= half
    # with the naive interval (n instead of n_eff) the coverage would be about 78 %
    assert covered / trials >= 0.90


def drive(meshing=21, hydraulic=False):
    """The default drive's elements, with another meshing order or tensioner."""
    return dataclasses.replace(elements(), crank_teeth=meshing, hydraulic=hydraulic)


def test_headline_keys_and_order_keys_per_signal():
    keys = cycle_stats.headline_keys(drive())
    assert keys[:7] == ["tensioner.F.mean", "tensioner.F.peakToPeak", "chain.Ftight.mean", "chain.Fslack.mean",
                        "tensionGuide.phi.peakToPeak_deg", "camshaftIntake.timing.peakToPeak_degCA",
                        "camshaftExhaust.timing.peakToPeak_degCA"]
    assert cycle_stats.order_keys(keys) == {
        "tensioner.F": [f"tensioner.F.order{k}" for k in (2, 4, 6, 8, 21)],
        "tensionGuide.phi": [f"tensionGuide.phi.order{k}_deg" for k in (2, 4, 6, 8, 21)]}
    assert len(keys) == 17 and "tensioner.F.order19" in cycle_stats.headline_keys(drive(19))


def test_headline_keys_of_other_drives_name_their_own_elements():
    """A single camshaft's timing, a pump's and an idler's speed fluctuation, no chamber without a
    hydraulic tensioner, the tension guide by its name (the test drives, tests/drives/)."""
    root = paths.ROOT / "tests" / "drives"
    single = cycle_stats.headline_keys(elements(root / "sohc_single_cam.json"))
    assert "camshaft.timing.peakToPeak_degCA" in single and not [k for k in single if "camshaftIntake" in k]
    pump = cycle_stats.headline_keys(elements(root / "diesel_pump.json"))
    assert {"hpPump.w.peakToPeak_rpm", "camshaftIntake.timing.peakToPeak_degCA"} <= set(pump)
    idler = cycle_stats.headline_keys(elements(root / "idler.json"))
    assert "idler.w.peakToPeak_rpm" in idler
    eight = cycle_stats.headline_keys(elements(root / "dohc_8mm.json"))
    assert {"tensionerArm.phi.peakToPeak_deg", "tensionerArm.phi.order19_deg", "intakeCam.timing.peakToPeak_degCA"} \
        <= set(eight) and not [k for k in eight if "tensionGuide" in k]


def test_timing_follows_the_tooth_ratio():
    """A sprocket turning exactly by the tooth ratio has no timing deviation: a 28-tooth pump on a
    21-tooth crankshaft turns by 21/28 of its angle."""
    e = elements(paths.ROOT / "tests" / "drives" / "diesel_pump.json")
    phi = np.linspace(0.0, 10.0, 50)
    d = {"crankshaft.phi": phi, "hpPump.phi": phi * 21.0 / 28.0}
    assert np.max(np.abs(cycle_stats.timing_deg(d, e, "hpPump"))) < 1e-12
