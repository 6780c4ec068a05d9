"""Measured-input tables (camshaft load torques, crankshaft speed): loader, engine-speed
interpolation, periodic look-up and conversion into the runner's time-series input CSV.

The format is specified in harness/tables/data/README.md. In short: comment lines start with '#'
(recognised keys: 'chaindrive table:', 'engine speed: <n> rpm', 'provenance:', 'units:'), then a
header whose first column is `crank_angle_deg` (angle-based table: degrees crank angle from
cylinder 1 firing TDC, one 720-deg engine cycle, periodic) or `time_s` (time-based table: a
record in seconds), then comma-separated numbers. Columns used here: `camshaftIntake.tau`,
`camshaftExhaust.tau` [N m, positive opposing the camshaft rotation], `crankshaft.speed_rpm`
[rpm] or `crankshaft.w` [rad/s]; other columns are kept.

The tables shipped in harness/tables/data (and the second engine's in harness/tables/data_sport,
read with data_dir) are SYNTHESIZED (harness/tables/make_tables.py), not measurements; real
measurements in the same format are read the same way.
"""
import dataclasses
import math
import pathlib
import re

import numpy as np


PERIOD_DEG = 720.0
ANGLE = "crank_angle_deg"
SPROCKET_ANGLE = "sprocket_angle_deg"  # a sprocket's own-angle table: degrees of its own rotation, one turn
SPROCKET_PERIOD_DEG = 360.0
TIME = "time_s"
PERIODS = {"angle": PERIOD_DEG, "sprocket": SPROCKET_PERIOD_DEG}  # of the periodic kinds
TORQUE_COLUMNS = ("camshaftIntake.tau", "camshaftExhaust.tau")
SPEED_RPM = "crankshaft.speed_rpm"
SPEED_W = "crankshaft.w"
DATA_DIR = pathlib.Path(__file__).resolve().parent / "data"
RPM_PER_RAD_S = 60.0 / (2.0 * math.pi)


class Table:
    """One table. kind: 'angle' or 'time'; x: crank angle [deg] or time [s]; columns: dict name ->
    numpy array; rpm: engine speed from the header (None if absent); provenance, quantity: str;
    header: all 'key: value' comment lines; path: the file (None if derived)."""

    def __init__(self, kind, x, columns, rpm=None, provenance="", quantity="", header=None, path=None):
        self.kind = kind
        self.x = np.asarray(x, float)
        self.columns = {k: np.asarray(v, float) for k, v in columns.items()}
        self.rpm = rpm
        self.provenance = provenance
        self.quantity = quantity
        self.header = dict(header or {})
        self.path = path

    def __repr__(self):
        where = f" from {self.path}" if self.path else ""
        rpm = f" at {self.rpm:g} rpm" if self.rpm is not None else ""
        return (f"<Table {self.quantity or '?'} ({self.kind}){rpm}, {len(self.x)} rows, "
                f"columns {list(self.columns)}{where}>")


def _number(text):
    v = float(text)  # raises ValueError
    if not math.isfinite(v):
        raise ValueError(text)
    return v


def load(path):
    """Reads a table (see the module text). Raises ValueError naming the file, the line and the
    column for malformed input."""
    path = pathlib.Path(path)
    header, names, data, linenos = _read(path)
    kind = {ANGLE: "angle", SPROCKET_ANGLE: "sprocket"}.get(names[0], "time")
    if kind in PERIODS:
        data = _one_cycle(path, data, linenos, PERIODS[kind], names[0])
    rpm = _engine_speed(path, header)
    header.pop("_engine_speed_line", None)
    columns = {name: data[:, c] for c, name in enumerate(names) if c > 0}
    return Table(kind, data[:, 0], columns, rpm, header.get("provenance", ""), _quantity(header, names), header, path)


def _read(path):
    """(header keys, column names, data rows as an array, their line numbers) of a table file."""
    header, names, rows, linenos = {}, None, [], []
    with open(path, encoding="utf-8") as f:
        for lineno, raw in enumerate(f, start=1):
            line = raw.strip()
            if not line:
                continue
            if line.startswith("#"):
                if names is None:
                    _comment(header, line[1:].strip(), lineno)
                continue
            cells = [c.strip() for c in line.split(",")]
            if names is None:
                names = _column_names(path, lineno, line, cells)
                continue
            rows.append(_row(path, lineno, names, cells, rows[-1] if rows else None))
            linenos.append(lineno)
    if names is None:
        raise ValueError(f"{path}: no header line: expected a line starting with '{ANGLE},' or '{TIME},' "
                         "after the '#' comment lines")
    if len(rows) < 2:
        raise ValueError(f"{path}: {len(rows)} data rows; a table needs at least 2")
    return header, names, np.array(rows, float), linenos


def _comment(header, text, lineno):
    """A comment line before the column names: 'key: value' into header (the first value of a
    key; the line of the last 'engine speed:')."""
    if ":" in text:
        key, value = text.split(":", 1)
        header.setdefault(key.strip().lower(), value.strip())
        if key.strip().lower() == "engine speed":
            header["_engine_speed_line"] = lineno


def _column_names(path, lineno, line, cells):
    """The header line: the column names, checked."""
    if cells[0] not in (ANGLE, SPROCKET_ANGLE, TIME):
        raise ValueError(f"{path}:{lineno}: header expected: the first non-comment line must name the "
                         f"columns, starting with '{ANGLE}', '{SPROCKET_ANGLE}' or '{TIME}'; got '{line[:60]}'")
    for c, name in enumerate(cells):
        if not name:
            raise ValueError(f"{path}:{lineno}: column {c + 1} of the header has no name")
        if name in cells[:c]:
            raise ValueError(f"{path}:{lineno}: column '{name}' appears twice in the header")
    if len(cells) < 2:
        raise ValueError(f"{path}:{lineno}: header '{line}' has no value column")
    return cells


def _row(path, lineno, names, cells, previous):
    """The values of a data row, checked; previous: the row before (None for the first)."""
    if len(cells) != len(names):
        raise ValueError(f"{path}:{lineno}: expected {len(names)} values ({', '.join(names)}), "
                         f"got {len(cells)}")
    vals = []
    for name, cell in zip(names, cells):
        try:
            vals.append(_number(cell))
        except ValueError:
            raise ValueError(f"{path}:{lineno}: column '{name}': '{cell}' is not a finite number") from None
    if previous is not None and vals[0] <= previous[0]:
        raise ValueError(f"{path}:{lineno}: column '{names[0]}': {cells[0]} does not increase "
                         f"(previous row {previous[0]:g}); rows must be in increasing order")
    return vals


def _one_cycle(path, data, linenos, period, column):
    """The rows of an angle table: one period, an engine cycle (720 deg crank) or a sprocket's turn
    (360 deg); a last row at start + period repeats the first one and is dropped; a longer span is
    an error."""
    span = data[-1, 0] - data[0, 0]
    if abs(span - period) <= 1e-9 * period:
        return data[:-1]  # the row at start + period repeats the first one (periodic table)
    if span > period:
        what = "one engine cycle" if period == PERIOD_DEG else "one turn of its sprocket"
        raise ValueError(f"{path}:{linenos[-1]}: column '{column}': the table covers {what} (less than {period:g} "
                         f"deg, or exactly {period:g} with the first row repeated); it spans {span:g} deg")
    return data


def _engine_speed(path, header):
    """The engine speed [rpm] of the 'engine speed:' header line (None without one)."""
    if "engine speed" not in header:
        return None
    m = re.fullmatch(r"([-+0-9.eE]+)\s*(rpm)?", header["engine speed"])
    try:
        rpm = _number(m.group(1)) if m else None
    except ValueError:
        rpm = None
    if rpm is None or rpm <= 0.0:
        raise ValueError(f"{path}:{header['_engine_speed_line']}: 'engine speed:' must be a positive number in "
                         f"rpm, e.g. 'engine speed: 3000 rpm'; got '{header['engine speed']}'")
    return rpm


def _quantity(header, names):
    """What the table holds: the 'chaindrive table:' header, else guessed from the columns."""
    quantity = header.get("chaindrive table", "")
    if not quantity:
        if SPEED_RPM in names or SPEED_W in names:
            quantity = "crankshaft speed"
        elif any(n.endswith(".tau") for n in names):
            quantity = "camshaft load torque"
    return quantity


def lookup(table, column, angle_deg):
    """Periodic linear interpolation of an angle table's column at angle_deg (scalar or array; any
    real angle): a crank-angle table over 720 deg, a sprocket's own-angle table over 360 deg."""
    if table.kind not in PERIODS:
        raise ValueError(f"{table.path or 'table'}: lookup by angle needs an angle table, this one is "
                         f"{table.kind}-based")
    if column not in table.columns:
        raise KeyError(f"{table.path or 'table'}: no column '{column}'; columns: {', '.join(table.columns)}")
    out = np.interp(np.asarray(angle_deg, float), table.x, table.columns[column], period=PERIODS[table.kind])
    return out if np.ndim(out) else float(out)


def _available(data_dir, stem):
    """{rpm: path} of data_dir/<stem>_<n>rpm.csv (the engine speed from the file name)."""
    out = {}
    for p in sorted(pathlib.Path(data_dir).glob(f"{stem}_*rpm.csv")):
        m = re.fullmatch(re.escape(stem) + r"_([0-9]+(?:\.[0-9]+)?)rpm\.csv", p.name)
        if m:
            out[float(m.group(1))] = p
    return out


def _load_checked(path, rpm):
    t = load(path)
    if t.rpm is None:
        t.rpm = rpm
    elif abs(t.rpm - rpm) > 1e-6 * rpm:
        raise ValueError(f"{path}: 'engine speed: {t.rpm:g} rpm' disagrees with the file name ({rpm:g} rpm)")
    return t


def _for_speed(stem, rpm, data_dir):
    """The table for an engine speed: the file for exactly that speed if present, else the
    linear interpolation (per crank angle, weight by engine speed) between the two nearest
    tabulated speeds below and above; ValueError outside the tabulated range."""
    data_dir = pathlib.Path(data_dir) if data_dir is not None else DATA_DIR
    rpm = float(rpm)
    avail = _available(data_dir, stem)
    if not avail:
        raise ValueError(f"{data_dir}: no {stem}_<n>rpm.csv tables")
    for r, p in avail.items():
        if abs(r - rpm) <= 1e-9 * rpm:
            return _load_checked(p, r)
    speeds = sorted(avail)
    lower = [r for r in speeds if r < rpm]
    upper = [r for r in speeds if r > rpm]
    if not lower or not upper:
        raise ValueError(f"{rpm:g} rpm is outside the tabulated range {speeds[0]:g}-{speeds[-1]:g} rpm of "
                         f"{stem}_<n>rpm.csv in {data_dir}")
    r1, r2 = lower[-1], upper[0]
    t1, t2 = _load_checked(avail[r1], r1), _load_checked(avail[r2], r2)
    for t in (t1, t2):
        if t.kind not in PERIODS:
            raise ValueError(f"{t.path}: interpolation between engine speeds needs angle-based tables; this one is "
                             f"time-based (supply a table for exactly {rpm:g} rpm)")
    w = (rpm - r1) / (r2 - r1)
    cols = {c: (1.0 - w) * v + w * lookup(t2, c, t1.x) for c, v in t1.columns.items() if c in t2.columns}
    prov = (f"interpolated linearly in engine speed between {r1:g} rpm ({t1.provenance}) and {r2:g} rpm "
            f"({t2.provenance})")
    header = dict(t1.header, provenance=prov, **{"engine speed": f"{rpm:g} rpm"})
    return Table(t1.kind, t1.x, cols, rpm, prov, t1.quantity, header, None)


def available_speeds(data_dir, stem):
    """The engine speeds [rpm] of the tables data_dir/<stem>_<n>rpm.csv (default folder DATA_DIR)."""
    return list(_available(pathlib.Path(data_dir) if data_dir is not None else DATA_DIR, stem))


def tabulated_speeds(data_dir=None):
    """The engine speeds [rpm] with both a camshaft-torque and a crankshaft-speed table."""
    data_dir = pathlib.Path(data_dir) if data_dir is not None else DATA_DIR
    return sorted(set(_available(data_dir, "camshaft_torque")) & set(_available(data_dir, "crankshaft_speed")))


def speed_problem(rpm, data_dir=None, rpm_option="--rpm", folder_option="--tables"):
    """Why the tables of data_dir (default DATA_DIR) cannot give the inputs at rpm, in one line
    naming the option (rpm_option, folder_option), its value and what is allowed; None if they can
    (both kinds of table at rpm, exactly or interpolated between tabulated speeds)."""
    folder = pathlib.Path(data_dir) if data_dir is not None else DATA_DIR
    if not folder.is_dir():
        return f"{folder_option} {folder}: no such folder"
    ranges = []
    # (the load tables are a drive's sprockets', found and checked with them: sprocket_loads)
    for stem in ("crankshaft_speed",):
        speeds = sorted(_available(folder, stem))
        if not speeds:
            return (f"{folder_option} {folder}: no {stem}_<n>rpm.csv tables there; their format: "
                    f"harness/tables/data/README.md")
        ranges.append((speeds[0], speeds[-1]))
    lo, hi = max(r[0] for r in ranges), min(r[1] for r in ranges)
    if not lo <= rpm <= hi:
        return f"{rpm_option} {rpm:g}: outside the tabulated engine speeds [{lo:g}, {hi:g}] rpm of the tables in {folder}"
    return None


def camshaft_torque(rpm, data_dir=None):
    """Camshaft load-torque table for an engine speed (exact file or interpolated, see _for_speed)."""
    return _for_speed("camshaft_torque", rpm, data_dir)


def crankshaft_speed(rpm, data_dir=None):
    """Crankshaft-speed table for an engine speed (exact file or interpolated, see _for_speed)."""
    return _for_speed("crankshaft_speed", rpm, data_dir)


@dataclasses.dataclass
class Load:
    """The load torque of one loaded sprocket [N m, opposing its rotation], from one of three sources:
    a constant (--load NAME=VALUE), its own table torque_<name>_<n>rpm.csv (column <name>.tau over
    sprocket_angle_deg, one turn of the sprocket, the header's `phase:` the table's angle at the
    sprocket's start; or over crank_angle_deg) or the column <name>.tau of the crank-angle table
    camshaft_torque_<n>rpm.csv. A crank-angle table is looked up at the crank angle that turns the
    sprocket by its angle: the sprocket's angle times its ratio (2 for a camshaft)."""
    name: str
    source: str                  # for reports: the file and column, or "--load"
    table: Table | None = None
    constant: float = 0.0
    ratio: float = 1.0           # crankshaft degrees per degree of the sprocket (crank-angle tables)
    phase_deg: float = 0.0       # the own-angle table's angle at the sprocket's start

    def at(self, sprocket_deg):
        """The torque at the sprocket's angle from its start [deg] (scalar or array)."""
        if self.table is None:
            return np.full_like(np.asarray(sprocket_deg, float), self.constant) if np.ndim(sprocket_deg) else self.constant
        column = self.name + ".tau"
        if self.table.kind == "sprocket":
            return lookup(self.table, column, np.asarray(sprocket_deg, float) + self.phase_deg)
        return lookup(self.table, column, np.asarray(sprocket_deg, float) * self.ratio)


def _phase(table):
    """[deg] the header's `phase: <x> deg` of an own-angle table (0 without one)."""
    text = table.header.get("phase", "0")
    m = re.fullmatch(r"([-+0-9.eE]+)\s*(deg)?", text)
    try:
        return _number(m.group(1)) if m else _number("x")
    except ValueError:
        raise ValueError(f"{table.path}: 'phase:' must be an angle in degrees, e.g. 'phase: 30 deg'; got '{text}'") from None


def sprocket_loads(elements, rpm, data_dir=None, constants=None):
    """{name: Load} of every loaded sprocket of a drive (drive.description.Elements) at an engine
    speed: its constant (constants, --load), else its own-angle table in data_dir, else the column
    <name>.tau of the folder's crank-angle camshaft_torque table. A loaded sprocket with none of
    them, a constant for a sprocket that takes none, and (in a folder the user gave) a table or
    column that matches no loaded sprocket are ValueErrors naming them and what the drive and the
    tables have."""
    folder = pathlib.Path(data_dir) if data_dir is not None else DATA_DIR
    constants = dict(constants or {})
    loaded = elements.loaded
    for name in constants:
        if name not in loaded:
            raise ValueError(f"--load {name}: not a loaded sprocket of the drive; its loaded sprockets: "
                             f"{', '.join(loaded) or 'none'}")
    crank_table = _for_speed("camshaft_torque", rpm, folder) if _available(folder, "camshaft_torque") else None
    own = {name: f"torque_{name}" for name in loaded if _available(folder, f"torque_{name}")}
    if data_dir is not None:
        _check_unmatched(folder, crank_table, loaded)
    loads = {}
    for name in loaded:
        if name in constants:
            loads[name] = Load(name, f"--load {name}={constants[name]:g}", constant=float(constants[name]))
        elif name in own:
            table = _for_speed(own[name], rpm, folder)
            loads[name] = Load(name, f"{table.path or own[name]} ({table.provenance})", table, ratio=elements.ratio(name),
                               phase_deg=_phase(table))
        elif crank_table is not None and name + ".tau" in crank_table.columns:
            loads[name] = Load(name, f"{crank_table.path or 'camshaft_torque'}: {name}.tau ({crank_table.provenance})",
                               crank_table, ratio=elements.ratio(name))
        else:
            raise ValueError(f"sprocket '{name}' has no load: no --load {name}=VALUE, no torque_{name}_<n>rpm.csv and "
                             f"no column {name}.tau in camshaft_torque_<n>rpm.csv in {folder} (the tables there load "
                             f"{', '.join(table_sprockets(folder, crank_table)) or 'no sprocket'}); a sprocket that "
                             f"carries no load is an idler (\"motion\": \"idler\" in the drive)")
    return loads


def table_sprockets(folder, crank_table):
    """The sprocket names the load tables of a folder name: own-angle files and crank-angle columns."""
    names = [c[:-len(".tau")] for c in (crank_table.columns if crank_table is not None else {}) if c.endswith(".tau")]
    for p in sorted(pathlib.Path(folder).glob("torque_*_*rpm.csv")):
        m = re.fullmatch(r"torque_(.+)_[0-9.]+rpm\.csv", p.name)
        if m and m.group(1) not in names:
            names.append(m.group(1))
    return names


def _check_unmatched(folder, crank_table, loaded):
    """A load table or column of a folder the user gave that names no loaded sprocket: ValueError."""
    for name in table_sprockets(folder, crank_table):
        if name not in loaded:
            raise ValueError(f"{folder}: the load table of '{name}' matches no loaded sprocket of the drive (its loaded "
                             f"sprockets: {', '.join(loaded) or 'none'})")


def _omega_column(table):
    """Crankshaft speed [rad/s] of a speed table."""
    if SPEED_W in table.columns:
        w = table.columns[SPEED_W]
    elif SPEED_RPM in table.columns:
        w = table.columns[SPEED_RPM] / RPM_PER_RAD_S
    else:
        raise ValueError(f"{table.path or 'table'}: no crankshaft speed column ('{SPEED_RPM}' or '{SPEED_W}')")
    if np.any(w <= 0.0):
        raise ValueError(f"{table.path or 'table'}: the crankshaft speed must be positive")
    return w


def crank_angle(table, t, theta0_deg=0.0):
    """Crank angle theta(t) [deg] and speed omega(t) [rad/s] of an angle-based speed table by
    integrating d theta / dt = omega(theta) exactly for the piecewise-linear omega(theta), the
    engine at theta0_deg at t = 0; the table is repeated every 720 deg."""
    x = np.append(table.x, table.x[0] + PERIOD_DEG) * (math.pi / 180.0)   # rad
    w = _omega_column(table)
    w = np.append(w, w[0])
    dx = np.diff(x)
    b = np.diff(w) / dx                                  # d omega / d theta per interval
    small = np.abs(b) * dx < 1e-12 * w[:-1]
    b_safe = np.where(small, 1.0, b)
    dt = np.where(small, dx / w[:-1], np.log(w[1:] / w[:-1]) / b_safe)
    tn = np.concatenate([[0.0], np.cumsum(dt)])          # time at the nodes from the first node
    cycle = tn[-1]

    def t_of(theta_rad):                                 # time from the first node, theta in [x0, x0 + period)
        i = np.clip(np.searchsorted(x, theta_rad, side="right") - 1, 0, len(dx) - 1)
        s = theta_rad - x[i]
        wi = w[i] + b[i] * s
        return tn[i] + np.where(small[i], s / w[i], np.log(wi / w[i]) / b_safe[i])

    th0 = math.radians(theta0_deg)
    p = 2.0 * math.pi * PERIOD_DEG / 360.0
    k0 = math.floor((th0 - x[0]) / p)
    tt = np.asarray(t, float) + t_of(th0 - k0 * p)       # time since the first node of cycle k0
    k = np.floor(tt / cycle)
    tl = tt - k * cycle
    i = np.clip(np.searchsorted(tn, tl, side="right") - 1, 0, len(dx) - 1)
    tau = tl - tn[i]
    s = np.where(small[i], w[i] * tau, w[i] * np.expm1(b[i] * tau) / b_safe[i])
    theta = x[i] + s + (k + k0) * p
    return np.degrees(theta), w[i] + b[i] * s


def _time_column(table, column, t, what):
    tx = table.x - table.x[0]
    if t[-1] > tx[-1] * (1.0 + 1e-9) + 1e-12:
        raise ValueError(f"{table.path or 'table'}: the time-based {what} table covers {tx[-1]:g} s; "
                         f"{t[-1]:g} s requested")
    if column not in table.columns:
        raise ValueError(f"{table.path or 'table'}: no column '{column}'")
    return np.interp(t, tx, table.columns[column])


def time_series(rpm, duration, dt, data_dir=None, theta0_deg=0.0, speed_table=None, loads=None, elements=None):
    """Open-loop input time series at the engine speed rpm from the tables, for a drive
    (drive.description.Elements; default: the default drive): dict of numpy arrays 'time' [s],
    '<crank>.w' [rad/s], '<sprocket>.tau' [N m] of every loaded sprocket and 'crank_angle_deg'
    (theta(t), not an input of the runner), on t = 0, dt, ..., duration.

    Angle-based speed table: theta(t) solves d theta/dt = omega(theta) (crank_angle), starting at
    theta0_deg (default 0 = cylinder 1 firing TDC); its mean over time is the harmonic mean of
    the table's speed over the angle, within 0.2 % of its arithmetic mean (the engine speed) at
    1000 rpm and above. A time-based speed table gives theta(t) by the trapezoidal integral of
    omega. The loads (sprocket_loads(elements, rpm, data_dir) unless given) are looked up at each
    sprocket's angle theta(t) over its ratio, the chain taken as rigid; a time-based load table
    directly from its first sample."""
    from ..drive.description import elements as drive_elements
    elements = elements or drive_elements()
    speed = speed_table if speed_table is not None else crankshaft_speed(rpm, data_dir)
    loads = loads if loads is not None else sprocket_loads(elements, rpm, data_dir)
    n = int(round(duration / dt))
    t = np.arange(n + 1) * dt
    if speed.kind == "angle":
        theta, w = crank_angle(speed, t, theta0_deg)
    else:
        col = SPEED_W if SPEED_W in speed.columns else SPEED_RPM
        w = _time_column(speed, col, t, "crankshaft speed")
        if col == SPEED_RPM:
            w = w / RPM_PER_RAD_S
        theta = theta0_deg + np.degrees(np.concatenate([[0.0], np.cumsum(0.5 * (w[1:] + w[:-1]) * dt)]))
    out = {"time": t, elements.crank + ".w": w}
    for name, load in loads.items():
        timed = load.table is not None and load.table.kind == "time"
        out[name + ".tau"] = _time_column(load.table, name + ".tau", t, "torque") if timed else \
            load.at(theta / elements.ratio(name))
    out["crank_angle_deg"] = theta
    return out


def write_inputs_csv(path, rpm, duration, dt=2e-5, data_dir=None, theta0_deg=0.0):
    """Writes the default drive's input CSV of chaindrive-run ('#' comments, then
    'time,crankshaft.w,camshaftIntake.tau,camshaftExhaust.tau', SI units) from the tables."""
    speed = crankshaft_speed(rpm, data_dir)
    ts = time_series(rpm, duration, dt, data_dir, theta0_deg=theta0_deg, speed_table=speed)
    cols = [c for c in ts if c != "crank_angle_deg"]
    with open(path, "w") as f:
        f.write("# inputs for chaindrive-run: SI units (s, rad/s, N m)\n")
        f.write(f"# crankshaft {rpm:g} rpm and camshaft torques from tables (harness/tables/tables.py), starting at "
                f"{theta0_deg:g} deg crank angle\n")
        f.write(f"# crankshaft speed: {speed.provenance}\n")
        f.write(f"# camshaft torque: {camshaft_torque(rpm, data_dir).provenance}\n")
        f.write(",".join(cols) + "\n")
        np.savetxt(f, np.column_stack([ts[c] for c in cols]), delimiter=",", fmt="%.10g")
    return path
