"""The pulse study's analysis (harness/study/pulse_response.py) on signals with a known answer, through
the same path as the models' runs (the high-pass filter, the envelope, the spectrum, the fit): a
damped sinusoid sampled at the steps chaindrive-run writes when asked for 1e-5 s (the link model's
three steps of 1e-4/28 s, the span model's one of 1e-4/3 s) and at 1e-5 s itself. The frequency
lies within a bin of the spectrum (the window's length over its samples), the damping ratio within
10 %, whatever the sampling step."""
import math

import numpy as np
import pytest

from harness.study import pulse_response as pr

FREQUENCY, DAMPING_RATIO = 375.0, 0.024  # [Hz], [-]
STEPS = {"link model": 3e-4 / 28, "span model": 1e-4 / 3, "as asked": 1e-5}


def known_signals(step):
    """(t, pulsed, plain): the plain run's slow drift, the pulsed one with a damped sinusoid after the pulse."""
    t = np.arange(0.0, pr.PULSE_TIME + pr.PULSE_LENGTH + pr.AFTER, step)
    plain = 1e-3 * np.sin(2.0 * math.pi * 5.0 * t)  # (a drift the high-pass removes)
    after = np.clip(t - (pr.PULSE_TIME + pr.PULSE_LENGTH), 0.0, None)
    omega, rate = 2.0 * math.pi * FREQUENCY, DAMPING_RATIO * 2.0 * math.pi * FREQUENCY
    ringing = np.where(t >= pr.PULSE_TIME + pr.PULSE_LENGTH, 1e-3 * np.exp(-rate * after) * np.sin(omega * after), 0.0)
    return t, plain + ringing, plain


@pytest.mark.parametrize("name", STEPS)
def test_a_known_mode_is_found_at_any_sampling_step(name):
    step = STEPS[name]
    t, pulsed, plain = known_signals(step)
    assert pr.sampling_step(t) == pytest.approx(step, rel=1e-9)
    found = pr.figures(*pr.filtered(t, pulsed, plain))
    bin_width = 1.0 / (pr.FIT[1] + step)  # (the spectrum's window: FIT[1] of samples)
    assert abs(found["frequency_Hz"] - FREQUENCY) <= bin_width, found
    assert found["dampingRatio"] == pytest.approx(DAMPING_RATIO, rel=0.1), found


def test_samples_not_equally_spaced_are_refused():
    t = np.array([0.0, 1e-5, 2e-5, 4e-5])
    with pytest.raises(ValueError, match="not equally spaced"):
        pr.sampling_step(t)


@pytest.mark.parametrize("name", STEPS)
def test_the_fit_finds_a_known_mode_finer_than_a_bin(name):
    """The damped sinusoid fitted over the same window: its frequency within 0.5 % (the bin is 13 %
    of 375 Hz), its damping ratio within 5 %, whatever the sampling step."""
    t, pulsed, plain = known_signals(STEPS[name])
    ta, difference, plain_after = pr.filtered(t, pulsed, plain)
    rough = pr.figures(ta, difference, plain_after)
    frequency, rate, ratio = pr.fit_mode(ta, difference, rough["frequency_Hz"], rough["decayRate_per_s"])
    assert frequency == pytest.approx(FREQUENCY, rel=0.005)
    assert ratio == pytest.approx(DAMPING_RATIO, rel=0.05)
    assert rate == pytest.approx(DAMPING_RATIO * 2.0 * math.pi * FREQUENCY, rel=0.05)
