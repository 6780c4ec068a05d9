"""Generates the SYNTHESIZED "measured" tables of harness/tables/data (engine i4-bucket) and
harness/tables/data_sport (engine i4-sport): camshaft load torques and the crankshaft speed over
one engine cycle (720 deg crank) per engine speed, from the physical model of
harness/tables/valvetrain.py plus simulated measurement artefacts. No measurement enters.

    python -m harness tables [--engine i4-bucket|i4-sport] [--out DIR] [--rpm 1000 2000 ...] [--seed N]
    python -m harness tables --drive-tables tests/drives [--out DIR] [--rpm 1000 3000 6000] [--seed N]

--out defaults to the engine's folder (DATA_DIRS). Besides the files it prints the model's
magnitudes (summary) and the table of what the written files hold (files_table, the table of
the folder's README.md).

--drive-tables DRIVES writes a tables folder per test drive, DRIVES/tables/<drive>/ (or
DIR/<drive>/ with --out), for the drives DRIVE_LOADS knows, at 1000, 3000 and 6000 rpm unless
--rpm is given (write_drive_tables; tests/drives/tables/README.md): the shipped crankshaft speed
and, per loaded sprocket, its load: the engine's camshaft loads over the sprocket's own angle
(torque_<sprocket>_<n>rpm.csv, sprocket_angle_deg), the shipped crank-angle camshaft_torque
table, or the high-pressure pump's load (valvetrain.HighPressurePump) over its own angle.

Deterministic: the same seed (and numpy's PCG64 generator) gives byte-identical files; each
engine speed and quantity draws from its own stream (seed, rpm, quantity), so adding or removing
an engine speed does not change the other tables. Quantities (STREAMS): 0 the camshaft torques,
1 the crankshaft speed, 2 a single camshaft carrying both valve trains, 3 the high-pressure pump.

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
A table over a sprocket's own angle gets the same artefacts over one turn of the sprocket (the
low-pass at the sprocket's orders: order m at m times its speed); the pump's cycle-to-cycle
variation is one of its delivery (PUMP_DELIVERY_COV), not of the combustion.
"""
import math
import pathlib

import numpy as np

from .. import paths
from . import valvetrain
from .tables import ANGLE, DATA_DIR, PERIOD_DEG, SPROCKET_ANGLE, SPROCKET_PERIOD_DEG, load, tabulated_speeds

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
# random streams per quantity: _rng(seed, rpm, stream)
STREAMS = {"camshaft torque": 0, "crankshaft speed": 1, "single camshaft": 2, "pump": 3}

# the test drives' tables (write_drive_tables)
SPROCKET_RESOLUTION_DEG = 0.5    # own-angle table step [deg of the sprocket]: rows 0.0 ... 359.5
DRIVE_RPMS = (1000, 3000, 6000)
PUMP_DELIVERY_COV = 0.03         # [E] cycle-to-cycle variation of the pump's delivery (rail pressure ripple)
CRANK_TABLE = "camshaft_torque"  # a load from the shipped crank-angle table's column <name>.tau
PUMP = "pump"                    # the high-pressure pump's load, valvetrain.HP_PUMP
# {drive (the JSON's stem): {loaded sprocket: its load}}: a tuple of the engine's camshafts
# (valvetrain.Engine.camshafts by name), summed, over the sprocket's own angle; CRANK_TABLE; PUMP
DRIVE_LOADS = {
    "dohc_8mm": {"intakeCam": ("camshaftIntake",), "exhaustCam": ("camshaftExhaust",)},
    "sohc_single_cam": {"camshaft": ("camshaftIntake", "camshaftExhaust")},
    "idler": {"camshaft": ("camshaftIntake", "camshaftExhaust")},
    "diesel_pump": {"camshaftIntake": CRANK_TABLE, "camshaftExhaust": CRANK_TABLE, "hpPump": PUMP},
}

PROVENANCE_TORQUE = ("SYNTHESIZED by harness/tables/make_tables.py (valve-train model, "
                     "harness/tables/valvetrain.py), not a measurement")
PROVENANCE_SPEED = ("SYNTHESIZED by harness/tables/make_tables.py (crankshaft speed model, "
                    "harness/tables/valvetrain.py), not a measurement")
PROVENANCE_PUMP = ("SYNTHESIZED by harness/tables/make_tables.py (high-pressure pump model, "
                   "harness/tables/valvetrain.py), not a measurement")


def angles():
    return np.arange(0.0, 720.0, RESOLUTION_DEG)


def sprocket_angles():
    """The rows of an own-angle table: 0.0 ... 359.5 deg of the sprocket."""
    return np.arange(0.0, SPROCKET_PERIOD_DEG, SPROCKET_RESOLUTION_DEG)


def _rng(seed, rpm, stream):
    return np.random.default_rng([int(seed), int(round(rpm * 1000)), stream])


def lowpass_periodic(y, rpm, cutoff_hz, period_crank_deg=PERIOD_DEG):
    """Periodic steady state of a first-order low-pass 1 / (1 + i f / f_c) on one period of
    period_crank_deg crank degrees (default one 720-deg cycle; a sprocket's turn: 360 deg times
    its ratio) sampled uniformly: bin m holds m cycles per period, i.e. f = m n / (period / 6) Hz
    (m n / 120 for 720 deg)."""
    Y = np.fft.rfft(y)
    f = np.arange(len(Y)) * rpm / (period_crank_deg / 6.0)
    return np.fft.irfft(Y / (1.0 + 1j * f / cutoff_hz), n=len(y))


def _quantize(y, step):
    return np.rint(y / step) * step + 0.0  # + 0.0 turns -0.0 into 0.0


def _measure(signal, rng, scales, rpm, period_crank_deg=PERIOD_DEG):
    """A torque "measured" (steps 1-4 of the module text) over one period of uniform samples:
    signal(scale) is the physical torque [N m] of a cycle with the variation `scale` (1.0: the
    nominal one); one cycle per scale, each with white noise of NOISE_FRACTION times the nominal
    signal's alternating amplitude, averaged, low-passed (period_crank_deg: the crank degrees of
    the period), offset and quantized. Returns (table values, nominal signal, noise sigma, offset)."""
    clean = signal(1.0)
    sigma = NOISE_FRACTION * 0.5 * (clean.max() - clean.min())
    acc = np.zeros_like(clean)
    for s in scales:
        acc += signal(s)
        acc += sigma * rng.standard_normal(len(clean))
    y = lowpass_periodic(acc / len(scales), rpm, TORQUE_BANDWIDTH_HZ, period_crank_deg)
    offset = TORQUE_OFFSET_SD * rng.standard_normal()
    return _quantize(y + offset, TORQUE_STEP), clean, sigma, offset


def camshaft_torques(rpm, seed=DEFAULT_SEED, engine=valvetrain.DEFAULT_ENGINE):
    """{column: torque [N m]} over angles() with the artefacts, plus the physical signals and
    notes for the header."""
    theta = angles()
    rng = _rng(seed, rpm, STREAMS["camshaft torque"])
    scales = 1.0 + COMBUSTION_COV * rng.standard_normal(CYCLES)
    out, physical, notes = {}, {}, {}
    for train in engine.camshafts:
        def signal(s, train=train):
            return valvetrain.camshaft_load(train, theta, rpm, engine, crank_scale=s).total
        col = train.name + ".tau"
        out[col], physical[col], sigma, offset = _measure(signal, rng, scales, rpm)
        notes[col] = (sigma, offset)
    return out, physical, notes


def single_camshaft_torque(rpm, seed=DEFAULT_SEED, engine=valvetrain.DEFAULT_ENGINE, trains=None):
    """The load of one camshaft carrying the valve trains `trains` (names; default all of the
    engine's: a single camshaft driving the intake and the exhaust valves), the sum of their
    loads, "measured" once over its own angle sprocket_angles() (crank angle 2 x camshaft angle).
    Returns (torque [N m] with the artefacts, the physical sum, noise sigma, offset)."""
    names = list(trains) if trains is not None else [t.name for t in engine.camshafts]
    chosen = [_train(engine, n) for n in names]
    theta = 2.0 * sprocket_angles()
    rng = _rng(seed, rpm, STREAMS["single camshaft"])
    scales = 1.0 + COMBUSTION_COV * rng.standard_normal(CYCLES)

    def signal(s):
        return sum(valvetrain.camshaft_load(t, theta, rpm, engine, crank_scale=s).total for t in chosen)
    return _measure(signal, rng, scales, rpm, 2.0 * SPROCKET_PERIOD_DEG)


def pump_torque(rpm, ratio, seed=DEFAULT_SEED, pump=valvetrain.HP_PUMP):
    """The high-pressure pump's load over its own angle sprocket_angles(), "measured": ratio is
    the crank revolutions per pump revolution (the low-pass acts at the pump's orders). Returns
    (torque [N m] with the artefacts, the physical torque, noise sigma, offset)."""
    psi = sprocket_angles()
    rng = _rng(seed, rpm, STREAMS["pump"])
    scales = 1.0 + PUMP_DELIVERY_COV * rng.standard_normal(CYCLES)
    return _measure(lambda s: pump.torque(psi, rpm, s), rng, scales, rpm, SPROCKET_PERIOD_DEG * ratio)


def _train(engine, name):
    for t in engine.camshafts:
        if t.name == name:
            return t
    raise ValueError(f"engine {engine.name} has no camshaft '{name}' (it has "
                     f"{', '.join(t.name for t in engine.camshafts)})")


def crankshaft_speed(rpm, seed=DEFAULT_SEED, engine=valvetrain.DEFAULT_ENGINE):
    """Crankshaft speed [rpm] over angles() with the artefacts, and the physical signal."""
    theta = angles()
    rng = _rng(seed, rpm, STREAMS["crankshaft speed"])
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


def _torque_artefacts(notes):
    """The `artefacts:` line of a torque table; notes: {column: (noise sigma, offset)}."""
    return (f"artefacts: average of {CYCLES} cycles, per-cycle sensor noise "
            + ", ".join(f"{c} {s:.3f}" for c, (s, _) in notes.items())
            + f" N.m RMS; first-order low-pass {TORQUE_BANDWIDTH_HZ:g} Hz; offset "
            + ", ".join(f"{c} {o:+.3f}" for c, (_, o) in notes.items())
            + f" N.m; quantized to {TORQUE_STEP:g} N.m")


def _write_camshaft_torque(out_dir, rpm, seed, engine, torques=None):
    """camshaft_torque_<n>rpm.csv of `engine` (torques: camshaft_torques' result if already computed)."""
    tau, _, notes = torques if torques is not None else camshaft_torques(rpm, seed, engine)
    extra = _common_notes(seed, engine) + [_torque_artefacts(notes)]
    path = pathlib.Path(out_dir) / f"camshaft_torque_{rpm:g}rpm.csv"
    with open(path, "w", newline="\n") as f:
        f.write(_header("camshaft load torque", rpm, PROVENANCE_TORQUE,
                        "crank_angle_deg in degrees crank angle from cylinder 1 firing TDC; torque in N.m, "
                        "positive when it opposes the camshaft rotation", extra))
        cols = list(tau)
        f.write(",".join([ANGLE] + cols) + "\n")
        for i, th in enumerate(angles()):
            f.write(f"{th:.1f}," + ",".join(f"{tau[c][i]:.2f}" for c in cols) + "\n")
    return path


def _write_crankshaft_speed(out_dir, rpm, seed, engine, measured=None):
    """crankshaft_speed_<n>rpm.csv of `engine` (measured: crankshaft_speed's result if already computed)."""
    speed, _, sigma = measured if measured is not None else crankshaft_speed(rpm, seed, engine)
    extra = _common_notes(seed, engine) + [
        f"artefacts: average of {CYCLES} cycles with {100 * COMBUSTION_COV:g} % cycle-to-cycle variation of "
        f"the fluctuation, per-cycle sensor noise {sigma:.3f} rpm RMS; first-order low-pass "
        f"{SPEED_BANDWIDTH_HZ:g} Hz; mean set to the engine speed; quantized to {SPEED_STEP:g} rpm",
    ]
    path = pathlib.Path(out_dir) / f"crankshaft_speed_{rpm:g}rpm.csv"
    with open(path, "w", newline="\n") as f:
        f.write(_header("crankshaft speed", rpm, PROVENANCE_SPEED,
                        "crank_angle_deg in degrees crank angle from cylinder 1 firing TDC; crankshaft.speed_rpm "
                        "in rpm (absolute crankshaft speed, positive in the running direction)", extra))
        f.write(f"{ANGLE},crankshaft.speed_rpm\n")
        for i, th in enumerate(angles()):
            f.write(f"{th:.1f},{speed[i]:.2f}\n")
    return path


def write_tables(out_dir=None, rpms=DEFAULT_RPMS, seed=DEFAULT_SEED, engine=valvetrain.DEFAULT_ENGINE):
    """Writes camshaft_torque_<n>rpm.csv and crankshaft_speed_<n>rpm.csv of `engine` into out_dir
    (default: the engine's folder, DATA_DIRS); returns the paths."""
    out_dir = pathlib.Path(out_dir) if out_dir is not None else DATA_DIRS[engine.name]
    out_dir.mkdir(parents=True, exist_ok=True)
    written = []
    for rpm in rpms:
        written.append(_write_camshaft_torque(out_dir, rpm, seed, engine))
        written.append(_write_crankshaft_speed(out_dir, rpm, seed, engine))
    return written


# ---------------------------------------------------------------------------------------------
# the test drives' tables: a folder per drive, a table per loaded sprocket

def _shown(path):
    """A path as the headers show it: relative to the repository if inside it (so the files do
    not depend on where the repository lies), else absolute."""
    path = pathlib.Path(path).resolve()
    try:
        return path.relative_to(paths.ROOT).as_posix()
    except ValueError:
        return path.as_posix()


def _engine_option(engine):
    return "" if engine.name == valvetrain.DEFAULT_ENGINE.name else f" --engine {engine.name}"


def _drive_option(drives_dir, seed, engine):
    return f"generator: python -m harness tables{_engine_option(engine)} --drive-tables {_shown(drives_dir)} --seed {seed}"


def _user_drive_option(drive, loads, seed, engine):
    return (f"generator: python -m harness tables{_engine_option(engine)} --drive {_shown(pathlib.Path(drive))} "
            + " ".join(f"--sprocket-load {item}" for item in loads) + f" --seed {seed}")


def _write_sprocket_torque(path, name, rpm, quantity, provenance, lines, values):
    """An own-angle table torque_<name>_<n>rpm.csv: sprocket_angle_deg over sprocket_angles() and
    the column <name>.tau; lines: the header lines after `units:` (`phase:` first)."""
    units = (f"{SPROCKET_ANGLE} in degrees of the sprocket's own rotation from its start (the FMU's {name}.phi = 0); "
             "torque in N.m, positive when it opposes the sprocket rotation")
    with open(path, "w", newline="\n") as f:
        f.write(_header(quantity, rpm, provenance, units, lines))
        f.write(f"{SPROCKET_ANGLE},{name}.tau\n")
        for a, v in zip(sprocket_angles(), values):
            f.write(f"{a:.1f},{v:.2f}\n")
    return path


def _sprocket_sampling(ratio, what):
    step = SPROCKET_RESOLUTION_DEG * ratio
    return (f"sampling: {SPROCKET_RESOLUTION_DEG:g} deg {what} ({step:.4g} deg crank), 0.0 to "
            f"{SPROCKET_PERIOD_DEG - SPROCKET_RESOLUTION_DEG:g} deg; periodic over one turn of the sprocket "
            f"({SPROCKET_PERIOD_DEG * ratio:.4g} deg crank; the value at 360 is the value at 0)")


def _drive_line(drive_path, name, teeth, crank, ratio):
    return (f"drive: {_shown(drive_path)}, sprocket {name}: {teeth} teeth on a {crank}-tooth crankshaft sprocket, "
            f"{ratio:.4g} crank degrees per sprocket degree")


def _camshaft_table(out, drive_path, elements, name, trains, rpm, seed, engine, torques, generator):
    """torque_<name>_<n>rpm.csv of a camshaft sprocket carrying the valve trains `trains`: one
    train is the shipped crank-angle table's column, every second row (crank angle 2 x camshaft
    angle); several are a single camshaft's sum, measured once (single_camshaft_torque)."""
    ratio = elements.ratio(name)
    if abs(ratio - 2.0) > 1e-12:
        raise ValueError(f"{drive_path}: sprocket {name} turns at 1/{ratio:g} of the crankshaft speed; a camshaft's "
                         "load needs 1/2")
    teeth = next(s.teeth for s in elements.free if s.name == name)
    data = f"harness/tables/{DATA_DIRS[engine.name].name}/camshaft_torque_{rpm:g}rpm.csv"
    if len(trains) == 1:
        col = _train(engine, trains[0]).name + ".tau"
        rows = np.rint(2.0 * sprocket_angles() / RESOLUTION_DEG).astype(int)
        values = torques[0][col][rows]
        source = (f"load: the engine's camshaft {col[:-4]}: column {col} of {data} at crank angle 2 x sprocket "
                  f"angle (its rows at 0, 1, ..., 719 deg crank)")
        notes = {name + ".tau": torques[2][col]}
    else:
        values, _, sigma, offset = single_camshaft_torque(rpm, seed, engine, trains)
        source = (f"load: a single camshaft driving the valves of {' and '.join(trains)}: the sum of their model loads "
                  f"(each camshaft's bearing drag included), measured once (random stream "
                  f"{STREAMS['single camshaft']}); crank angle = 2 x sprocket angle from cylinder 1 firing TDC")
        notes = {name + ".tau": (sigma, offset)}
    lines = ["phase: 0 deg", _sprocket_sampling(ratio, "camshaft"), _drive_line(drive_path, name, teeth,
             elements.crank_teeth, ratio), source] + _common_notes(seed, engine)[1:2] + \
        [generator, _torque_artefacts(notes)]
    return _write_sprocket_torque(out / f"torque_{name}_{rpm:g}rpm.csv", name, rpm, "camshaft load torque",
                                  PROVENANCE_TORQUE, lines, values)


def _pump_table(out, drive_path, elements, name, rpm, seed, generator, engine, pump=valvetrain.HP_PUMP):
    """torque_<name>_<n>rpm.csv of the high-pressure pump (pump_torque)."""
    ratio = elements.ratio(name)
    teeth = next(s.teeth for s in elements.free if s.name == name)
    values, _, sigma, offset = pump_torque(rpm, ratio, seed, pump)
    p = pump.rail_pressure(rpm)
    lines = [
        "phase: 0 deg", _sprocket_sampling(ratio, "pump"),
        _drive_line(drive_path, name, teeth, elements.crank_teeth, ratio)
        + f" (the pump at {1.0 / ratio:.4g} x crank speed)",
        f"pump: single plunger on a {pump.lobes}-lobe cam, a half-sine torque pulse per lobe on its delivery stroke "
        f"(from {pump.delivery_start_deg:g} deg pump angle, every {360.0 / pump.lobes:g} deg, "
        f"{180.0 / pump.lobes:g} deg long), {pump.lobes} pulses per turn; estimates [E]: displacement {pump.displacement * 1e6:g} cm^3 per turn, "
        f"rail pressure {p / 1e5:g} bar at full delivery, efficiency {pump.efficiency:g}, drag {pump.drag:g} N.m: "
        f"mean {pump.mean(rpm):.3f} N.m, pulse peak {pump.peak(rpm):.3f} N.m above the drag; model in "
        "harness/tables/valvetrain.py (HighPressurePump) and tests/drives/tables/README.md",
        generator,
        f"artefacts: average of {CYCLES} pump turns with {100 * PUMP_DELIVERY_COV:g} % turn-to-turn variation of "
        f"the delivery, per-turn sensor noise {sigma:.3f} N.m RMS; first-order low-pass {TORQUE_BANDWIDTH_HZ:g} Hz; "
        f"offset {offset:+.3f} N.m; quantized to {TORQUE_STEP:g} N.m",
    ]
    return _write_sprocket_torque(out / f"torque_{name}_{rpm:g}rpm.csv", name, rpm, "high-pressure pump load torque",
                                  PROVENANCE_PUMP, lines, values)


def write_drive_tables(drives_dir, out_dir=None, rpms=DRIVE_RPMS, seed=DEFAULT_SEED,
                       engine=valvetrain.DEFAULT_ENGINE, drives=None):
    """Writes the tables folder of each test drive drives_dir/<drive>.json of DRIVE_LOADS (or of
    `drives`, its names) into out_dir/<drive>/ (default drives_dir/tables/<drive>/): at each
    engine speed the engine's crankshaft_speed_<n>rpm.csv (the shipped file) and each loaded
    sprocket's load as DRIVE_LOADS gives it. The drive's loaded sprockets must be those
    DRIVE_LOADS names. Returns the paths written."""
    drives_dir = pathlib.Path(drives_dir)
    out_dir = pathlib.Path(out_dir) if out_dir is not None else drives_dir / "tables"
    written, cache = [], {}
    for drive in (drives if drives is not None else sorted(DRIVE_LOADS)):
        if drive not in DRIVE_LOADS:
            raise ValueError(f"no loads known for the drive '{drive}'; make_tables.DRIVE_LOADS has "
                             f"{', '.join(sorted(DRIVE_LOADS))}")
        path = drives_dir / f"{drive}.json"
        if not path.is_file():
            raise ValueError(f"--drive-tables {drives_dir}: no {path.name} there (make_tables.DRIVE_LOADS names it)")
        written += write_sprocket_tables(path, DRIVE_LOADS[drive], out_dir / drive, rpms, seed, engine,
                                         _drive_option(drives_dir, seed, engine), cache)
    return written


def write_sprocket_tables(path, spec, out, rpms, seed, engine, generator, cache=None):
    """The tables folder `out` of the drive `path` whose loaded sprockets carry the loads `spec`
    ({sprocket: a tuple of the engine's camshafts, CRANK_TABLE or PUMP}): at each engine speed the
    engine's crankshaft speed and each sprocket's load; `generator` is the command line the files
    name. Returns the paths written."""
    from ..drive.description import elements as drive_elements
    el = drive_elements(path)
    if sorted(el.loaded) != sorted(spec):
        raise ValueError(f"{path}: its loaded sprockets {', '.join(el.loaded) or 'none'} are not those the tables "
                         f"load ({', '.join(spec)})")
    out = pathlib.Path(out)
    out.mkdir(parents=True, exist_ok=True)
    cache = {} if cache is None else cache
    written = []
    for rpm in rpms:
        if rpm not in cache:
            cache[rpm] = (camshaft_torques(rpm, seed, engine), crankshaft_speed(rpm, seed, engine))
        torques, speed = cache[rpm]
        written.append(_write_crankshaft_speed(out, rpm, seed, engine, speed))
        if CRANK_TABLE in spec.values():
            written.append(_write_camshaft_torque(out, rpm, seed, engine, torques))
        for name in el.loaded:
            load = spec[name]
            if load == PUMP:
                written.append(_pump_table(out, path, el, name, rpm, seed, generator, engine))
            elif load != CRANK_TABLE:
                written.append(_camshaft_table(out, path, el, name, load, rpm, seed, engine, torques, generator))
    return written


# --sprocket-load NAME=KIND: what a user's sprocket carries
LOAD_KINDS = {"intake": ("camshaftIntake",), "exhaust": ("camshaftExhaust",),
              "intake+exhaust": ("camshaftIntake", "camshaftExhaust"), "pump": PUMP}


def sprocket_loads_option(values, drive):
    """{sprocket: load} of --sprocket-load NAME=KIND ...; every loaded sprocket of the drive once."""
    from ..drive.description import elements as drive_elements
    loaded = drive_elements(drive).loaded
    spec = {}
    for item in values or []:
        name, _, kind = item.partition("=")
        if name not in loaded:
            raise ValueError(f"--sprocket-load {item}: '{name}' is not a loaded sprocket of {drive} "
                             f"({', '.join(loaded) or 'none'})")
        if kind not in LOAD_KINDS:
            raise ValueError(f"--sprocket-load {item}: '{kind}' is not one of {', '.join(LOAD_KINDS)}")
        spec[name] = LOAD_KINDS[kind]
    missing = [n for n in loaded if n not in spec]
    if missing:
        raise ValueError(f"--sprocket-load: no load for {', '.join(missing)} (give NAME=KIND for every loaded "
                         f"sprocket of {drive}: {', '.join(loaded)}; KIND one of {', '.join(LOAD_KINDS)})")
    return spec


def pump_summary(rpms=DRIVE_RPMS, pump=valvetrain.HP_PUMP):
    """Text table of the pump model per engine speed (no artefacts)."""
    lines = ["rpm   rail [bar]  mean [N m]  peak above drag [N m]"]
    for rpm in rpms:
        lines.append(f"{rpm:<5g} {pump.rail_pressure(rpm) / 1e5:10.0f}  {pump.mean(rpm):10.3f}  {pump.peak(rpm):10.3f}")
    return "\n".join(lines)


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
                    "i4-bucket, harness/tables/data_sport for i4-sport; with --drive-tables DRIVES/tables)")
    ap.add_argument("--rpm", type=float, nargs="+", default=None,
                    help=f"engine speeds [rpm] (default {' '.join(map(str, DEFAULT_RPMS))}; with --drive-tables "
                         f"{' '.join(map(str, DRIVE_RPMS))})")
    ap.add_argument("--drive-tables", metavar="DRIVES",
                    help="write the test drives' tables instead: a folder per drive DRIVES/<drive>.json that "
                         f"make_tables.DRIVE_LOADS knows ({', '.join(sorted(DRIVE_LOADS))}), DRIVES/tables/<drive>/ "
                         "(or OUT/<drive>/), e.g. --drive-tables tests/drives")
    ap.add_argument("--drive", help="write the tables of this drive's loaded sprockets instead (into --out, default "
                    "results/tables/<drive>/), each carrying the load --sprocket-load gives it")
    ap.add_argument("--sprocket-load", action="append", metavar="NAME=KIND",
                    help=f"with --drive: the load of the loaded sprocket NAME, KIND one of {', '.join(LOAD_KINDS)} "
                         "(a camshaft driving the engine's intake valves, its exhaust valves or both; the "
                         "high-pressure pump); once per loaded sprocket")
    ap.add_argument("--seed", type=int, default=DEFAULT_SEED, help=f"random seed (default {DEFAULT_SEED})")
    ap.add_argument("--quiet", action="store_true", help="do not print the summary")


def run_drive(args, engine):
    """--drive FILE --sprocket-load NAME=KIND ...: the tables of a user's drive."""
    from ..errors import UserError
    rpms = args.rpm or list(DRIVE_RPMS)
    out = pathlib.Path(args.out or paths.RESULTS / "tables" / pathlib.Path(args.drive).stem)
    try:
        spec = sprocket_loads_option(args.sprocket_load, args.drive)
        written = write_sprocket_tables(args.drive, spec, out, rpms, args.seed, engine,
                                        _user_drive_option(args.drive, args.sprocket_load, args.seed, engine))
    except ValueError as e:
        raise UserError(str(e)) from None
    if not args.quiet:
        for p in written:
            print(p)
    print(f"written: {len(written)} tables into {out} (run the drive with --drive {args.drive} --tables {out})")
    return 0


def run(args):
    engine = valvetrain.ENGINES[args.engine]
    if args.drive:
        return run_drive(args, engine)
    if args.drive_tables:
        rpms = args.rpm or list(DRIVE_RPMS)
        try:
            written = write_drive_tables(args.drive_tables, args.out, rpms, args.seed, engine)
        except ValueError as e:
            from ..errors import UserError
            raise UserError(str(e)) from None
        if not args.quiet:
            for p in written:
                print(p)
            print("the high-pressure pump model without artefacts (valvetrain.HP_PUMP):")
            print(pump_summary(rpms))
        return 0
    args.rpm = args.rpm or list(DEFAULT_RPMS)
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
