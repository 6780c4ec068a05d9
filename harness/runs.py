"""Runs of the solver alone (chaindrive-run) and their CSV outputs."""
import platform
import re
import subprocess
import sys

import numpy as np

from . import paths


def read_csv(path):
    """Reads an output CSV into a dict of numpy arrays keyed by column name."""
    with open(path) as f:
        header = f.readline().strip().split(",")
    data = np.loadtxt(path, delimiter=",", skiprows=1, ndmin=2)
    return {name: data[:, i] for i, name in enumerate(header)}


def run(out_csv, rpm=3000.0, cycles=2.0, duration=None, integrator=None, rtol=None, step=None,
        output_step=1e-4, inputs_csv=None, loads=None, crank_vibration=None, drive=None, link=None,
        preload=True, check=True, fidelity="link", initial_state=None, save_state=None):
    """Runs chaindrive-run; returns (returncode, stdout, parsed summary dict). Without integrator,
    rtol or step: chaindrive-run's defaults (the fidelity's own, src/run/defaults.h). initial_state,
    save_state: state files to start from (the duration counts from its time) and to save the end in."""
    cmd = [paths.executable("chaindrive-run"), "--rpm", str(rpm), "--output-step", repr(output_step),
           "--out", str(out_csv), "--quiet", "--fidelity", fidelity]
    if integrator is not None:
        cmd += ["--integrator", integrator]
    cmd += ["--duration", repr(duration)] if duration is not None else ["--cycles", repr(cycles)]
    if rtol is not None:
        cmd += ["--rtol", repr(rtol)]
    if step is not None:
        cmd += ["--step", repr(step)]
    if inputs_csv:
        cmd += ["--inputs", str(inputs_csv)]
    for name, tau in (loads or {}).items():
        cmd += ["--load", f"{name}={tau!r}"]
    for order, amp_deg in (crank_vibration or []):
        cmd += ["--crank-vibration", f"{order!r}:{amp_deg!r}"]
    if drive:
        cmd += ["--drive", str(drive)]
    if link is not None:
        cmd += ["--link", str(link)]
    if not preload:
        cmd += ["--no-preload"]
    if initial_state:
        cmd += ["--initial-state", str(initial_state)]
    if save_state:
        cmd += ["--save-state", str(save_state)]
    p = subprocess.run(cmd, capture_output=True, text=True)
    if check and p.returncode not in (0, 3):
        raise RuntimeError(f"chaindrive-run failed ({p.returncode}): {p.stderr.strip()}")
    if p.stderr.strip():  # (its notes, e.g. an output step rounded to whole steps: never dropped)
        sys.stderr.write(p.stderr if p.stderr.endswith("\n") else p.stderr + "\n")
    return p.returncode, p.stdout, parse_summary(p.stdout)


def parse_summary(text):
    """Figures printed by chaindrive-run."""
    out = {}
    m = re.search(r"simulated ([0-9.eE+-]+) s .* in ([0-9.eE+-]+) s CPU -> ([0-9.eE+-]+) CPU s per simulated s", text)
    if m:
        out["simulated"] = float(m.group(1))
        out["cpu"] = float(m.group(2))
        out["cpu_per_sim_s"] = float(m.group(3))
    m = re.search(r"steps (\d+), rhs evaluations (\d+) \(model count (\d+)\), jacobians (\d+)", text)
    if m:
        out["steps"] = int(m.group(1))
        out["rhs"] = int(m.group(3))
        out["jacobians"] = int(m.group(4))
    m = re.search(r"FAILED: (.*)", text)
    if m:
        out["failure"] = m.group(1)
    return out


def write_lines(path, lines):
    """Writes a report (lines of text) to path, creating its folder; prints where."""
    import pathlib
    out = pathlib.Path(path)
    out.parent.mkdir(parents=True, exist_ok=True)
    out.write_text("\n".join(lines) + "\n")
    print(f"\nwritten: {out}")


def write_json(path, record):
    """Writes a report's figures (a JSON-able record) to path, beside its Markdown; prints where."""
    import json
    import pathlib
    out = pathlib.Path(path)
    out.write_text(json.dumps(record, indent=1) + "\n")
    print(f"written: {out}")


def machine():
    """One line describing the machine, for benchmark reports."""
    cpu = platform.processor() or "unknown cpu"
    try:
        with open("/proc/cpuinfo") as f:
            for line in f:
                if line.startswith("model name"):
                    cpu = line.split(":", 1)[1].strip()
                    break
    except OSError:
        pass
    try:
        import os
        cores = os.cpu_count()
    except Exception:  # pragma: no cover
        cores = "?"
    return f"{cpu}, {cores} logical cores, {platform.system()} {platform.release()}, Python {platform.python_version()}"
