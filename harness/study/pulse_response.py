"""The camshafts' response to a torque pulse, link model against span model: whether a short dynamic
run of the link model gives the span model a damping of the camshafts' mode.

    python -m harness pulse-response [--rpm 3000] [--pulse 20] [--replicas 8] [--out docs/study/pulse_response]

Per fidelity, two runs of the solver alone (chaindrive-run, each fidelity's default step) at a
constant crankshaft speed with constant camshaft loads (LOAD): one plain, its twin with a pulse of
--pulse N m on both camshafts for PULSE_LENGTH at PULSE_TIME. The response is the intake camshaft's
timing (its angle less half the crankshaft's) in the pulsed run less the plain one, high-passed
(HIGH_PASS, zero-phase: the slow drift the pulse leaves in the guide and the chamber removed), and
its envelope (Hilbert). Printed and written (OUT/
pulse.json, OUT/pulse.md): the envelope at several times after the pulse over its largest value,
the frequency of the response's spectral peak, the decay rate and damping ratio of an exponential
fitted over FIT, and the plain run's own high-passed motion (its RMS over the same window: the
level the model reaches without a pulse). A model whose response falls to its own level and stays
there, rather than decaying on, gives no modal damping to identify.

The mode is also identified finer than the spectrum's bin: a damped sinusoid fitted by least squares
to the response over FIT (frequency, decay rate, amplitude, phase; started from the spectral peak and
the envelope's decay), and, because the models are chaotic (twins separate e-fold in about 1.4 ms),
over --replicas twin pairs whose crankshaft speed differs by 1e-9 per pair (harness/replicas.py):
each pair's fitted frequency and damping ratio, their mean and Student's t 95 % half-width.
"""
import json
import math
import pathlib
import tempfile

import numpy as np
from scipy.signal import butter, hilbert, sosfiltfilt

from .. import paths, replicas, runs

LOAD = 5.0                       # [N m] on each camshaft
PULSE_TIME, PULSE_LENGTH = 0.02, 3e-4  # [s]
AFTER = 0.05                     # [s] simulated after the pulse
OUTPUT_STEP = 1e-5               # [s] asked for; the samples' own step is what the analysis takes
HIGH_PASS = 100.0                # [Hz] leaves out the slow drift the pulse leaves (the guide, the chamber)
FIT = (0.002, 0.02)              # [s] after the pulse
SAMPLES = (0.002, 0.005, 0.01, 0.02, 0.04)  # [s] after the pulse
FIDELITIES = ("link", "span")


def add_arguments(ap):
    ap.add_argument("--rpm", type=float, default=3000.0, help="crankshaft speed [rpm]")
    ap.add_argument("--replicas", type=int, default=8, help="twin pairs per model (their speeds 1e-9 apart)")
    ap.add_argument("--pulse", type=float, default=20.0, help="torque pulse on each camshaft [N m]")
    ap.add_argument("--out", default=str(paths.RESULTS / "pulse_response"))


def check(ap, args):
    if not 100.0 <= args.rpm <= 7000.0:
        ap.error(f"--rpm {args.rpm:g}: outside [100, 7000] rpm")
    if not 0.0 < args.pulse <= 200.0:
        ap.error(f"--pulse {args.pulse:g}: outside (0, 200] N m")
    if not 2 <= args.replicas <= 100:
        ap.error(f"--replicas {args.replicas}: outside 2..100 (an interval needs two)")
    return args


def write_inputs(path, rpm, pulse, replica=0):
    """The inputs' time series: constant speed (replica k's 1 + k 1e-9 times it) and loads, the pulse
    between its two time pairs."""
    w = rpm * 2.0 * math.pi / 60.0 * (1.0 + replica * replicas.PERTURBATION)
    end = PULSE_TIME + PULSE_LENGTH
    rows = [(0.0, 0.0), (PULSE_TIME, 0.0), (PULSE_TIME + 1e-9, pulse), (end, pulse), (end + 1e-9, 0.0), (1.0, 0.0)]
    lines = ["time,crankshaft.w,camshaftIntake.tau,camshaftExhaust.tau"]
    lines += [f"{t!r},{w!r},{LOAD + p!r},{LOAD + p!r}" for t, p in rows]
    pathlib.Path(path).write_text("\n".join(lines) + "\n")


def timing(record):
    return record["camshaftIntake.phi"] - 0.5 * record["crankshaft.phi"]


def sampling_step(t):
    """The step [s] the samples were written at, from their own time column: chaindrive-run writes
    every whole number of its grid steps, so the step asked for (OUTPUT_STEP) is not the step got
    (the span model's 1e-4/3 s grid: 33.3 us; the link model's 1e-4/28: 3 steps, 10.7 us)."""
    # over the whole column: its printed digits jitter each difference (1e-5 of a 10 us step at
    # 0.2 s), not the span
    steps = np.diff(t)
    step = float((t[-1] - t[0]) / (len(t) - 1))
    if not np.allclose(steps, step, rtol=1e-3, atol=0.0):
        raise ValueError(f"the samples are not equally spaced: steps from {steps.min():.6g} to {steps.max():.6g} s")
    return step


def filtered(t, pulsed, plain):
    """(times after the pulse, the high-passed response, the high-passed plain run) from the two
    runs' timing signals sampled at times t (the filter designed at their own sampling rate)."""
    sos = butter(4, HIGH_PASS, btype="highpass", fs=1.0 / sampling_step(t), output="sos")
    difference = sosfiltfilt(sos, pulsed - plain)
    plain = sosfiltfilt(sos, plain - np.mean(plain))
    after = t >= PULSE_TIME + PULSE_LENGTH
    return t[after] - t[after][0], difference[after], plain[after]


def response(rpm, pulse, fidelity, work, replica=0):
    """filtered() of one fidelity's plain and pulsed runs (twin pair `replica`)."""
    signals = {}
    for name, p in (("plain", 0.0), ("pulsed", pulse)):
        inputs, out = work / f"{fidelity}-{name}-{replica}-inputs.csv", work / f"{fidelity}-{name}-{replica}.csv"
        write_inputs(inputs, rpm, p, replica)
        runs.run(out, rpm=rpm, duration=PULSE_TIME + PULSE_LENGTH + AFTER, output_step=OUTPUT_STEP,
                 inputs_csv=inputs, fidelity=fidelity)
        signals[name] = runs.read_csv(out)
    return filtered(signals["plain"]["time"], timing(signals["pulsed"]), timing(signals["plain"]))


def figures(t, difference, plain):
    """The envelope's course, the peak frequency, the fitted decay and the plain run's level."""
    envelope = np.abs(hilbert(difference))
    largest = float(envelope.max())
    window = t <= FIT[1]
    spectrum = np.abs(np.fft.rfft(difference[window] * np.hanning(window.sum())))
    frequency = float(np.fft.rfftfreq(window.sum(), sampling_step(t))[np.argmax(spectrum)])
    fit = (t >= FIT[0]) & (t <= FIT[1])
    rate = float(np.polyfit(t[fit], np.log(envelope[fit]), 1)[0])
    return dict(samplingStep_s=sampling_step(t), largest_rad=largest, frequency_Hz=frequency, decayRate_per_s=-rate,
                dampingRatio=-rate / (2.0 * math.pi * frequency) if frequency > 0.0 else None,
                envelopeOverLargest={f"{s * 1e3:g} ms": float(envelope[np.searchsorted(t, s)] / largest)
                                     for s in SAMPLES},
                plainRmsOverLargest=float(np.sqrt(np.mean(plain ** 2)) / largest))


def fit_mode(t, difference, frequency, rate):
    """(frequency [Hz], decay rate [1/s], damping ratio) of the damped sinusoid a e^(-rate t)
    sin(2 pi f t + phase) fitted by least squares to the response over FIT, started from the
    spectral peak and the envelope's decay: finer than the spectrum's bin."""
    from scipy.optimize import least_squares  # (here: scipy.optimize takes a while to import)
    window = (t >= FIT[0]) & (t <= FIT[1])
    tw, xw = t[window] - FIT[0], difference[window]
    amplitude = float(np.abs(hilbert(difference))[window][0])

    def residual(p):
        a, r, f, phase = p
        return a * np.exp(-r * tw) * np.sin(2.0 * math.pi * f * tw + phase) - xw
    best = min((least_squares(residual, [amplitude, max(rate, 1.0), frequency, phase0], x_scale="jac")
                for phase0 in np.linspace(0.0, 2.0 * math.pi, 4, endpoint=False)), key=lambda r: r.cost)
    _, r, f = best.x[:3]
    omega = 2.0 * math.pi * abs(f)
    return float(abs(f)), float(r), float(r / math.hypot(r, omega))


def modes(rpm, pulse, fidelity, work, count):
    """Each twin pair's fitted mode and their means with Student's t 95 % half-widths."""
    from ..cycle_stats import student_half_width
    per_pair = []
    for k in range(count):
        t, difference, plain = response(rpm, pulse, fidelity, work, k)
        f = figures(t, difference, plain)
        frequency, rate, ratio = fit_mode(t, difference, f["frequency_Hz"], f["decayRate_per_s"])
        per_pair.append(dict(frequency_Hz=frequency, decayRate_per_s=rate, dampingRatio=ratio))
    summary = {key: dict(mean=float(np.mean([p[key] for p in per_pair])),
                         ci95=student_half_width([p[key] for p in per_pair], len(per_pair)))
               for key in ("frequency_Hz", "decayRate_per_s", "dampingRatio")}
    return dict(pairs=per_pair, **summary)


def report_lines(args, found):
    lines = ["# The camshafts' response to a torque pulse: link model against span model", "",
             f"Command: python -m harness pulse-response {' '.join(args.argv)}", "",
             f"Constant crankshaft speed {args.rpm:g} rpm, {LOAD:g} N m on each camshaft; the twin run's pulse "
             f"{args.pulse:g} N m on both camshafts for {PULSE_LENGTH * 1e3:g} ms; the intake camshaft's timing "
             f"difference high-passed at {HIGH_PASS:g} Hz (the slow drift the pulse leaves removed); its envelope after the pulse over its largest "
             f"value; the decay fitted over {FIT[0] * 1e3:g}-{FIT[1] * 1e3:g} ms; the plain run's own high-passed "
             f"motion (RMS) on the same scale. Each run's sampling step is its CSV's own (chaindrive-run writes "
             f"every whole number of its grid steps nearest the {OUTPUT_STEP * 1e6:g} us asked for); the peak's "
             f"frequency is read to a bin of the spectrum over {FIT[1] * 1e3:g} ms, {1.0 / FIT[1]:g} Hz.", "",
             "| fidelity | sampling step [us] | largest [rad] | peak [Hz] | " + " | ".join(f"{s * 1e3:g} ms" for s in SAMPLES) +
             " | fitted decay [1/s] | damping ratio | plain run's level |",
             "|---|---|---|---|" + "---|" * len(SAMPLES) + "---|---|---|"]
    for fidelity, f in found.items():
        course = " | ".join(f"{v:.3f}" for v in f["envelopeOverLargest"].values())
        lines.append(f"| {fidelity} | {f['samplingStep_s'] * 1e6:.4g} | {f['largest_rad']:.3g} | {f['frequency_Hz']:.0f} | {course} | "
                     f"{f['decayRate_per_s']:.0f} | {f['dampingRatio']:.3f} | {f['plainRmsOverLargest']:.3f} |")
    lines += ["", f"The mode fitted (a damped sinusoid by least squares over {FIT[0] * 1e3:g}-{FIT[1] * 1e3:g} ms, finer "
              f"than the spectrum's bin) on {args.replicas} twin pairs per model whose crankshaft speeds differ by "
              f"{replicas.PERTURBATION:g} per pair: the mean and its 95 % half-width (Student's t over the pairs).", "",
              "| fidelity | frequency [Hz] | decay rate [1/s] | damping ratio | pairs |", "|---|---|---|---|---|"]
    for fidelity, f in found.items():
        m = f["fitted"]
        lines.append(f"| {fidelity} | {m['frequency_Hz']['mean']:.1f} +- {m['frequency_Hz']['ci95']:.1f} | "
                     f"{m['decayRate_per_s']['mean']:.1f} +- {m['decayRate_per_s']['ci95']:.1f} | "
                     f"{m['dampingRatio']['mean']:.4f} +- {m['dampingRatio']['ci95']:.4f} | {len(m['pairs'])} |")
    return lines + [""]


def run(args):
    out = pathlib.Path(args.out)
    with tempfile.TemporaryDirectory() as tmp:
        found = {fidelity: figures(*response(args.rpm, args.pulse, fidelity, pathlib.Path(tmp)))
                 for fidelity in FIDELITIES}
        for fidelity in FIDELITIES:
            found[fidelity]["fitted"] = modes(args.rpm, args.pulse, fidelity, pathlib.Path(tmp), args.replicas)
    lines = report_lines(args, found)
    print("\n".join(lines))
    out.mkdir(parents=True, exist_ok=True)
    (out / "pulse.json").write_text(json.dumps(dict(rpm=args.rpm, pulse_Nm=args.pulse, replicas=args.replicas,
                                                    fidelities=found),
                                               indent=1) + "\n")
    runs.write_lines(out / "pulse.md", lines)
    return 0
