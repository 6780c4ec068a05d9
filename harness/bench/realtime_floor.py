"""The floor under the routes to a quarter of real time: the real-time factor the link model could at
best reach if every link in contact kept today's cost per step at the longest step that still meets
the accuracy table, and every other link cost nothing.

    python -m harness realtime-floor REPORT.json [--fine-step 5e-6] [--duration 2] [--out results/realtime_floor.md]

A longer step and multirate, the routes that shorten the work, meet at one limit: a roller's impact
on its tooth has to be resolved in time (it lasts half a period of the contact mode, 14-20 us; the
accuracy table is lost at longer steps, docs/study/hydraulic_steps.md), and so has every contact
force. So the links in contact need steps no longer than --fine-step, with their contact work; the
links off every sprocket and guide are what a multirate scheme with an implicit coarse step could
save, at best all of their cost. For each speed of REPORT.json (bench-realtime's JSON: the method,
its step and its RTF through ChainDrive.fmu, the model's: realtime.model_rtf):

- the contact stages' share of the solver's time: `perf record` of chaindrive-run with the report's
  method and step at that speed (--duration s), the samples of the functions in CONTACT_FUNCTIONS
  over those of every function of the steps (OUTSIDE_THE_STEPS left out: the static preload, the CSV);
- the links in contact: the mean of the output `contacts` over the same run (its first tenth left
  out), over the chain's links (`contacts` counts contact points: a roller seated on a sprocket,
  one per pin and so per link wrapped, and a link's plate on a guide);
- the floor: RTF x (step / fine step) x (contact share + (1 - contact share) x links in contact / links).

The report's method must be an explicit one (fixed-verlet and its variants with the damping
implicit): the floor starts from today's explicit step, whose work outside the contacts is the
links' own (an implicit method's linear algebra would be counted as the start's).

The floor is optimistic by construction (every link not in contact free, no cost of coupling the
rates, the links about to touch counted as free), so a target below it is out of reach of these
routes without making the contact work itself cheaper: the report gives the factor that would need.
Needs perf (Debian: linux-perf) and the kernel's permission to sample the process.
"""
import pathlib
import re
import shutil
import subprocess
import tempfile

import numpy as np

from .. import paths, runs
from ..drive.description import drive_json
from ..errors import UserError, tool_failure
from .realtime import RTF_TARGET, load_report, model_rtf

# functions of the contact stages (src/dynamics/contact_lanes.cpp, contact_kinematics.cpp,
# contact_compliant.cpp, src/assembly/geometry.cpp; the vector loops carry their width's suffix, Avx2
# or Sse2) and of what is not the steps' work: the start (the static preload's linear algebra, the
# initial state) and the writing of the CSV (the FMU formats no text)
CONTACT_FUNCTIONS = ("rollers", "closestOffSeat", "closestOnArc", "compliantContactForce", "plates",
                     "setPlateContact", "detectPlateContacts", "windows", "placeFace", "detectContacts")
OUTSIDE_THE_STEPS = ("Eigen::", "initialState", "printf", "hack_digit", "__mpn_", "strchrnul")
EXPLICIT_METHODS = ("fixed-verlet", "fixed-verlet-implicit-joint-damping", "fixed-verlet-implicit-damping")
SKIPPED_FRACTION = 0.1  # of the run's outputs before the contacts are counted


def add_arguments(ap):
    ap.add_argument("report", metavar="REPORT.json", help="a JSON report of python -m harness bench-realtime")
    ap.add_argument("--fine-step", type=float, default=5e-6,
                    help="the longest step that meets the accuracy table with the contacts resolved [s]")
    ap.add_argument("--duration", type=float, default=2.0, help="simulated seconds of each profiled run")
    ap.add_argument("--out", default=str(paths.RESULTS / "realtime_floor.md"))


def check(ap, args):
    args.loaded = load_report(ap, args.report)
    for speed in args.loaded["speeds"]:
        if speed["method"] not in EXPLICIT_METHODS:
            ap.error(f"{args.report}: method {speed['method']} at {speed['rpm']:g} rpm: the floor starts from an "
                     f"explicit method's step ({', '.join(EXPLICIT_METHODS)})")
    if not args.fine_step > 0.0:
        ap.error(f"--fine-step {args.fine_step}: a step is positive")
    if not args.duration >= 0.2:
        ap.error(f"--duration {args.duration}: at least 0.2 s, for enough samples")
    if shutil.which("perf") is None:
        ap.error("perf not found: the contact stages' share comes from a profile (Debian: apt-get install linux-perf)")
    return args


def stage_of(function):
    """'contact', 'outside' (the steps) or 'rest' for a function's name as perf reports it: the
    names of CONTACT_FUNCTIONS after a scope (::) or the start of the name, OUTSIDE_THE_STEPS anywhere."""
    if any(re.search(rf"(^|::){name}", function) for name in CONTACT_FUNCTIONS):
        return "contact"
    return "outside" if any(f in function for f in OUTSIDE_THE_STEPS) else "rest"


def stage_shares(report_text):
    """Percent of the samples in the contact stages, the other stages of the steps and outside the
    steps, from `perf report --stdio` (user-space functions only)."""
    shares = dict(contact=0.0, outside=0.0, rest=0.0)
    for line in report_text.splitlines():
        m = re.match(r"\s+([\d.]+)%\s+\S+\s+\S+\s+\[\.\]\s+(.*)", line)
        if not m:
            continue
        shares[stage_of(m.group(2))] += float(m.group(1))
    return shares


def profile(rpm, method, step, duration, tmp):
    """The contact share of the run's time (its start left out) and the mean contact points."""
    csv, data = tmp / "run.csv", tmp / "perf.data"
    cmd = ["perf", "record", "-q", "-F", "2000", "-o", str(data), paths.executable("chaindrive-run"), "--rpm",
           repr(rpm), "--integrator", method, "--step", repr(step), "--duration", repr(duration),
           "--output-step", "1e-3", "--out", str(csv), "--quiet"]
    p = subprocess.run(cmd, capture_output=True, text=True)
    if p.returncode != 0 and data.exists() and csv.exists():  # (perf passes on its child's failure)
        raise tool_failure("chaindrive-run", p.stderr)
    if p.returncode != 0 or not data.exists():
        raise UserError(f"perf record failed ({p.returncode}): {p.stderr.strip()[-300:]} (the kernel may refuse "
                        f"sampling: /proc/sys/kernel/perf_event_paranoid)")
    report = subprocess.run(["perf", "report", "-i", str(data), "--stdio", "--no-children"], capture_output=True,
                            text=True)
    shares = stage_shares(report.stdout)
    if report.returncode != 0 or shares["contact"] + shares["rest"] <= 0.0:
        raise UserError(f"perf report gave no samples of the steps ({report.returncode}): "
                        f"{report.stderr.strip()[-300:]}")
    contacts = runs.read_csv(csv)["contacts"]
    return dict(contactShare=shares["contact"] / (shares["contact"] + shares["rest"]),
                outsidePercent=shares["outside"],
                contactPoints=float(np.mean(contacts[int(SKIPPED_FRACTION * len(contacts)):])))


def floor_parts(rtf, step, fine_step, contact_share, in_contact):
    """The floor's RTF (the module's formula) in its two parts: the contact work and the rest of the
    links in contact."""
    scale = rtf * (step / fine_step)
    return scale * contact_share, scale * (1.0 - contact_share) * in_contact


def floor_of(speed, fine_step, links, measured):
    """The floor of a speed of the report from its profile (measured: profile()), against the target:
    the contact work's speed-up that would bring it down to the target (contact / s + rest = target),
    None when the floor meets the target or when even free contact work would not."""
    contact, rest = floor_parts(model_rtf(speed), speed["step"], fine_step, measured["contactShare"],
                                min(1.0, measured["contactPoints"] / links))
    floor_rtf, target = contact + rest, RTF_TARGET.get(speed["rpm"])
    below = target is not None and floor_rtf > target
    return dict(rpm=speed["rpm"], method=speed["method"], step=speed["step"], rtf=model_rtf(speed), rtfTarget=target,
                fineStep=fine_step, links=links, **measured, floor=floor_rtf, targetBelowFloor=below,
                contactSpeedupForTarget=contact / (target - rest) if below and target > rest else None)


def line(f):
    verdict = ""
    if f["rtfTarget"] is not None:
        verdict = f"{'above' if f['targetBelowFloor'] else 'below'} the target {f['rtfTarget']:g}"
        if f["targetBelowFloor"]:
            needed = f["contactSpeedupForTarget"]
            verdict += (f"; the contact work would have to be {needed:.2f} times cheaper" if needed is not None
                        else "; out of reach even with the contact work free")
    return (f"| {f['rpm']:g} rpm | {f['method']} at {f['step'] * 1e6:.4g} us | {f['rtf']:.3g} | "
            f"{100 * f['contactShare']:.1f} % | {f['contactPoints']:.1f} of {f['links']} | "
            f"{f['fineStep'] * 1e6:.3g} us | **{f['floor']:.3g}** | {verdict} |")


def run(args):
    links = drive_json()["chain"]["numberOfLinks"]
    command = f"python -m harness realtime-floor {' '.join(args.argv)}"
    with tempfile.TemporaryDirectory() as tmp:
        floors = [floor_of(s, args.fine_step, links, profile(s["rpm"], s["method"], s["step"], args.duration,
                                                              pathlib.Path(tmp))) for s in args.loaded["speeds"]]
    lines = ["# The floor under the routes to a quarter of real time", "",
             f"Machine: {runs.machine()}; command: {command}; the report's RTFs measured on: "
             f"{args.loaded.get('machine', 'unknown')}", "",
             "| speed | method | RTF (report) | contact stages' share | contact points (links in contact) | "
             "fine step | floor | against the target |", "|---|---|---|---|---|---|---|---|"]
    lines += [line(f) for f in floors]
    print("\n".join(lines))
    runs.write_lines(args.out, lines)
    runs.write_json(pathlib.Path(args.out).with_suffix(".json"),
                    dict(machine=runs.machine(), command=command, report=args.report, speeds=floors))
    return 0
