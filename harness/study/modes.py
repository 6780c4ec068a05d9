"""The drive's modes that the cycle statistics feel, identified in the link model and in the span
model side by side (docs/modes.md): the loaded sprockets' mode in phase and in anti-phase, the
tension guide's mode and the hydraulic chamber's response to its supply, at several speeds and
loads, each with its interval over twin pairs.

    python -m harness modes [--drive FILE] [--rpm 1000 3000 6000] [--loads 5 15] [--replicas 8]
        [--workers N] [--out docs/study/modes]

Per fidelity, speed and load, a run-in of RUN_IN_REVOLUTIONS crankshaft revolutions settles the
drive (the hydraulic chamber pumps up over many; its state saved); from it, per twin pair (crankshaft
speeds 1e-9 apart per pair: the link model is chaotic, twins separate e-fold in about 1.4 ms, so the
pairs are unlike each other when the pulse comes, PULSE_TIME after the run-in): a plain run of the solver alone (chaindrive-run,
each fidelity's default step) at a constant crankshaft speed with every loaded sprocket at the load,
and one run per excitation that differs from it only by a short pulse at PULSE_TIME:

- `loads-in-phase`: +PULSE on every loaded sprocket for PULSE_LENGTH;
- `loads-in-anti-phase` (two or more loaded sprockets): +PULSE and -PULSE alternately;
- `tension-guide`: +GUIDE_PULSE on the tension guide (towards the chain) for PULSE_LENGTH;
- `supply` (a hydraulic tensioner): its supply pressure SUPPLY_STEP higher from PULSE_TIME on.

The response is the excited run less the plain one in every channel (each loaded sprocket's timing:
its angle less the crankshaft's over their ratio; the tension guide's angle). The pairs' responses are
averaged: what the pulse causes has the same phase in every pair, the chaos each pair adds after the
pulse has none in common and averages out (the share of the response energy that survives is
reported as `coherent`). A mode is fitted to the mean's channels of the excited elements at once
over FIT after the pulse (the sprockets' timings; the guide's
angle): one frequency and one decay rate, each channel its own
amplitude and phase and its own slow drift (a quadratic: what the pulse leaves in the guide and the
chamber; variable projection, all of these by linear least squares for each trial frequency and
rate), started from the summed spectra's peak of the responses high-passed at HIGH_PASS (zero-phase,
designed at the samples' own rate: sampling_step, from their time column). No filter touches the
fitted signal: a 100 Hz high-pass took 10 % off the damping of a mode at 160 Hz. Its shape: each
channel's amplitude over the largest one's and its phase relative to it. The supply's response is
the tensioner force's change: its gain over the step after SUPPLY_SETTLE and the time it takes to
reach 63 % of it (low-passed at SUPPLY_LOW_PASS), of the pairs' mean. Every figure's interval: the
jackknife over the pairs (the fit repeated with each pair left out), Student's t 95 %.
"""
import concurrent.futures
import dataclasses
import itertools
import json
import math
import os
import pathlib
import tempfile

import numpy as np
from scipy.signal import butter, hilbert, sosfiltfilt

from .. import paths, replicas, runs
from ..cycle_stats import student_half_width
from ..drive import description
from .pulse_response import sampling_step

RUN_IN_REVOLUTIONS = 40                   # of the crankshaft before the pulses: the tensioner settled
PULSE_TIME, PULSE_LENGTH = 0.05, 3e-4     # [s] after the run-in (twins 1e-9 apart have separated by then: e-fold
                                          # per 1.4 ms)
PULSE = 20.0                              # [N m] on a loaded sprocket
GUIDE_PULSE = 10.0                        # [N m] on the tension guide
AFTER = 0.05                              # [s] simulated after a pulse
OUTPUT_STEP = 1e-4                        # [s] a whole number of every drive's own steps (1e-4/N): 14 samples a
                                          # period at 700 Hz; the analysis takes the samples' own step anyway
HIGH_PASS = 100.0                         # [Hz] the spectrum that starts the fit leaves out the slow drift
FIT = (0.002, 0.02)                       # [s] after the pulse
SUPPLY_STEP = 1e5                         # [Pa] gauge
SUPPLY_AFTER = 0.2                        # [s] simulated after the supply's step
SUPPLY_SETTLE = (0.15, 0.2)               # [s] after the step: the window of the response's final value
SUPPLY_LOW_PASS = 200.0                   # [Hz] the chain's vibration left out of the supply's response
FIDELITIES = ("link", "span")
RINGING = 0.3                             # the largest damping ratio taken for a mode
MIN_PERIODS = 2                           # of a mode within the fit's window


@dataclasses.dataclass(frozen=True)
class Excitation:
    name: str
    pulses: tuple         # ((input column, value added), ...) over the pulse
    fitted: tuple = ()    # the channels the mode is fitted to (the excited elements'; the shape takes all)
    step: bool = False    # held from PULSE_TIME on (the supply), not a pulse


def excitations(el):
    """The excitations a drive (description.Elements) offers."""
    loaded = el.loaded
    timings = tuple(f"{n}.timing" for n in loaded)
    out = [Excitation("loads-in-phase", tuple((f"{n}.tau", PULSE) for n in loaded), timings)] if loaded else []
    if len(loaded) >= 2:
        out.append(Excitation("loads-in-anti-phase", tuple((f"{n}.tau", PULSE * (-1) ** i) for i, n in enumerate(loaded)),
                              timings))
    if el.tension_guide:
        # (fitted to the guide's own angle: the link model's guide rings at its own frequency, well
        # above the sprockets' mode that its pulse excites too)
        out.append(Excitation("tension-guide", ((f"{el.tension_guide}.tau", GUIDE_PULSE),), (f"{el.tension_guide}.phi",)))
    if el.hydraulic:
        out.append(Excitation("supply", (("tensioner.supplyPressure", SUPPLY_STEP),), step=True))
    return out


def channels(el, record):
    """The response channels of a run's record: each loaded sprocket's timing [rad of the sprocket]
    and the tension guide's angle [rad]."""
    crank = record[f"{el.crank}.phi"]
    out = {f"{n}.timing": record[f"{n}.phi"] - crank / el.ratio(n) for n in el.loaded}
    if el.tension_guide:
        out[f"{el.tension_guide}.phi"] = record[f"{el.tension_guide}.phi"]
    return out


def write_inputs(path, el, rpm, load, replica, excitation=None, supply=None, start=0.0):
    """The inputs' time series: the crankshaft at rpm (replica k's 1 + k 1e-9 times it), every loaded
    sprocket at `load`, a hydraulic tensioner's supply at `supply` [Pa] (None: the drive's, no
    column), the excitation's pulse (or step) added from `start` + PULSE_TIME."""
    w = rpm * 2.0 * math.pi / 60.0 * (1.0 + replica * replicas.PERTURBATION)
    base = {f"{el.crank}.w": w, **{f"{n}.tau": load for n in el.loaded}}
    if el.tension_guide:
        base[f"{el.tension_guide}.tau"] = 0.0
    if supply is not None:
        base["tensioner.supplyPressure"] = supply
    added = dict(excitation.pulses) if excitation else {}
    pulse = start + PULSE_TIME
    times = [(0.0, False), (pulse, False), (pulse + 1e-9, True)]
    if excitation is not None and excitation.step:
        times += [(pulse + 1.0, True)]
    else:
        end = pulse + PULSE_LENGTH
        times += [(end, True), (end + 1e-9, False), (pulse + 1.0, False)]
    columns = list(base)
    lines = ["time," + ",".join(columns)]
    for t, on in times:
        lines.append(f"{t!r}," + ",".join(repr(base[c] + (added.get(c, 0.0) if on else 0.0)) for c in columns))
    pathlib.Path(path).write_text("\n".join(lines) + "\n")


def high_passed(t, x):
    sos = butter(4, HIGH_PASS, btype="highpass", fs=1.0 / sampling_step(t), output="sos")
    return sosfiltfilt(sos, x)


def low_passed(t, x):
    sos = butter(4, SUPPLY_LOW_PASS, btype="lowpass", fs=1.0 / sampling_step(t), output="sos")
    return sosfiltfilt(sos, x)


def fit_mode(t, responses, fitted=None):
    """The damped sinusoid common to the responses (name -> samples at t after the pulse) of the
    channels `fitted` (None: all) over FIT, each channel with its own slow drift (a quadratic in t,
    fitted with it): (frequency [Hz], decay rate [1/s], damping ratio, {name: (amplitude over the
    largest, phase relative to the largest [deg])} of every channel at that frequency and decay,
    whether the frequency ended at its search bound: two bins either side of the spectrum's peak;
    there, no mode was found)."""
    from scipy.optimize import least_squares  # (here: scipy.optimize takes a while to import)
    window = (t >= FIT[0]) & (t <= FIT[1])
    tw = t[window] - FIT[0]
    names = list(responses)
    fitted = list(fitted or names)
    x = np.array([responses[n][window] for n in names])              # (channels, samples)
    rows = [names.index(n) for n in fitted]
    step = sampling_step(t)
    # the starting values from the high-passed responses (the fit itself takes them unfiltered)
    passed = {n: high_passed(t, responses[n]) for n in fitted}
    spectrum = sum(np.abs(np.fft.rfft(passed[n][t <= FIT[1]] * np.hanning((t <= FIT[1]).sum()))) ** 2 for n in fitted)
    freqs = np.fft.rfftfreq((t <= FIT[1]).sum(), step)
    f0 = float(freqs[np.argmax(spectrum)])
    largest = fitted[int(np.argmax(np.max(np.abs(x[rows]), axis=1)))]
    envelope = np.abs(hilbert(passed[largest]))[window]
    r0 = float(-np.polyfit(tw, np.log(envelope), 1)[0])

    drift = np.array([np.ones_like(tw), tw / FIT[1], (tw / FIT[1]) ** 2])  # (what a pulse leaves: slow)

    def amplitudes(p):
        rate, f = p
        mode = np.exp(-rate * tw) * np.array([np.cos(2.0 * math.pi * f * tw), np.sin(2.0 * math.pi * f * tw)])
        basis = np.vstack([mode, drift])
        coef = np.linalg.lstsq(basis.T, x.T, rcond=None)[0]          # (2 + 3, channels)
        return basis, coef

    def residual(p):
        basis, coef = amplitudes(p)
        return (coef.T @ basis - x)[rows].ravel()
    bin_width = 1.0 / FIT[1]
    # (a negative rate is a response that grows over the window: reported as it is)
    lower, upper = max(f0 - 2.0 * bin_width, 1.0), f0 + 2.0 * bin_width
    best = least_squares(residual, [r0, f0], bounds=([-np.inf, lower], [np.inf, upper]), x_scale="jac")
    rate, f = best.x
    _, coef = amplitudes(best.x)
    complex_amp = coef[0] - 1j * coef[1]                               # a cos + b sin = Re(A e^(i w t))
    ref = rows[int(np.argmax(np.abs(complex_amp[rows])))]
    shape = {n: (float(abs(complex_amp[i]) / abs(complex_amp[ref])),
                 float(np.degrees(np.angle(complex_amp[i] / complex_amp[ref])))) for i, n in enumerate(names)}
    omega = 2.0 * math.pi * f
    at_bound = min(abs(f - lower), abs(f - upper)) <= 1e-6 * f  # (the iterates stay strictly inside)
    return float(f), float(rate), float(rate / math.hypot(rate, omega)), shape, at_bound


def supply_response(t, force_change):
    """(gain [N/Pa], time to 63 % of it [s]) of the tensioner force's change after the supply's step
    (t: after the step)."""
    smooth = low_passed(t, force_change)
    final = float(np.mean(smooth[(t >= SUPPLY_SETTLE[0]) & (t <= SUPPLY_SETTLE[1])]))
    reached = np.nonzero(np.sign(final) * smooth >= 0.63 * abs(final))[0]
    return final / SUPPLY_STEP, float(t[reached[0]]) if len(reached) else float("nan")


def responses_of(t, excited, plain, start):
    """(times from `start`, {channel: excited less plain from `start` on}) of two runs' channels (name
    -> samples at t)."""
    after = t >= start
    return t[after] - t[after][0], {c: (excited[c] - plain[c])[after] for c in excited}


def ensemble_mode(t, pairs, fitted=None):
    """The mode in the pairs' responses (each {channel: samples at t}): fit_mode of their mean over the
    pairs (the response the pulse causes; the chaos each pair adds after it has no phase in common
    and averages out), its intervals by the jackknife over the pairs (each pair left out in turn);
    `coherent`: the mean's energy over the pairs' mean energy (1: no chaos in the responses, 1/n:
    nothing but chaos)."""
    n = len(pairs)
    mean = {c: np.mean([p[c] for p in pairs], axis=0) for c in pairs[0]}
    whole = fit_mode(t, mean, fitted)
    left_out = [fit_mode(t, {c: (n * mean[c] - p[c]) / (n - 1) for c in mean}, fitted) for p in pairs] if n > 2 else []
    window = (t >= FIT[0]) & (t <= FIT[1])
    energy = lambda x: float(np.sum(x[window] ** 2))  # noqa: E731
    names = list(fitted or mean)
    coherent = sum(energy(mean[c]) for c in names) / np.mean([sum(energy(p[c]) for c in names) for p in pairs])
    out = {key: jackknife(whole[i], [lo[i] for lo in left_out]) for i, key in
           enumerate(("frequency_Hz", "decayRate_per_s", "dampingRatio"))}
    out["shape"] = {c: {"ratio": jackknife(whole[3][c][0], [lo[3][c][0] for lo in left_out]),
                        "phase_deg": jackknife(whole[3][c][1], [lo[3][c][1] for lo in left_out], degrees=True)}
                    for c in mean}
    out["coherent"] = float(coherent)
    out["notAMode"] = not_a_mode(whole[0], whole[2], whole[4])
    return out


def not_a_mode(frequency, damping_ratio, at_bound):
    """Why a fit is no mode ("" when it is one): its frequency at the search bound; fewer than
    MIN_PERIODS periods in the fit's window (the drift term mimics a slower one: a decay without
    ringing fits at the spectrum's first bins); a damping ratio beyond RINGING (a decay the fit
    dressed as a sinusoid: a known decay without ringing fits with 0.5-0.8)."""
    lowest = MIN_PERIODS / (FIT[1] - FIT[0])
    if at_bound:
        return f"the fit's frequency {frequency:.1f} Hz at its search bound"
    if frequency < lowest:
        return f"{frequency:.1f} Hz, below the {lowest:.0f} Hz the fit's window resolves ({MIN_PERIODS} periods)"
    if damping_ratio > RINGING:
        return f"a decay, not a ringing (damping ratio {damping_ratio:.2f} at {frequency:.1f} Hz)"
    return ""


def ensemble_supply(t, force_changes):
    """supply_response of the pairs' mean tensioner-force change after the supply's step, with its
    jackknife intervals."""
    n = len(force_changes)
    mean = np.mean(force_changes, axis=0)
    gain, rise = supply_response(t, mean)
    left_out = [supply_response(t, (n * mean - x) / (n - 1)) for x in force_changes] if n > 2 else []
    return dict(gain_N_per_bar=jackknife(gain * 1e5, [g * 1e5 for g, _ in left_out]),
                rise63_s=jackknife(rise, [r for _, r in left_out]))


@dataclasses.dataclass(frozen=True)
class Point:
    """One drive, fidelity, speed and load, and what its runs share."""
    drive: str
    fidelity: str
    rpm: float
    load: float

    def simulate(self, work, name, pair, excitation, duration, start=0.0, initial_state=None, save_state=None):
        """chaindrive-run of pair `pair` with `excitation` (None: plain) from `start` (the state
        `initial_state`'s time; 0: a fresh start) for `duration`; its record, inputs and outputs in
        `work` under `name`."""
        d = description.drive_json(self.drive)
        el = description.elements(d)
        inputs, out = pathlib.Path(work) / f"{name}-inputs.csv", pathlib.Path(work) / f"{name}.csv"
        write_inputs(inputs, el, self.rpm, self.load, pair, excitation,
                     description.supply_pressure(d) if el.hydraulic else None, start)
        runs.run(out, rpm=self.rpm, duration=duration, output_step=OUTPUT_STEP, inputs_csv=inputs,
                 fidelity=self.fidelity, drive=self.drive, initial_state=initial_state, save_state=save_state)
        return runs.read_csv(out)


def settle(case):
    """The run-in of one (Point, folder): RUN_IN_REVOLUTIONS at the plain inputs, its end state saved
    in the folder; returns (the point, the state file, its time, the tensioner force's mean over the
    run-in's last quarter over the quarter before, - 1: how settled it is; None without a tensioner)."""
    point, folder = case
    tag = f"{point.fidelity}-{point.rpm:g}-{point.load:g}"
    state = pathlib.Path(folder) / f"{tag}.state.json"
    record = point.simulate(folder, tag, 0, None, RUN_IN_REVOLUTIONS * 60.0 / point.rpm, save_state=state)
    quarter = len(record["time"]) // 4
    force = record.get("tensioner.F")
    drift = None if force is None else float(np.mean(force[-quarter:]) / np.mean(force[-2 * quarter:-quarter]) - 1.0)
    return point, str(state), float(record["time"][-1]), drift


def run_case(case):
    """One (Point, pair, settled state, its time): from the state, its plain run and one run per
    excitation; per excitation the response: (times from the pulse's end, {channel: response}), the
    supply's (times from its step, the tensioner force's change)."""
    point, pair, state, start = case
    el = description.elements(point.drive)
    found = {}
    with tempfile.TemporaryDirectory() as work:
        def simulate(name, excitation, duration):
            return point.simulate(work, name, pair, excitation, duration, start, initial_state=state)
        longest = PULSE_TIME + (SUPPLY_AFTER if el.hydraulic else PULSE_LENGTH + AFTER)
        plain = simulate("plain", None, longest)
        for k, ex in enumerate(excitations(el)):
            excited = simulate(f"excited{k}", ex, PULSE_TIME + (SUPPLY_AFTER if ex.step else PULSE_LENGTH + AFTER))
            n = len(excited["time"])
            head = {key: v[:n] for key, v in plain.items()}
            if ex.step:
                t, change = responses_of(excited["time"], {"F": excited["tensioner.F"]}, {"F": head["tensioner.F"]},
                                         start + PULSE_TIME)
                found[ex.name] = (t, change["F"])
            else:
                found[ex.name] = responses_of(excited["time"], channels(el, excited), channels(el, head),
                                              start + PULSE_TIME + PULSE_LENGTH)
    return point, found


def summarize(per_pair, el):
    """Per excitation of a drive (description.Elements): the mode of the pairs' responses
    (ensemble_mode), the supply's response (ensemble_supply)."""
    out = {}
    for ex in excitations(el):
        t = per_pair[0][ex.name][0]
        responses = [p[ex.name][1] for p in per_pair]
        out[ex.name] = ensemble_supply(t, responses) if ex.step else ensemble_mode(t, responses, ex.fitted)
    return out


def jackknife(whole, left_out, degrees=False):
    """{mean: the whole sample's estimate, ci95: Student's t 95 % half-width of the jackknife's
    standard error from the leave-one-out estimates (angles within 180 deg of the whole's), n}."""
    n = len(left_out)
    if n < 2:
        return dict(mean=float(whole), ci95=None, n=n)
    values = np.array(left_out, dtype=float)
    if degrees:
        values = whole + (values - whole + 180.0) % 360.0 - 180.0
    from scipy import stats as scistats
    error = math.sqrt((n - 1) / n * float(np.sum((values - values.mean()) ** 2)))
    return dict(mean=float(whole), ci95=float(scistats.t.ppf(0.975, n - 1) * error), n=n)


def add_arguments(ap):
    ap.add_argument("--drive", default=str(description.DEFAULT_DRIVE), help="drive description (default: the default drive)")
    ap.add_argument("--rpm", type=float, nargs="+", default=[1000.0, 3000.0, 6000.0], help="crankshaft speeds [rpm]")
    ap.add_argument("--loads", type=float, nargs="+", default=[5.0, 15.0],
                    help="load on every loaded sprocket [N m] (default 5 15)")
    ap.add_argument("--replicas", type=int, default=16, help="twin pairs per point (their speeds 1e-9 apart)")
    ap.add_argument("--fidelities", nargs="+", choices=FIDELITIES, default=list(FIDELITIES))
    ap.add_argument("--workers", type=int, default=os.cpu_count() or 1, help="runs side by side")
    ap.add_argument("--out", default=str(paths.RESULTS / "modes"), help="the results folder")


def check(ap, args):
    if any(not 100.0 <= r <= 7000.0 for r in args.rpm):
        ap.error(f"--rpm {' '.join(f'{r:g}' for r in args.rpm)}: each within [100, 7000] rpm")
    if not 3 <= args.replicas <= 100:
        ap.error(f"--replicas {args.replicas}: outside 3..100 (the jackknife's interval needs three)")
    if args.workers < 1:
        ap.error(f"--workers {args.workers}: at least 1")
    if not excitations(description.elements(args.drive)):
        ap.error(f"--drive {args.drive}: no loaded sprocket, tension guide or hydraulic tensioner to excite")
    return args


def run(args):
    points = [Point(args.drive, *p) for p in itertools.product(args.fidelities, args.rpm, args.loads)]
    found, settled = {}, {}
    with tempfile.TemporaryDirectory() as states, \
            concurrent.futures.ProcessPoolExecutor(min(args.workers, len(points) * args.replicas)) as pool:
        for point, state, start, drift in pool.map(settle, [(p, states) for p in points]):
            settled[point] = (state, start, drift)
        cases = [(p, k, *settled[p][:2]) for p in points for k in range(args.replicas)]
        for point, responses in pool.map(run_case, cases):
            found.setdefault(point, []).append(responses)
    el = description.elements(args.drive)
    results = [dict(point=f"{p.fidelity}-{p.rpm:g}-{p.load:g}", fidelity=p.fidelity, rpm=p.rpm, load_Nm=p.load,
                    pairs=len(found[p]), runInDrift=settled[p][2], modes=summarize(found[p], el)) for p in points]
    out = pathlib.Path(args.out)
    out.mkdir(parents=True, exist_ok=True)
    drive = pathlib.Path(args.drive).resolve()
    shown = drive.relative_to(paths.ROOT) if drive.is_relative_to(paths.ROOT) else drive
    (out / "modes.json").write_text(json.dumps(dict(drive=str(shown),
                                                    argv=args.argv, results=results), indent=1) + "\n")
    lines = report_lines(args, results)
    (out / "modes.md").write_text("\n".join(lines) + "\n")
    print("\n".join(lines))
    print(f"written: {out / 'modes.md'}, {out / 'modes.json'}")
    return 0


def cell(x, digits):
    if x["mean"] is None:
        return "-"
    return f"{x['mean']:.{digits}f}" + (f" +- {x['ci95']:.{digits}f}" if x["ci95"] is not None else "")


def report_lines(args, results):
    lines = ["# The drive's modes: link model against span model", "",
             f"Command: `python -m harness modes {' '.join(args.argv)}` (harness/study/modes.py, docs/modes.md): "
             f"pulses of {PULSE:g} N m on the loaded sprockets and {GUIDE_PULSE:g} N m on the tension guide for "
             f"{PULSE_LENGTH * 1e3:g} ms, the supply {SUPPLY_STEP / 1e5:g} bar higher; each mode fitted to every "
             f"excited channel at once over {FIT[0] * 1e3:g}-{FIT[1] * 1e3:g} ms after its pulse (with each channel's slow "
             f"drift) on the mean of {args.replicas} twin pairs' responses; +- the jackknife's 95 % half-width over the "
             "pairs; `coherent`: the mean's share of the pairs' response energy (1: no chaos, "
             f"1/{args.replicas}: nothing but chaos). A negative damping ratio: the response grows over the window.", ""]
    drifts = ", ".join(f"{r['fidelity']} {r['rpm']:g} rpm {r['load_Nm']:g} N m " +
                       (f"{r['runInDrift']:+.2%}" if r["runInDrift"] is not None else "(no tensioner)") for r in results)
    lines += [f"Each point's pulses come {PULSE_TIME * 1e3:g} ms after a run-in of {RUN_IN_REVOLUTIONS} crankshaft "
              "revolutions; the tensioner force's mean over its last quarter against the quarter before (how settled "
              f"the drive was): {drifts}.", ""]
    names = sorted({n for r in results for n in r["modes"]}, key=lambda n: [e for e in (
        "loads-in-phase", "loads-in-anti-phase", "tension-guide", "supply")].index(n))
    for name in names:
        rows = [r for r in results if name in r["modes"]]
        if name == "supply":
            lines += [f"## {name}", "", "| rpm | load [N m] | fidelity | tensioner force gain [N/bar] | 63 % after [ms] |",
                      "|---|---|---|---|---|"]
            for r in rows:
                m = r["modes"][name]
                rise = dict(m["rise63_s"], mean=m["rise63_s"]["mean"] * 1e3 if m["rise63_s"]["mean"] is not None else None,
                            ci95=m["rise63_s"]["ci95"] * 1e3 if m["rise63_s"]["ci95"] is not None else None)
                lines.append(f"| {r['rpm']:g} | {r['load_Nm']:g} | {r['fidelity']} | {cell(m['gain_N_per_bar'], 1)} | "
                             f"{cell(rise, 1)} |")
            lines.append("")
            continue
        channel_names = list(rows[0]["modes"][name]["shape"])
        lines += [f"## {name}", "", "| rpm | load [N m] | fidelity | frequency [Hz] | damping ratio | coherent | " +
                  " | ".join(f"{c}: ratio, phase [deg]" for c in channel_names) + " |",
                  "|---|---|---|---|---|---|" + "---|" * len(channel_names)]
        for r in rows:
            m = r["modes"][name]
            shape = " | ".join(f"{cell(m['shape'][c]['ratio'], 2)}, {cell(m['shape'][c]['phase_deg'], 0)}" for c in channel_names)
            if m["notAMode"]:
                lines.append(f"| {r['rpm']:g} | {r['load_Nm']:g} | {r['fidelity']} | no mode: {m['notAMode']} | | "
                             f"{m['coherent']:.2f} |" + " |" * len(channel_names))
                continue
            lines.append(f"| {r['rpm']:g} | {r['load_Nm']:g} | {r['fidelity']} | {cell(m['frequency_Hz'], 1)} | "
                         f"{cell(m['dampingRatio'], 4)} | {m['coherent']:.2f} | {shape} |")
        lines.append("")
    return lines
