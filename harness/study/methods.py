"""The methods of the study (contact method x integrator, each with a sweep of one setting), its
references and settings, and one run of the solver with a method (run_solver)."""
import json
import subprocess
import time

from .. import paths
from ..drive.description import drive_json

SHORT_HORIZON = 1e-3     # [s] window of the short-horizon (trajectory) errors: shorter than the
                         # predictability time (differences grow by e per 2 ms on average, several
                         # times faster through some contact events), so that they measure the step
HORIZON_LABEL = f"{SHORT_HORIZON * 1e3:g} ms"
OUTPUT_STEP = 6e-5       # [s] output interval of every run: whole steps of every fixed step below
THRESHOLD_RMS = 1.0      # [%] the "1 % RMS error" of the tensioner force over the short horizon
CYCLES_TIME = 0.8        # [s] engine time measured per point (whole cycles, at least MIN_CYCLES)
MIN_CYCLES = 6
REFERENCE_FACTOR = 3     # the reference ensemble: this many times the cycles of a point
RIGID_SHARE = 0.25       # rigid-contact methods (100-3000 CPU s/s): this share of the cycles
SETTLE_CYCLES = 1        # engine cycles of every run before its measured ones
# headline statistics of the verdict "as accurate as the physics allows" (levels, then orders)
VERDICT_KEYS = ["tensioner.F.mean", "tensioner.F.peakToPeak", "chain.Ftight.mean", "chain.Fslack.mean",
                "tensionGuide.phi.peakToPeak_deg", "tensioner.F.order2", "tensioner.F.order4", "tensioner.F.order6",
                "tensioner.F.order8"]

# Methods: contact method x integrator (x joint model), each with a sweep of one setting.
METHODS = [
    dict(id="verlet", label="compliant / fixed-verlet", contact="compliant", integrator="fixed-verlet",
         option="step", full=[4e-6, 3e-6, 2.5e-6, 2e-6, 1e-6, 5e-7], quick=[2e-6, 1e-6], default=2.5e-6,
         stability=[1e-6, 2e-6, 3e-6, 3.125e-6, 1e-5 / 3, 4e-6, 6e-6, 8e-6], fixed=True),
    # Verlet with the damping implicit in each kick (fixed_verlet.cpp): the joints' by one Jacobi sweep
    # (the real-time method, at 1e-4 / 28 s in the FMU: between the points at 3.33 and 3.75 us), or the
    # diagonal of the joints' and contacts' damping
    dict(id="verlet-ijd", label="compliant / fixed-verlet-implicit-joint-damping", contact="compliant",
         integrator="fixed-verlet-implicit-joint-damping", option="step", full=[3e-6, 1e-5 / 3, 3.75e-6, 4e-6, 5e-6],
         quick=[1e-5 / 3], default=1e-5 / 3, stability=[2e-6, 3e-6, 4e-6, 5e-6, 6e-6, 8e-6], fixed=True),
    dict(id="verlet-id", label="compliant / fixed-verlet-implicit-damping", contact="compliant",
         integrator="fixed-verlet-implicit-damping", option="step", full=[2.5e-6, 3e-6, 1e-5 / 3, 3.75e-6],
         quick=[1e-5 / 3], default=1e-5 / 3, stability=[2e-6, 3e-6, 1e-5 / 3, 3.75e-6, 4e-6, 5e-6], fixed=True),
    dict(id="erk-fixed", label="compliant / arkode-erk-fixed", contact="compliant", integrator="arkode-erk-fixed",
         option="step", full=[4e-6, 2e-6, 1e-6], quick=[2e-6], default=2e-6,
         stability=[1e-6, 2e-6, 4e-6, 6e-6, 8e-6, 1.2e-5], fixed=True),
    dict(id="erk", label="compliant / arkode-erk", contact="compliant", integrator="arkode-erk",
         option="rtol", full=[1e-3, 1e-4, 1e-5, 1e-6, 1e-7], quick=[1e-4], default=1e-5,
         stability=[1e-2, 1e-3, 1e-5, 1e-7]),
    dict(id="bdf-klu", label="compliant / cvode-bdf-klu", contact="compliant", integrator="cvode-bdf-klu",
         option="rtol", full=[1e-3, 1e-4, 1e-5, 1e-6], quick=[1e-4], default=1e-5,
         stability=[1e-2, 1e-3, 1e-5, 1e-7]),
    # (cvode-bdf-band is not among them: the link model's state is laid out component by component,
    # so its Jacobian has no band and the band solver refuses it)
    dict(id="ts", label="time-stepping (rigid contacts)", contact="time-stepping", integrator="fixed-verlet",
         option="step", full=[3e-6, 2.5e-6, 1e-6], quick=[2.5e-6], default=2.5e-6,
         stability=[1e-6, 2e-6, 3e-6, 4e-6, 6e-6], fixed=True),
    dict(id="ts-ideal", label="time-stepping, ideal joints", contact="time-stepping", joints="ideal",
         integrator="fixed-verlet", option="step", full=[2e-5, 1e-5, 5e-6], quick=[2e-5], default=2e-5,
         stability=[5e-6, 1e-5, 2e-5, 4e-5, 8e-5], fixed=True),
    dict(id="ed", label="event-driven (rigid contacts)", contact="event-driven", integrator="arkode-erk",
         option="rtol", full=[1e-3, 1e-5, 1e-7], quick=[1e-5], default=1e-5, stability=[1e-3, 1e-5, 1e-7]),
    dict(id="ed-ideal", label="event-driven, ideal joints", contact="event-driven", joints="ideal",
         integrator="arkode-erk", option="rtol", full=[1e-4, 1e-6], quick=[1e-5], default=1e-5,
         stability=[1e-3, 1e-5, 1e-7]),
    # the joints and contacts implicit (link fidelity): stable far beyond Verlet's step
    dict(id="newmark", label="compliant / fixed-newmark", contact="compliant", integrator="fixed-newmark",
         option="step", full=[1.5e-5, 1e-5, 5e-6, 2.5e-6], quick=[1e-5], default=5e-6,
         stability=[5e-6, 1e-5, 1.5e-5, 2e-5, 3e-5], fixed=True),
]
REFERENCE = dict(id="reference", label="reference: compliant / arkode-erk", contact="compliant",
                 integrator="arkode-erk", option="rtol")
REFERENCE_CHECK = dict(id="reference-check", label="reference check: compliant / fixed-verlet", contact="compliant",
                       integrator="fixed-verlet", option="step")

KIND_CODES = {"blow-up": "BU", "non-finite": "NF", "tunnelling": "TU", "lcp-ray-termination": "RAY",
              "lcp-numerical-failure": "LCP", "lcp-iteration-limit": "LIT", "newton-failure": "NEW",
              "step-size-collapse": "STEP", "runaway-events": "EVT", "timeout": "TIME", "other": "ERR",
              "refused": "REF"}  # (refused: the method does not run the drive, before its first step)


def default_drive_json():
    return drive_json()


def setting_label(m, v):
    return f"h = {v * 1e6:g} us" if m["option"] == "step" else f"rtol = {v:g}"


def is_rigid(m):
    return m["contact"] != "compliant"


def refused(process):
    """chaindrive-run's own one-line refusal of a method on the drive (the combination's rule, before
    any step; exit status 1 without a summary), or None."""
    lines = [line for line in process.stderr.splitlines() if line.startswith("chaindrive-run: ")]
    if process.returncode != 1 or len(lines) != 1 or "does not integrate" not in lines[0]:
        return None
    return lines[0][len("chaindrive-run: "):]


def run_solver(out_dir, tag, m, value, rpm, inputs_csv, duration, timeout, initial_state=None, drive=None,
               save_state=None, write_csv=True, extra=(), output_step=OUTPUT_STEP):
    """One chaindrive-run; returns the parsed summary (with 'kind' = ok / failure kind / timeout).
    The fixed-step schemes never step past an output time, so their step must not exceed the
    output step: a run whose effective step differs from the one asked for is an error."""
    out_dir.mkdir(parents=True, exist_ok=True)
    csv = out_dir / f"{tag}.csv"
    summary = out_dir / f"{tag}.json"
    cmd = [paths.executable("chaindrive-run"), "--rpm", repr(float(rpm)), "--inputs", str(inputs_csv),
           "--duration", repr(duration), "--output-step", repr(output_step), "--contact-method", m["contact"],
           "--integrator", m["integrator"], f"--{m['option']}", repr(value), "--summary", str(summary), "--quiet"]
    if m.get("joints"):
        cmd += ["--joint-model", m["joints"]]
    if write_csv:
        cmd += ["--out", str(csv)]
    if initial_state:
        cmd += ["--initial-state", str(initial_state)]
    if drive:
        cmd += ["--drive", str(drive)]
    if save_state:
        cmd += ["--save-state", str(save_state)]
    cmd += list(extra)
    t0 = time.monotonic()
    try:
        p = subprocess.run(cmd, capture_output=True, text=True, timeout=timeout)
    except subprocess.TimeoutExpired:
        return dict(kind="timeout", failure=f"exceeded the wall-time budget of {timeout:g} s", cpuSeconds=timeout,
                    simulated=0.0, requested=duration, csv=None)
    wall = time.monotonic() - t0
    refusal = refused(p)
    if refusal:  # the method does not run this drive (event-driven: a hydraulic tensioner's chamber)
        return dict(kind="refused", failure=refusal, failureTime=0.0, cpuSeconds=0.0, simulated=0.0,
                    requested=duration, csv=None)
    if p.returncode not in (0, 3) or not summary.exists():
        raise RuntimeError(f"chaindrive-run failed ({p.returncode}): {' '.join(cmd)}\n{p.stderr.strip()}")
    s = json.loads(summary.read_text())
    if write_csv and abs(s.get("outputStep", output_step) - output_step) > 1e-9 * output_step:
        raise RuntimeError(f"{tag}: the output step {output_step:g} s is not a whole number of steps of "
                           f"{value:g} s (the runner wrote outputs every {s['outputStep']:g} s)")
    s["kind"] = "ok" if s["status"] == "ok" else s.get("failureKind", "other")
    s["csv"] = str(csv) if (write_csv and s["status"] == "ok") else None
    s["wall"] = wall
    return s
