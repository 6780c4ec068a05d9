"""The example drives: each made by the layout aid from its layout file, its FMU's interface, its
picture, and — where it runs on its own — its main job with its own tables and the physics checks
(docs/examples/README.md):

- **torque balance**: the chain's pull across each loaded sprocket, the span forces after and
  before it (the per-span probes) times its pitch radius, against its mean load torque over the
  counted cycles, within 10 % (the pull also carries what the sprocket's meshing dissipates), and
  the mean chain torque on it (its contact forces' moment, output tauChain) against the load
  within 2 % (the inertia torque averages out over whole cycles; what remains is the sprocket's
  bearing damping);
- **meshing order**: the crankshaft meshing order (its teeth per revolution) stands out of the
  slack span's force spectrum: its mean amplitude over the counted cycles against the median of
  the half orders within 4 of it;
- **energy balance** over the counted cycles (the main job's own check, limit 5 %).

    python -m harness example-drives [--rpm 3000] [--cycles 120] [--only NAME ...] [--out docs/examples]

The V6's primary and bank drives run coupled through their intermediate shafts (harness/vengine.py,
docs/v_engine.md); here they get the layout, the interface and the picture.
"""
import dataclasses
import json
import math
import pathlib
import shutil
import subprocess
import sys
import tempfile

import numpy as np

from .. import cycle_stats, paths
from ..drive import geometry as geo
from ..drive.description import drive_json, elements
from ..errors import UserError

DRIVES = paths.ROOT / "tests" / "drives"
OUT = paths.ROOT / "docs" / "examples"
TORQUE_BALANCE_LIMIT = 0.10   # |pull x radius - load| / |load| over the counted cycles (the pull carries the
#                               sprocket's meshing losses besides its load)
CHAIN_TORQUE_LIMIT = 0.02     # |mean chain torque - mean load| / |load|: the sprocket's inertia torque averages out
MESHING_PROMINENCE = 3.0      # the meshing order's amplitude over the median of its neighbours
NEIGHBOURHOOD = 4.0           # [orders] either side of the meshing order


@dataclasses.dataclass(frozen=True)
class Example:
    name: str                 # tests/drives/<name>.json, its layout tests/drives/layouts/<name>.json
    what: str                 # the layout it stands for
    runs_alone: bool = True   # False: it runs only coupled (the V6's drives)

    @property
    def drive(self):
        return DRIVES / f"{self.name}.json"

    @property
    def tables(self):
        return DRIVES / "tables" / self.name


EXAMPLES = [
    Example("sohc_single_cam", "single camshaft (SOHC)"),
    Example("dohc_8mm", "DOHC inline-four on an 8 mm chain, counterclockwise"),
    Example("diesel_pump", "diesel DOHC with a high-pressure pump in the chain"),
    Example("idler", "single camshaft with an idler"),
    Example("v6_primary", "V6 primary drive: crankshaft to two intermediate shafts", runs_alone=False),
    Example("v6_bank", "V6 bank drive: intermediate shaft to two camshafts", runs_alone=False),
]


def layout_report(example, out):
    """The layout aid on the example's layout file (python -m harness layout): its report kept as
    out/layout.md; returns whether it makes the committed drive bit for bit."""
    with tempfile.TemporaryDirectory() as scratch:
        drive = pathlib.Path(scratch) / f"{example.name}.json"
        layout = (DRIVES / "layouts" / f"{example.name}.json").relative_to(paths.ROOT).as_posix()
        cmd = [sys.executable, "-m", "harness", "layout", layout, "--out", str(drive), "--picture",
               str(pathlib.Path(scratch) / "drive.png")]
        done = subprocess.run(cmd, capture_output=True, text=True, cwd=paths.ROOT)
        if done.returncode != 0:
            raise UserError(f"{example.name}: the layout aid failed: {done.stderr.strip()}")
        sys.stderr.write(done.stderr)   # (a tool's notes are never dropped)
        report = done.stdout.replace(str(drive), f"tests/drives/{example.name}.json")
        report = report.replace(str(pathlib.Path(scratch) / "drive.png"), "drive.png")
        (out / "layout.md").write_text(f"# The layout aid on {example.name}\n\n`python -m harness layout "
                                       f"tests/drives/layouts/{example.name}.json`:\n\n```\n{report}```\n")
        return drive.read_bytes() == example.drive.read_bytes()


def model_description(example, out):
    """The example's exported modelDescription.xml (chaindrive-info --fmu-files, as the export
    writes it) into out/; returns its inputs and outputs."""
    from ..fmu.export import fmu_files
    with tempfile.TemporaryDirectory() as stage:
        interface = fmu_files(example.drive, pathlib.Path(stage))
        shutil.copyfile(pathlib.Path(stage) / "modelDescription.xml", out / "modelDescription.xml")
    return {c: [v["name"] for v in interface["variables"] if v["causality"] == c] for c in ("input", "output")}


def main_job(example, rpm, cycles, out):
    """The main job of the example with its own tables; returns its record (outputs.csv) and run.json.
    Its run.json and summary.json are kept in out/, the rest (outputs, plots) in a scratch folder."""
    with tempfile.TemporaryDirectory() as scratch:
        cmd = [sys.executable, "-m", "harness", "run", "--drive", str(example.drive), "--tables", str(example.tables),
               "--rpm", f"{rpm:g}", "--cycles", str(cycles), "--out", scratch]
        done = subprocess.run(cmd, capture_output=True, text=True)
        if done.returncode != 0:
            raise UserError(f"{example.name}: the main job failed: {done.stderr.strip().splitlines()[-1:]}")
        sys.stderr.write(done.stderr)
        warnings = [line for line in done.stdout.splitlines() if line.startswith("warning:")]
        sys.stderr.writelines(f"{example.name}: {line}\n" for line in warnings)
        for name in ("run.json", "summary.json"):
            shutil.copyfile(pathlib.Path(scratch) / name, out / name)
        data = np.genfromtxt(pathlib.Path(scratch) / "outputs.csv", delimiter=",", names=True, deletechars="")
    record = {name: np.asarray(data[name], dtype=float) for name in data.dtype.names}
    return record, json.loads((out / "run.json").read_text())


def torque_balance(record, drive, el, first, last):
    """Per loaded sprocket over samples first..last-1: the chain's mean pull (the span force after it
    minus the one before it, times its pitch radius), the mean chain torque on it (its output
    tauChain: the contact forces' moment) and its mean load torque [N m], and the differences of
    both from the load relative to the load."""
    route, pitch = drive["chain"]["route"], drive["chain"]["pitch"]
    teeth = {s["name"]: s["teeth"] for s in drive["sprockets"]}
    rows = {}
    for name in el.loaded:
        i = route.index(name)
        before, after = route[i - 1], route[(i + 1) % len(route)]
        pull = record[f"chain.{name}.{after}.F"][first:last] - record[f"chain.{before}.{name}.F"][first:last]
        pull_torque = float(np.mean(pull)) * geo.pitch_radius(pitch, teeth[name])
        load = float(np.mean(record[f"input.{name}.tau"][first:last]))
        chain = float(np.mean(record[f"{name}.tauChain"][first:last]))
        rows[name] = {"pull_Nm": pull_torque, "chainTorque_Nm": chain, "load_Nm": load,
                      "error": (pull_torque - load) / abs(load), "chainTorqueError": (chain - load) / abs(load)}
    return rows


def meshing_prominence(record, el, spans):
    """The crankshaft meshing order's mean amplitude in the slack span's force over the counted
    cycles, the median of the half orders within NEIGHBOURHOOD of it, and their ratio. (The slack
    span: the tight span carries the loads' harmonics and its own resonances near the meshing order,
    on the pump drive order 19 above order 21.)"""
    z = el.meshing_order
    orders = [k for k in cycle_stats.half_orders(z + NEIGHBOURHOOD) if k >= z - NEIGHBOURHOOD]
    means, _ = cycle_stats.order_spectrum(record, spans, "chain.Fslack", orders, crank=el.crank)
    at_z = float(means[orders.index(float(z))])
    others = float(np.median([m for k, m in zip(orders, means) if k != z]))
    return {"order": z, "amplitude_N": at_z, "neighbours_N": others, "ratio": at_z / others}


def physics_checks(record, run, drive):
    """The three checks of the module text over the main job's counted cycles."""
    el = elements(drive)
    spans = cycle_stats.counted_spans(record[el.crank + ".phi"], run["runInCycles"], run["cycles"])
    balance = torque_balance(record, drive, el, spans[0][0], spans[-1][1])
    meshing = meshing_prominence(record, el, spans)
    energy = run["checks"]["energyBalanceError"]
    passed = (all(abs(r["error"]) <= TORQUE_BALANCE_LIMIT and abs(r["chainTorqueError"]) <= CHAIN_TORQUE_LIMIT
                  for r in balance.values())
              and meshing["ratio"] >= MESHING_PROMINENCE and abs(energy) <= run["checks"]["energyBalanceLimit"])
    return {"cycles": len(spans), "torqueBalance": balance, "torqueBalanceLimit": TORQUE_BALANCE_LIMIT,
            "chainTorqueLimit": CHAIN_TORQUE_LIMIT,
            "meshingOrder": meshing, "meshingProminenceLimit": MESHING_PROMINENCE,
            "energyBalanceError": energy, "energyBalanceLimit": run["checks"]["energyBalanceLimit"], "passed": passed}


def run_example(example, rpm, cycles, out_root):
    """Everything of one example into out_root/<name>/; returns its row of the report."""
    from ..plots.drive_picture import drive_picture
    out = out_root / example.name
    out.mkdir(parents=True, exist_ok=True)
    row = {"name": example.name, "what": example.what, "layoutMatches": layout_report(example, out),
           "interface": model_description(example, out)}
    drive = drive_json(example.drive)
    row["links"] = drive["chain"]["numberOfLinks"]
    drive_picture(str(out / "drive.png"), str(example.drive), drive["name"])
    if example.runs_alone:
        record, run = main_job(example, rpm, cycles, out)
        row["checks"] = physics_checks(record, run, drive)
        (out / "checks.json").write_text(json.dumps(row["checks"], indent=1) + "\n")
    return row


def report_line(row):
    """One line of the console report."""
    text = (f"{row['name']}: {row['links']} links, layout aid {'matches' if row['layoutMatches'] else 'DIFFERS'}, "
            f"inputs {', '.join(row['interface']['input'])}")
    c = row.get("checks")
    if not c:
        return text + "; runs only coupled (no main job of its own)"
    torques = ", ".join(f"{k} {v['pull_Nm']:.3f}/{v['chainTorque_Nm']:.3f}/{v['load_Nm']:.3f} N m ({v['error']:+.2%}, "
                        f"{v['chainTorqueError']:+.2%})"
                        for k, v in c["torqueBalance"].items())
    m = c["meshingOrder"]
    return (text + f"; pull/chain torque/load {torques}; order {m['order']:g} {m['amplitude_N']:.1f} N, "
            f"{m['ratio']:.1f} x its neighbours; energy balance {c['energyBalanceError']:+.2%}; "
            f"{'passed' if c['passed'] else 'FAILED'}")


README_INTRO = """# Example drives

Real engine layouts as the project models them, each made by the layout aid from its layout file
([drive_layout.md](../drive_layout.md); the drives, their layout files and tables in
[tests/drives](../../tests/drives/README.md) with the sources of their numbers). Per example: its
FMU's model description (`modelDescription.xml`, as `./run.sh export` writes it), its picture, the
layout aid's report (`layout.md`), and where it runs on its own the main job at {rpm:g} rpm with its
own tables, {cycles} counted cycles (`run.json`, `summary.json`) and the physics checks
(`checks.json`): the chain's pull across each loaded sprocket (the span forces after and before it
times its pitch radius) against its mean load within {pull:.0%} (the pull also carries the losses
of the chain's wrap on the sprocket, which the outputs do not separate) and the mean chain torque
on it (output `tauChain`) within {chain:.0%} of the load; the crankshaft meshing order at least
{prominence:g} times the median of the half orders within {near:g} of it in the slack span's force;
the energy balance within the main job's limit. Made by
`python -m harness example-drives --rpm {rpm:g} --cycles {cycles}` (harness/study/example_drives.py).

| example | links | layout aid | inputs | loaded sprocket: pull / chain torque / load | meshing order | energy balance | checks |
|---|---|---|---|---|---|---|---|"""


def readme(rows, rpm, cycles):
    """docs/examples/README.md: the examples, their interfaces and their checks."""
    lines = README_INTRO.format(rpm=rpm, cycles=cycles, pull=TORQUE_BALANCE_LIMIT, chain=CHAIN_TORQUE_LIMIT,
                                prominence=MESHING_PROMINENCE, near=NEIGHBOURHOOD).splitlines()
    for r in rows:
        c = r.get("checks")
        inputs = ", ".join(f"`{n}`" for n in r["interface"]["input"])
        link = f"[{r['name']}]({r['name']}/drive.png): {r['what']}"
        if not c:
            lines.append(f"| {link} | {r['links']} | {'bit for bit' if r['layoutMatches'] else 'differs'} | {inputs} | "
                         "runs coupled through its shafts: [v_engine.md](../v_engine.md) | | | |")
            continue
        torques = "; ".join(f"`{k}` {v['pull_Nm']:.2f} / {v['chainTorque_Nm']:.2f} / {v['load_Nm']:.2f} N m "
                            f"({v['error']:+.1%}, {v['chainTorqueError']:+.1%})"
                            for k, v in c["torqueBalance"].items())
        m = c["meshingOrder"]
        lines.append(f"| {link} | {r['links']} | {'bit for bit' if r['layoutMatches'] else 'differs'} | {inputs} | "
                     f"{torques} | {m['order']:g}: {m['amplitude_N']:.1f} N, {m['ratio']:.1f} x | "
                     f"{c['energyBalanceError']:+.2%} | {'passed' if c['passed'] else '**failed**'} |")
    return "\n".join(lines) + "\n"


def committed_rows(out):
    """The report's rows from the committed results in out/ (the drives, model descriptions and checks)."""
    import xml.etree.ElementTree as ET
    rows = []
    for e in EXAMPLES:
        root = ET.parse(out / e.name / "modelDescription.xml").getroot()
        links = drive_json(e.drive)["chain"]["numberOfLinks"]
        row = {"name": e.name, "what": e.what, "layoutMatches": True, "links": links,
               "interface": {c: [v.get("name") for v in root.iter("ScalarVariable") if v.get("causality") == c]
                             for c in ("input", "output")}}
        if (out / e.name / "checks.json").exists():
            row["checks"] = json.loads((out / e.name / "checks.json").read_text())
        rows.append(row)
    return rows


def add_arguments(ap):
    ap.add_argument("--report-only", action="store_true",
                    help="write README.md again from the committed results of --out (no runs; the layout aid's "
                         "match is what the tests check)")
    ap.add_argument("--rpm", type=float, default=3000.0, help="engine speed of the main jobs (default 3000)")
    ap.add_argument("--cycles", type=int, default=120, help="counted cycles of each main job (default 120)")
    ap.add_argument("--only", nargs="+", choices=[e.name for e in EXAMPLES], help="these examples only")
    ap.add_argument("--out", default=str(OUT), help="the results folder (default docs/examples)")


def run(args):
    out = pathlib.Path(args.out)
    if args.report_only:
        (out / "README.md").write_text(readme(committed_rows(out), args.rpm, args.cycles))
        print(f"written: {out / 'README.md'}")
        return 0
    rows = []
    for example in [e for e in EXAMPLES if not args.only or e.name in args.only]:
        rows.append(run_example(example, args.rpm, args.cycles, out))
        print(report_line(rows[-1]), flush=True)
    if not args.only:
        (out / "README.md").write_text(readme(rows, args.rpm, args.cycles))
        print(f"written: {out / 'README.md'}")
    failed = [r["name"] for r in rows if not r["layoutMatches"] or not r.get("checks", {"passed": True})["passed"]]
    if failed:
        raise UserError(f"example drives that failed a check: {', '.join(failed)}")
    return 0
