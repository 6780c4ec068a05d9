"""The runs of the divergence-rate study: the damped drives, the start states and their
perturbation, and the twin pairs (twin A from a start state, twin B from it perturbed)."""
import concurrent.futures as cf
import json
import pathlib

from ... import runs
from ...drive.description import elements
from ...job import run_in_cycles
from ...tables import tables
from ..methods import default_drive_json, run_solver

OUTPUT_STEP = 2e-5      # [s] output interval of every twin (50 kHz)
PERTURBATION = 1e-12    # relative change of one state component
# the smoke variant's twin length [engine cycles]: the default drive's twins (hydraulic tensioner)
# grow from the perturbation to independence in some 200 ms at 3000 rpm (a tensioner-force
# difference of 1e-6 N after the perturbation, 1e-2 N 80 ms later)
QUICK_CYCLES = 6


def damped_drive(path, joint, contact):
    """The default drive with joint damping and both contact damping factors scaled."""
    d = default_drive_json()
    d["chain"]["joint"]["damping"] *= joint
    for law in ("rollerSprocket", "plateGuide"):
        d["contact"][law]["dampingFactor"] *= contact
    path.parent.mkdir(parents=True, exist_ok=True)
    path.write_text(json.dumps(d, indent=1))
    return path


def rotor_angle_states(drive):
    """{rotor name: index of its angle in the state vector}: the layout of src/assembly/model.h (the 6 link
    components, each over all links, then per rotor its angle and, if free, its rate; sprockets first, then
    pivoting guides)."""
    idx = 6 * drive["chain"]["numberOfLinks"]
    out = {}
    for s in drive["sprockets"]:
        out[s["name"]] = idx
        idx += 1 if s.get("motion") == "prescribed" else 2
    for g in drive["guides"]:
        if g.get("motion") == "pivoting":
            out[g["name"]] = idx
            idx += 2
    return out


def link_state(drive, link, component):
    """Index of a link's state component (0 x, 1 y, 2 gamma, 3 vx, 4 vy, 5 omega): component by component over
    the links (src/assembly/model.h)."""
    return component * drive["chain"]["numberOfLinks"] + link


def perturbation_plan(drive, pairs):
    """(label, state index) per pair: link x or y spread along the chain, every third a rotor angle;
    pair k's component does not depend on the number of pairs (the step check's pairs are the
    ensemble's first ones)."""
    links = drive["chain"]["numberOfLinks"]
    rotors = list(rotor_angle_states(drive).items())
    plan = []
    for k in range(pairs):
        if k % 3 == 2:
            name, idx = rotors[(k // 3) % len(rotors)]
            plan.append((f"{name} angle", idx))
        else:
            link = (17 * k) % links
            coord = "xy"[k % 2]
            plan.append((f"link {link} {coord}", link_state(drive, link, "xy".index(coord))))
    return plan


def perturbed_state(src, dst, index, relative):
    """Copies a state file with state component `index` multiplied by (1 + relative)."""
    s = json.loads(pathlib.Path(src).read_text())
    v = float.fromhex(s["y"][index])
    w = v * (1.0 + relative)
    if w == v:
        raise ValueError(f"state {index} = {v!r}: a relative change of {relative:g} does not change it")
    s["y"][index] = w.hex()
    pathlib.Path(dst).write_text(json.dumps(s, indent=1))
    return dst


class Context:
    """What every run of the study shares: options, the inputs, the engine cycle, the log."""

    def __init__(self, args, settings):
        self.args = args
        self.quick = args.quick
        self.out = pathlib.Path(args.out)
        self.runs_dir = self.out / "runs"
        self.rpm = float(args.rpm)
        # an engine cycle as a whole number of output steps, so that the start states and the
        # twins' samples share one time grid
        self.cycle = round(120.0 / self.rpm / OUTPUT_STEP) * OUTPUT_STEP
        self.run_in_cycles = 1 if self.quick else run_in_cycles(self.rpm)
        self.timeout = 120.0 if self.quick else args.timeout
        self.verlet_steps = args.verlet_steps
        self.max_cycles = 2 if self.quick else args.max_cycles
        self.mesh = elements(default_drive_json())  # (the default drive's elements: the cycle statistics')
        self.log_lines = []
        self.states = {}  # setting id -> (start-state files, method that made them)
        longest = max(self.pairs(s) - 1 + max(self.cycles(s), self.max_cycles) for s in settings)
        self.runs_dir.mkdir(parents=True, exist_ok=True)
        self.inputs = tables.write_inputs_csv(self.runs_dir / "inputs.csv", self.rpm,
                                              (self.run_in_cycles + longest + 1) * self.cycle, dt=OUTPUT_STEP)

    def log(self, line):
        print(line, flush=True)
        self.log_lines.append(line)

    def pairs(self, s):
        return 3 if self.quick else self.args.pairs or s.get("pairs", 12)

    def cycles(self, s):
        """Shortest twin [engine cycles]: the step check's twins, and the least of the ensemble's."""
        return QUICK_CYCLES if self.quick else self.args.cycles or s.get("cycles", 5)

    def solve(self, sd, tag, method, duration, **kw):
        """One chaindrive-run (study.run_solver) with the study's inputs; adaptive methods get no
        step-size floor (their steps at contact onsets go below the default 1e-10 s at tight
        tolerances)."""
        extra = ("--min-step", "1e-15") if method["option"] == "rtol" else ()
        return run_solver(sd, tag, method, method["value"], self.rpm, self.inputs, duration, self.timeout,
                                extra=extra, output_step=OUTPUT_STEP, **kw)


def verlet(step):
    return dict(contact="compliant", integrator="fixed-verlet", option="step", value=step)


def method_label(m):
    return f"{m['integrator']} {m['value'] * 1e6:g} us" if m["option"] == "step" else \
        f"{m['integrator']} rtol {m['value']:g}"


def failure_of(r):
    return dict(kind=r["kind"], failure=r.get("failure"), failureTime=r.get("failureTime"))


def run_in(ctx, drive, sd, steps):
    """The run-in from the pre-loaded state with the first Verlet step of `steps` that completes
    it: (S_0, its method, every step tried with its outcome)."""
    sd.mkdir(parents=True, exist_ok=True)
    state = sd / "S0.json"
    tried = []
    for step in steps:
        state.unlink(missing_ok=True)
        m = verlet(step)
        r = ctx.solve(sd, f"runin_{step:g}", m, ctx.run_in_cycles * ctx.cycle, drive=drive, save_state=state,
                      write_csv=False)
        tried.append(dict(step=step, cpuSeconds=r.get("cpuSeconds"), **failure_of(r)))
        ctx.log(f"  run-in {ctx.run_in_cycles} cycles, {method_label(m)}: " +
                ("ok" if r["kind"] == "ok" else f"FAILED ({r['kind']}) at t = {r.get('failureTime') or 0:.6f} s: "
                                                 f"{r.get('failure')}"))
        if r["kind"] == "ok":
            return state, m, tried
    return None, None, tried


def continued_states(ctx, m, drive, sd, files, count):
    """S_0 .. S_(count-1): `files` continued one engine cycle at a time; (states, None) or
    (None, the failure)."""
    files = list(files)
    while len(files) < count:
        k = len(files)
        r = ctx.solve(sd, f"segment_{k}", m, ctx.cycle, initial_state=files[-1], drive=drive,
                      save_state=sd / f"S{k}.json", write_csv=False)
        if r["kind"] != "ok":
            ctx.log(f"  start state {k}: FAILED ({r['kind']}): {r.get('failure')}")
            return None, dict(step=m["value"], stage=f"start state {k}", **failure_of(r))
        files.append(sd / f"S{k}.json")
    return files, None


def twin(ctx, sd, tag, m, drive, state, duration):
    """One twin: its outputs (the columns the analysis needs) or its failure."""
    r = ctx.solve(sd, tag, m, duration, initial_state=state, drive=drive)
    out = dict(cpuSeconds=r.get("cpuSeconds"), simulated=r.get("simulated"), **failure_of(r))
    if r["kind"] == "ok":
        d = runs.read_csv(r["csv"])
        out["data"] = {c: d[c] for c in KEEP_COLUMNS}
        if not ctx.args.keep_runs:
            pathlib.Path(r["csv"]).unlink()
    return out


KEEP_COLUMNS = ("time", "crankshaft.phi", "camshaftIntake.phi", "camshaftExhaust.phi", "tensioner.F",
                "tensionGuide.phi", "chain.Ftight", "chain.Fslack")


def run_twins(ctx, m, drive, states, sd, cycles, quiet=False):
    """Every pair: twin A from S_k, twin B from S_k with one component perturbed, `cycles` engine
    cycles long."""
    sd.mkdir(parents=True, exist_ok=True)
    plan = perturbation_plan(json.loads(pathlib.Path(drive).read_text()), len(states))
    duration = cycles * ctx.cycle + 1e-3  # 1 ms more: the crankshaft lags the mean speed a little
    jobs = []
    for k, (state, (label, index)) in enumerate(zip(states, plan)):
        pert = perturbed_state(state, sd / f"S{k}_perturbed.json", index, PERTURBATION)
        jobs.append((k, label, index, state, pert))
    with cf.ThreadPoolExecutor(max_workers=ctx.args.jobs) as ex:
        futures = [(job, ex.submit(twin, ctx, sd, f"A{job[0]}", m, drive, job[3], duration),
                    ex.submit(twin, ctx, sd, f"B{job[0]}", m, drive, job[4], duration)) for job in jobs]
        pairs = []
        for (k, label, index, _, _), fa, fb in futures:
            a, b = fa.result(), fb.result()
            p = dict(start=k, perturbation=label, stateIndex=index, A=a, B=b)
            p["kind"] = "ok" if a["kind"] == b["kind"] == "ok" else (a if a["kind"] != "ok" else b)["kind"]
            pairs.append(p)
            if p["kind"] != "ok" or not quiet:
                ctx.log(f"  pair {k:2d} ({label}): " + ("ok" if p["kind"] == "ok" else
                        f"FAILED ({p['kind']}): {(a if a['kind'] != 'ok' else b).get('failure')}"))
    return pairs
