"""Generates the SYNTHESIZED "measured" tables of harness/tables/data (engine i4-bucket) and
harness/tables/data_sport (engine i4-sport): camshaft load torques and the crankshaft speed over
one engine cycle (720 deg crank) per engine speed, from the physical model of
harness/tables/valvetrain.py plus simulated measurement artefacts. No measurement enters.

    python -m harness tables [--engine i4-bucket|i4-sport] [--out DIR] [--rpm 1000 2000 ...] [--seed N]

--out defaults to the engine's folder (DATA_DIRS). Besides the files it prints the model's
magnitudes (summary) and the table of what the written files hold (files_table, the table of
the folder's README.md).

Deterministic: the same seed (and numpy's PCG64 generator) gives byte-identical files; each
engine speed and quantity draws from its own stream (seed, rpm, quantity), so adding or removing
an engine speed does not change the other tables.

Measurement artefacts, in the order applied (see harness/tables/data/README.md):
1. CYCLES engine cycles are "recorded"; each has its own combustion variation (the crankshaft
   speed fluctuation scaled by 1 + 0.03 N(0, 1), a 3 % coefficient of variation) and white
   sensor noise per sample of NOISE_FRACTION times the signal's alternating amplitude
   (half its peak-to-peak); the table is their phase-locked average (noise / 4 for 16 cycles).
2. Limited sensor bandwidth: a first-order low-pass (torque 2 kHz, crank speed 3 kHz) applied
   as its periodic steady state (in the frequency domain over the cycle, engine order k at
   k n / 60 Hz), with its amplitude loss and phase lag.
3. Offset: the torque sensor's zero error, N(0, 0.05 N m) per camshaft; the crankshaft speed has
   no offset (its mean over the crank angle is set to the engine speed, the operating point).
4. Quantization: torque to 0.01 N m, speed to 0.01 rpm.
"""
import math
import pathlib

import numpy as np

from . import valvetrain
from .tables import DATA_DIR, load, tabulated_speeds

RESOLUTION_DEG = 0.5          # table step; rows 0.0 ... 719.5 (the value at 720 is the one at 0)
DEFAULT_RPMS = (1000, 2000, 3000, 4000, 5000, 6000)
DEFAULT_SEED = 20240601
CYCLES = 16                   # cycles averaged per table
NOISE_FRACTION = 0.08         # per-sample sensor noise of one cycle / alternating amplitude
COMBUSTION_COV = 0.03         # cycle-to-cycle variation of the crank speed fluctuation
TORQUE_BANDWIDTH_HZ = 2000.0  # torque measuring shaft with telemetry [E]
SPEED_BANDWIDTH_HZ = 3000.0   # encoder-based speed measurement [E]
TORQUE_OFFSET_SD = 0.05       # N m
TORQUE_STEP = 0.01            # N m
SPEED_STEP = 0.01             # rpm
# each engine's folder of shipped tables
DATA_DIRS = {"i4-bucket": DATA_DIR, "i4-sport": DATA_DIR.parent / "data_sport"}

PROVENANCE_TORQUE = ("SYNTHESIZED by harness/tables/make_tables.py (valve-train model, "
                     "harness/tables/valvetrain.py), not a measurement")
PROVENANCE_SPEED = ("SYNTHESIZED by harness/tables/make_tables.py (crankshaft speed model, "
                    "harness/tables/valvetrain.py), not a measurement")


def angles():
    return np.arange(0.0, 720.0, RESOLUTION_DEG)


def _rng(seed, rpm, stream):
    return np.random.default_rng([int(seed), int(round(rpm * 1000)), stream])


def lowpass_periodic(y, rpm, cutoff_hz):
    """Periodic steady state of a first-order low-pass 1 / (1 + i f / f_c) on one 720-deg cycle
    sampled uniformly: bin m holds m cycles per 720 deg, i.e. f = m n / 120 Hz."""
    Y = np.fft.rfft(y)
    f = np.arange(len(Y)) * rpm / 120.0
    return np.fft.irfft(Y / (1.0 + 1j * f / cutoff_hz), n=len(y))


def _quantize(y, step):
    return np.rint(y / step) * step + 0.0  # + 0.0 turns -0.0 into 0.0


def camshaft_torques(rpm, seed=DEFAULT_SEED, engine=valvetrain.DEFAULT_ENGINE):
    """{column: torque [N m]} over angles() with the artefacts, plus the physical signals and
    notes for the header."""
    theta = angles()
    rng = _rng(seed, rpm, 0)
    scales = 1.0 + COMBUSTION_COV * rng.standard_normal(CYCLES)
    out, physical, notes = {}, {}, {}
    for train in engine.camshafts:
        clean = valvetrain.camshaft_load(train, theta, rpm, engine).total
        sigma = NOISE_FRACTION * 0.5 * (clean.max() - clean.min())
        acc = np.zeros_like(theta)
        for s in scales:
            acc += valvetrain.camshaft_load(train, theta, rpm, engine, crank_scale=s).total
            acc += sigma * rng.standard_normal(len(theta))
        y = lowpass_periodic(acc / CYCLES, rpm, TORQUE_BANDWIDTH_HZ)
        offset = TORQUE_OFFSET_SD * rng.standard_normal()
        col = train.name + ".tau"
        out[col] = _quantize(y + offset, TORQUE_STEP)
        physical[col] = clean
        notes[col] = (sigma, offset)
    return out, physical, notes


def crankshaft_speed(rpm, seed=DEFAULT_SEED, engine=valvetrain.DEFAULT_ENGINE):
    """Crankshaft speed [rpm] over angles() with the artefacts, and the physical signal."""
    theta = angles()
    rng = _rng(seed, rpm, 1)
    to_rpm = 60.0 / (2.0 * math.pi)
    crank = engine.crank
    clean = crank.speed(theta, rpm)[0] * to_rpm
    sigma = NOISE_FRACTION * 0.5 * (clean.max() - clean.min())
    acc = np.zeros_like(theta)
    for _ in range(CYCLES):
        s = 1.0 + COMBUSTION_COV * rng.standard_normal()
        acc += crank.speed(theta, rpm, s)[0] * to_rpm + sigma * rng.standard_normal(len(theta))
    y = lowpass_periodic(acc / CYCLES, rpm, SPEED_BANDWIDTH_HZ)
    y += rpm - y.mean()
    return _quantize(y, SPEED_STEP), clean, sigma


def _header(quantity, rpm, provenance, units, extra):
    lines = [f"chaindrive table: {quantity}", f"engine speed: {rpm:g} rpm", f"provenance: {provenance}",
             f"units: {units}"] + extra
    return "".join(f"# {l}\n" for l in lines)


def _common_notes(seed, engine):
    """The sampling, engine and generator lines. The default engine's lines are those its tables
    had before there was a second engine (no name, no --engine), so its files stay byte-identical;
    another engine's name leads its engine line and its --engine the generator line."""
    readme = f"harness/tables/{DATA_DIRS[engine.name].name}/README.md"
    if engine.name == valvetrain.DEFAULT_ENGINE.name:
        name, option = "", ""
    else:
        name, option = f"{engine.name}, ", f" --engine {engine.name}"
    return [
        f"sampling: {RESOLUTION_DEG:g} deg crank, 0.0 to {720.0 - RESOLUTION_DEG:g} deg; periodic over one "
        "720-deg engine cycle (the value at 720 is the value at 0)",
        f"engine: {name}{engine.description}; model and parameters in harness/tables/valvetrain.py and {readme}",
        f"generator: python -m harness tables{option} --seed {seed}",
    ]


def write_tables(out_dir=None, rpms=DEFAULT_RPMS, seed=DEFAULT_SEED, engine=valvetrain.DEFAULT_ENGINE):
    """Writes camshaft_torque_<n>rpm.csv and crankshaft_speed_<n>rpm.csv of `engine` into out_dir
    (default: the engine's folder, DATA_DIRS); returns the paths."""
    out_dir = pathlib.Path(out_dir) if out_dir is not None else DATA_DIRS[engine.name]
    out_dir.mkdir(parents=True, exist_ok=True)
    theta = angles()
    written = []
    for rpm in rpms:
        tau, _, notes = camshaft_torques(rpm, seed, engine)
        extra = _common_notes(seed, engine) + [
            f"artefacts: average of {CYCLES} cycles, per-cycle sensor noise "
            + ", ".join(f"{c} {s:.3f}" for c, (s, _) in notes.items())
            + f" N.m RMS; first-order low-pass {TORQUE_BANDWIDTH_HZ:g} Hz; offset "
            + ", ".join(f"{c} {o:+.3f}" for c, (_, o) in notes.items())
            + f" N.m; quantized to {TORQUE_STEP:g} N.m",
        ]
        path = out_dir / f"camshaft_torque_{rpm:g}rpm.csv"
        with open(path, "w", newline="\n") as f:
            f.write(_header("camshaft load torque", rpm, PROVENANCE_TORQUE,
                            "crank_angle_deg in degrees crank angle from cylinder 1 firing TDC; torque in N.m, "
                            "positive when it opposes the camshaft rotation", extra))
            cols = list(tau)
            f.write(",".join(["crank_angle_deg"] + cols) + "\n")
            for i, th in enumerate(theta):
                f.write(f"{th:.1f}," + ",".join(f"{tau[c][i]:.2f}" for c in cols) + "\n")
        written.append(path)

        speed, _, sigma = crankshaft_speed(rpm, seed, engine)
        extra = _common_notes(seed, engine) + [
            f"artefacts: average of {CYCLES} cycles with {100 * COMBUSTION_COV:g} % cycle-to-cycle variation of "
            f"the fluctuation, per-cycle sensor noise {sigma:.3f} rpm RMS; first-order low-pass "
            f"{SPEED_BANDWIDTH_HZ:g} Hz; mean set to the engine speed; quantized to {SPEED_STEP:g} rpm",
        ]
        path = out_dir / f"crankshaft_speed_{rpm:g}rpm.csv"
        with open(path, "w", newline="\n") as f:
            f.write(_header("crankshaft speed", rpm, PROVENANCE_SPEED,
                            "crank_angle_deg in degrees crank angle from cylinder 1 firing TDC; crankshaft.speed_rpm "
                            "in rpm (absolute crankshaft speed, positive in the running direction)", extra))
            f.write("crank_angle_deg,crankshaft.speed_rpm\n")
            for i, th in enumerate(theta):
                f.write(f"{th:.1f},{speed[i]:.2f}\n")
        written.append(path)
    return written


def summary(rpms=DEFAULT_RPMS, engine=valvetrain.DEFAULT_ENGINE):
    """Text table of the physical model's magnitudes per engine speed (no artefacts)."""
    theta = angles()
    lines = ["rpm   camshaft  mean   p-p   min    max   orders (largest 3)   Fmin[N]  | crank order-2 [deg]  speed min-max [rpm]"]
    for rpm in rpms:
        w = engine.crank.speed(theta, rpm)[0] * 60.0 / (2.0 * math.pi)
        a2 = abs(np.fft.rfft(w)[4]) / len(w) * 2.0 / (2.0 * rpm) / valvetrain.DEG
        for j, train in enumerate(engine.camshafts):
            load = valvetrain.camshaft_load(train, theta, rpm, engine)
            t = load.total
            amp = np.abs(np.fft.rfft(t)) / len(t) * 2.0
            top = sorted(range(1, 80), key=lambda b: -amp[b])[:3]
            orders = ", ".join(f"{b / 2:g}:{amp[b]:.1f}" for b in top)
            crank = f"| {a2:.4f}               {w.min():.0f}-{w.max():.0f}" if j == 0 else ""
            lines.append(f"{rpm:<5g} {train.name[8:]:<8} {t.mean():5.2f} {t.max() - t.min():5.1f} {t.min():6.2f} "
                         f"{t.max():6.2f}  {orders:<20} {load.min_contact_force:6.0f}   {crank}")
    return "\n".join(lines)


def _spectrum(y):
    """One-sided amplitude spectrum of one 720-deg cycle: bin b holds engine order b / 2."""
    return np.abs(np.fft.rfft(y)) / len(y) * 2.0


def _orders(amp, count):
    """The `count` largest engine orders below 40 as 'order (amplitude)'."""
    top = sorted(range(1, 80), key=lambda b: -amp[b])[:count]
    return ", ".join(f"{b / 2:g} ({amp[b]:.1f})" for b in top)


def files_table(data_dir, engine=valvetrain.DEFAULT_ENGINE):
    """Markdown table of what the tables in data_dir hold (artefacts included), per engine speed:
    camshaft torque mean, peak-to-peak (min to max) [N m] and largest engine orders (amplitude
    [N m]); crankshaft order-2 angle amplitude [deg] (the engine's law A_2(n) in brackets), its
    speed amplitude [rpm], the speed range [rpm] and the largest orders (amplitude [rpm])."""
    data_dir = pathlib.Path(data_dir)
    lines = ["| rpm | intake mean | intake p-p | intake orders | exhaust mean | exhaust p-p | exhaust orders "
             "| crank order 2 [deg] | order 2 [rpm] | speed range | speed orders |",
             "|---|---|---|---|---|---|---|---|---|---|---|"]
    for rpm in tabulated_speeds(data_dir):
        t = load(data_dir / f"camshaft_torque_{rpm:g}rpm.csv")
        cells = [f"{rpm:g}"]
        for c in ("camshaftIntake.tau", "camshaftExhaust.tau"):
            y = t.columns[c]
            cells += [f"{y.mean():.2f}", f"{y.max() - y.min():.1f} ({y.min():.1f} to {y.max():.1f})",
                      _orders(_spectrum(y), 3)]
        s = load(data_dir / f"crankshaft_speed_{rpm:g}rpm.csv").columns["crankshaft.speed_rpm"]
        amp = _spectrum(s)
        a2 = math.degrees(amp[4] / (2.0 * rpm))  # speed amplitude of order k = k n x angle amplitude [rad]
        cells += [f"{a2:.3f} ({engine.crank.order2_amplitude_deg(rpm):.3f})", f"{amp[4]:.1f}",
                  f"{s.min():.0f}-{s.max():.0f}", _orders(amp, 2)]
        lines.append("| " + " | ".join(cells) + " |")
    return "\n".join(lines)


def add_arguments(ap):
    ap.add_argument("--engine", choices=list(valvetrain.ENGINES), default=valvetrain.DEFAULT_ENGINE.name,
                    help=f"the engine (default {valvetrain.DEFAULT_ENGINE.name}); see harness/tables/valvetrain.py")
    ap.add_argument("--out", help="output directory (default: the engine's folder, harness/tables/data for "
                    "i4-bucket, harness/tables/data_sport for i4-sport)")
    ap.add_argument("--rpm", type=float, nargs="+", default=list(DEFAULT_RPMS), help="engine speeds [rpm]")
    ap.add_argument("--seed", type=int, default=DEFAULT_SEED, help=f"random seed (default {DEFAULT_SEED})")
    ap.add_argument("--quiet", action="store_true", help="do not print the summary")


def run(args):
    engine = valvetrain.ENGINES[args.engine]
    written = write_tables(args.out, args.rpm, args.seed, engine)
    if not args.quiet:
        for p in written:
            print(p)
        print(f"engine {engine.name}: the model without artefacts")
        print(summary(args.rpm, engine))
        for train in engine.camshafts:
            print(f"{train.name}: contact force reaches zero (valve float) at "
                  f"{valvetrain.float_speed(train, engine):.0f} rpm")
        print(f"\nwhat the tables in {written[0].parent} hold (artefacts included):\n")
        print(files_table(written[0].parent, engine))
    return 0
