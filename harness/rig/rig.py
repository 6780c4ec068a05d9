"""Force-displacement loops of the hydraulic tensioner on the bench (chaindrive-rig, src/rig): the
plunger driven on x(t) = a sin(2 pi f t) at 20, 100 and 200 Hz with 0.05 and 0.2 mm amplitude, the
default device (tensioner.hydraulic of the drive, its defaults when it has none) at 90 C on a
3 bar supply. Each loop runs until its pressure has settled (max(0.25 s, 10 periods)); the last
period is plotted, force over displacement, one panel per amplitude; its peak and least force
and mean pressure printed and written beside the picture (rig_loops.json, the figures the docs
quote).

    python -m harness rig [--drive FILE] [--out docs/tensioner/rig_loops.png] [--csv-dir DIR]
"""
import csv
import json
import pathlib
import subprocess
import tempfile

import numpy as np

from .. import paths
from . import plots

FREQUENCIES = (20.0, 100.0, 200.0)   # [Hz] the suppliers' rig range (20-200 Hz)
AMPLITUDES = (0.05e-3, 0.2e-3)       # [m]


def add_arguments(ap):
    ap.add_argument("--drive", default="", help="drive description whose tensioner.hydraulic block to test "
                    "(default: the embedded drive)")
    ap.add_argument("--out", default=str(paths.ROOT / "docs" / "tensioner" / "rig_loops.png"),
                    help="the loops' picture")
    ap.add_argument("--csv-dir", default="", help="keep the runs' CSV files here (default: a temporary folder)")


def read_csv(path):
    """{column: array} of a chaindrive-rig CSV file."""
    with open(path, newline="", encoding="utf-8") as f:
        rows = list(csv.reader(f))
    head, data = rows[0], np.array(rows[1:], dtype=float)
    return {name: data[:, i] for i, name in enumerate(head)}


def last_period(d, frequency):
    """The samples of the last period of a loop."""
    keep = d["time"] > d["time"][-1] - 1.0 / frequency - 1e-12
    return {k: v[keep] for k, v in d.items()}


def run_loop(folder, drive, frequency, amplitude):
    """One loop through chaindrive-rig; its CSV read back."""
    out = pathlib.Path(folder) / f"loop_{frequency:g}Hz_{amplitude * 1e3:g}mm.csv"
    cmd = [paths.executable("chaindrive-rig"), "--test", "loop", "--frequency", repr(frequency),
           "--amplitude", repr(amplitude), "--csv", str(out)]
    if drive:
        cmd += ["--drive", drive]
    subprocess.run(cmd, check=True, capture_output=True, text=True)
    return read_csv(out)


def run(args):
    loops = {}
    with tempfile.TemporaryDirectory() as tmp:
        folder = args.csv_dir or tmp
        pathlib.Path(folder).mkdir(parents=True, exist_ok=True)
        for a in AMPLITUDES:
            for f in FREQUENCIES:
                loops[(f, a)] = last_period(run_loop(folder, args.drive, f, a), f)
    summary = [{"name": f"{f:g}Hz-{a * 1e3:g}mm", "frequency": f, "amplitude": a,
                "peakForce": round(float(d["force"].max()), 2), "leastForce": round(float(d["force"].min()), 2),
                "meanPressureBar": round(float(d["pressure"].mean()) * 1e-5, 3)} for (f, a), d in loops.items()]
    print("the settled loop: peak force, least force, mean pressure")
    for s in summary:
        print(f"  {s['frequency']:5.0f} Hz  {s['amplitude'] * 1e3:.2f} mm: {s['peakForce']:7.1f} N  "
              f"{s['leastForce']:6.1f} N  {s['meanPressureBar']:5.1f} bar")
    out = pathlib.Path(args.out)
    out.parent.mkdir(parents=True, exist_ok=True)
    plots.loops(out, loops, AMPLITUDES, FREQUENCIES)
    out.with_suffix(".json").write_text(json.dumps({"loops": summary}, indent=1) + "\n", encoding="utf-8")
    print(f"wrote {out} and {out.with_suffix('.json')}")
    return 0
