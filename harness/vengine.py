"""A V-engine's timing chains coupled by co-simulation (docs/v_engine.md): the V6's primary drive
(tests/drives/v6_primary.json: crankshaft to two intermediate shafts) and a bank drive per
cylinder bank (tests/drives/v6_bank.json: the shaft's sprocket to the bank's two camshafts), each
its own FMU, coupled through the intermediate shafts by an explicit master in fmpy:

- each bank's shaft turns at the primary's shaft speed: bank `shaft.w` = primary `<shaft>.w`;
- the primary's shaft carries the bank's chain: primary `<shaft>.tau` (a load, positive against
  the rotation) = - the bank's chain torque on its prescribed sprocket (positive in the running
  direction: negative while the bank's chain loads it), by default its step mean `shaft.tauMean`
  carried on to the middle of the next step (TORQUES: --torque step-mean passes the plain mean,
  --torque sampled `shaft.tau` at the step's end, which samples the roller impacts);

each step's inputs computed from the outputs after the step before and held over the step
(Jacobi: the three FMUs step side by side; fmpy, or libcosim and ecos with the same bits:
run_libcosim, run_ecos; --coupling speed-first gives each bank its new speed before its torque is
read). The engine: a 60-degree V6, firing order 1-2-3-4-5-6 alternating between the banks every
120 deg crank; each bank's camshafts carry the valve-train model's loads of three cylinders (the
i4-bucket valve trains, SYNTHESIZED), the crankshaft speed the model's with firing order 3
(estimates). A bank's statistics key on the engine's crank angle: its camshafts turn at half the
crankshaft's speed through the two ratios (21/28 x 22/33 = 1/2).

    python -m harness v-engine [--coupling jacobi|speed-first] [--torque extrapolated|step-mean|sampled] [--rpm 3000]
        [--cycles 48] [--run-in 40] [--steps 1e-4 5e-5 2.5e-5 1.25e-5] [--out DIR]
"""
import dataclasses
import json
import math
import pathlib
import sys
import time

import numpy as np

from . import checks, cycle_stats, paths, runin
from .drive import description
from .errors import UserError
from .fmu import export, fmu
from .tables import make_tables, valvetrain

PRIMARY = paths.ROOT / "tests" / "drives" / "v6_primary.json"
BANK = paths.ROOT / "tests" / "drives" / "v6_bank.json"
# bank: (its shaft on the primary drive, its firing offset [deg crank] after cylinder 1's firing TDC)
BANKS = {"left": ("leftShaft", 0.0), "right": ("rightShaft", 120.0)}


def _teeth(drive):
    return {s["name"]: s["teeth"] for s in json.loads(drive.read_text())["sprockets"]}


def _ratios():
    """Crankshaft revolutions per intermediate-shaft revolution (28/21) and per camshaft revolution
    (28/21 x 33/22 = 2, in integers, exact), from the drives' teeth."""
    primary, bank = _teeth(PRIMARY), _teeth(BANK)
    shafts = {primary[s] for s, _ in BANKS.values()}
    cams = {bank[c] for c in CAMS}
    if len(shafts) != 1 or len(cams) != 1:
        raise ValueError(f"{PRIMARY.name}, {BANK.name}: both intermediate shafts and both camshafts need the same teeth")
    shaft, cam = shafts.pop(), cams.pop()
    return shaft / primary["crankshaft"], (shaft * cam) / (primary["crankshaft"] * bank["shaft"])


# solver steps per 0.1 ms: at or below each drive's own (1e-4/35 and 1e-4/31, chaindrive-info
# --defaults), so that communication steps of 0.1 ms / 2, / 4 and / 8 hold whole solver steps
SOLVER_DIVISIONS = {"primary": 40, "bank": 32}
SUPPLY_PRESSURE = description.SUPPLY_PRESSURE  # [Pa] the gallery's oil pressure at every tensioner (the main job's)
CAMS = ("intakeCam", "exhaustCam")
SHAFT_RATIO, CAM_RATIO = _ratios()
RUN_IN_MINIMUM = 8          # engine cycles of run-in at least (the main job's at 3000 rpm)

# [E] a V6's crankshaft: firing order 3 (three firings per revolution), smoother than an I4's
# order 2 (2.7 deg at idle): 1.2 deg at idle
V6_CRANK = valvetrain.CrankSpeedModel(base_order=3, idle_amplitude_deg=1.2)
# a bank: three cylinders firing every 240 deg, the i4-bucket's valve trains and camshaft drag
BANK_ENGINE = dataclasses.replace(valvetrain.I4_BUCKET, name="v6-bank", firing_order=(1, 2, 3), crank=V6_CRANK,
                                  description="one bank of a 60-degree V6: 3 cylinders, firing every 240 deg crank")


@dataclasses.dataclass(frozen=True)
class Tables:
    """The engine's tables of one speed over crank angle [deg, 0..720 in RESOLUTION_DEG steps]."""
    theta: np.ndarray
    speed_rpm: np.ndarray                  # crankshaft speed
    cams: dict                             # (bank, cam) -> load torque [N m] at the crankshaft's angle

    def speed(self, crank_deg):
        return float(np.interp(crank_deg, self.theta, self.speed_rpm, period=720.0)) * math.pi / 30.0

    def load(self, bank, cam, crank_deg):
        return float(np.interp(crank_deg, self.theta, self.cams[(bank, cam)], period=720.0))


def engine_tables(rpm, seed=make_tables.DEFAULT_SEED):
    """The V6's SYNTHESIZED tables at one speed: the bank engine's camshaft loads (bank left; the
    right bank's the same 120 deg later) and the crankshaft speed of firing order 3."""
    theta = make_tables.angles()
    torques, _, _ = make_tables.camshaft_torques(rpm, seed, BANK_ENGINE)
    speed, _, _ = make_tables.crankshaft_speed(rpm, seed, BANK_ENGINE)
    names = {"intakeCam": "camshaftIntake.tau", "exhaustCam": "camshaftExhaust.tau"}
    cams = {}
    for bank, (_, offset) in BANKS.items():
        for cam, column in names.items():
            cams[(bank, cam)] = np.interp(theta - offset, theta, torques[column], period=720.0)
    return Tables(theta, speed, cams)


FMUS = ("primary", *BANKS)
# the bank's torque the primary's shaft carries, and the output it comes from: "extrapolated" the
# step mean over the step before carried half a step on to the middle of the next (2 m_k - m_k-1:
# a plain mean is centred a whole step before the step it is held over, a lag the stiff shafts
# amplify), "step-mean" the plain mean, "sampled" the torque at the step's end (it samples the
# roller impacts, 14-20 us, at the communication step)
TORQUES = {"extrapolated": "shaft.tauMean", "step-mean": "shaft.tauMean", "sampled": "shaft.tau"}


def carried_torque(torque, now, before):
    """The bank's chain torque for the next step from its outputs after the last step (`now`) and
    after the one before it (`before`; None at the start)."""
    value = now[TORQUES[torque]]
    if torque == "extrapolated" and before is not None:
        return 2.0 * value - before[TORQUES[torque]]
    return value


def coupling_outputs(torque):
    """What the coupling reads of each FMU after a step ({fmu: [names]})."""
    return {"primary": ["crankshaft.phi"] + [f"{shaft}.w" for shaft, _ in BANKS.values()],
            **{bank: [TORQUES[torque]] + [c + ".phi" for c in CAMS] for bank in BANKS}}


def drive_of(name):
    return PRIMARY if name == "primary" else BANK


def solver_step(name):
    return 1e-4 / SOLVER_DIVISIONS["primary" if name == "primary" else "bank"]


def start_outputs(tables, torque):
    """What the first step's inputs are computed from: every angle 0, the shafts at the table's
    speed, no torque from the banks yet (the run-in takes up the start)."""
    out = {"primary": {"crankshaft.phi": 0.0, **{f"{s}.w": tables.speed(0.0) / SHAFT_RATIO for s, _ in BANKS.values()}}}
    out.update({bank: {TORQUES[torque]: 0.0, **{c + ".phi": 0.0 for c in CAMS}} for bank in BANKS})
    return out


def coupling_inputs(tables, out, torque, before=None):
    """Every FMU's inputs for the next step from the outputs after the last one ({fmu: {name: value}}):
    the crankshaft's speed from the table at its angle, each bank's shaft at the primary's shaft
    speed and its camshafts' loads at their crank angles, each primary shaft loaded by minus its
    bank's chain torque (carried_torque; `before`: the outputs after the step before)."""
    p = out["primary"]
    u = {"primary": {"crankshaft.w": tables.speed(math.degrees(p["crankshaft.phi"])),
                     "tensioner.supplyPressure": SUPPLY_PRESSURE}}
    for bank, (shaft, _) in BANKS.items():
        b = out[bank]
        u[bank] = {"shaft.w": p[shaft + ".w"], "tensioner.supplyPressure": SUPPLY_PRESSURE}
        for c in CAMS:
            u[bank][c + ".tau"] = tables.load(bank, c, CAM_RATIO * math.degrees(b[c + ".phi"]))
        u["primary"][shaft + ".tau"] = -carried_torque(torque, b, before[bank] if before else None)
    return u


COUPLINGS = ("jacobi", "speed-first")


def combination_problem(coupling, torque):
    """Why a coupling does not go with a torque (None if it does)."""
    if coupling == "speed-first" and torque != "sampled":
        return (f"--torque {torque} with --coupling speed-first: speed-first passes the torque's direct dependence "
                "on the bank's new speed, which only the sampled torque has (a step mean is the step before's); "
                "allowed: --torque sampled, or --coupling jacobi")
    return None


class Coupled:
    """The three FMUs in fmpy, stepped side by side: each step's inputs from the outputs after the
    step before (the first step's from start_outputs), held over the step. `coupling` "jacobi":
    exactly that; "speed-first": each bank gets its new inputs first, and the primary's load is the
    bank's chain torque with them (its direct dependence on its shaft's speed taken in; the banks
    initialized first, the primary then with their torques). `torque`: TORQUES."""

    def __init__(self, tables, coupling="jacobi", torque="extrapolated"):
        if combination_problem(coupling, torque):
            raise ValueError(combination_problem(coupling, torque))
        self.tables, self.coupling, self.torque = tables, coupling, torque
        self.last = None  # the outputs after the last step
        self.slaves = {n: fmu.Slave(n, fmu=export.fmu_for(drive_of(n)), parameters={"solver.step": solver_step(n)})
                       for n in FMUS}
        self.rows = []

    def start(self):
        self.inputs = coupling_inputs(self.tables, start_outputs(self.tables, self.torque), self.torque)
        for bank in BANKS:
            self.slaves[bank].initialize(inputs=self.inputs[bank])
        self.banks_first()
        self.slaves["primary"].initialize(inputs=self.inputs["primary"])
        self.record(0.0, {})

    def banks_first(self):
        """speed-first: the primary's loads from the banks' chain torques with their new inputs."""
        if self.coupling != "speed-first":
            return
        for bank, (shaft, _) in BANKS.items():
            for name, value in self.inputs[bank].items():
                self.slaves[bank].set(name, value)
            self.inputs["primary"][shaft + ".tau"] = -self.slaves[bank].get(["shaft.tau"])["shaft.tau"]

    def step(self, t, h):
        """One communication step from t with the inputs the last outputs gave."""
        used = self.inputs
        for name, slave in self.slaves.items():
            slave.step(h, inputs=used[name], t=t)
        wanted = coupling_outputs(self.torque)
        out = {name: slave.get(wanted[name]) for name, slave in self.slaves.items()}
        self.inputs = coupling_inputs(self.tables, out, self.torque, self.last)
        self.last = out
        self.banks_first()
        self.record(t + h, used)

    def record(self, t, used):
        """A row: the outputs at t and the inputs held over the step that ended there."""
        row = {"time": t}
        for name, slave in self.slaves.items():
            row.update({f"{name}.{k}": v for k, v in slave.get().items()})
            row.update({f"{name}.input.{k}": v for k, v in used.get(name, {}).items()})
        self.rows.append(row)

    def close(self):
        for slave in self.slaves.values():
            slave.close()

    def cpu(self):
        return sum(s.step_cpu for s in self.slaves.values())


def run_coupled(rpm, cycles, run_in, h, tables, coupling="jacobi", torque="extrapolated"):
    """The coupled V6 over run_in + cycles engine cycles at communication step h: its record
    (name -> array) and the CPU seconds inside the three FMUs' fmi2DoStep."""
    steps = int(math.ceil((run_in + cycles) * 120.0 / rpm / h - 1e-9))
    coupled = Coupled(tables, coupling, torque)
    try:
        coupled.start()
        for k in range(steps):
            coupled.step(k * h, h)
    except fmu.Refusal as e:
        raise UserError(f"v-engine at a communication step of {h:g} s: {e}") from None
    finally:
        coupled.close()
        for name, slave in coupled.slaves.items():   # (what the FMUs warned of, once each)
            for text in sorted({m for status, _, m in slave.messages if status == 1}):
                print(f"warning: {name} FMU at {h:g} s: {text}", file=sys.stderr)
    names = [n for n in coupled.rows[-1]]
    record = {n: np.array([r.get(n, np.nan) for r in coupled.rows]) for n in names}
    return record, coupled.cpu()


def run_libcosim(steps, h, tables, names, torque="extrapolated"):
    """The same coupling with libcosim stepping the three FMUs (its fixed-step algorithm; the inputs
    overridden by a manipulator before each step, the outputs read by an observer after it): the
    record of `names` ({fmu: [output names]}) after each step, as arrays named "<fmu>.<output>"."""
    from libcosimpy.CosimExecution import CosimExecution
    from libcosimpy.CosimLogging import CosimLogLevel, log_output_level
    from libcosimpy.CosimManipulator import CosimManipulator
    from libcosimpy.CosimObserver import CosimObserver
    from libcosimpy.CosimSlave import CosimLocalSlave

    log_output_level(CosimLogLevel.ERROR)
    ex = CosimExecution.from_step_size(int(round(h * 1e9)))
    idx, vr = {}, {}
    for name in FMUS:
        path = export.fmu_for(drive_of(name))
        idx[name] = ex.add_local_slave(CosimLocalSlave(fmu_path=str(path), instance_name=name))
        vr[name] = {v.name: v.valueReference for v in fmu.unpacked(path)[0].modelVariables}
        ex.real_initial_value(idx[name], vr[name]["solver.step"], solver_step(name))
    inputs = coupling_inputs(tables, start_outputs(tables, torque), torque)
    for name in FMUS:
        for k, value in inputs[name].items():
            ex.real_initial_value(idx[name], vr[name][k], value)
    observer, manipulator = CosimObserver.create_last_value(), CosimManipulator.create_override()
    ex.add_observer(observer)
    ex.add_manipulator(manipulator)
    wanted = {n: sorted(set(names.get(n, [])) | set(coupling_outputs(torque)[n])) for n in FMUS}
    rows, last = [], None
    for k in range(steps):
        if k:
            for name in FMUS:
                refs = [vr[name][x] for x in inputs[name]]
                manipulator.slave_real_values(idx[name], refs, list(inputs[name].values()))
        if not ex.step():
            raise UserError(f"libcosim: the coupled V6's step {k} failed")
        out = {n: dict(zip(wanted[n], observer.last_real_values(idx[n], [vr[n][x] for x in wanted[n]]))) for n in FMUS}
        inputs, last = coupling_inputs(tables, out, torque, last), out
        rows.append({f"{n}.{x}": v for n in FMUS for x, v in out[n].items()})
    return {key: np.array([r[key] for r in rows]) for key in rows[0]}


def run_ecos(steps, h, tables, names, torque="extrapolated"):
    """The same coupling with ecos stepping the three FMUs (its fixed-step simulation; the inputs set
    before each step, the outputs read after it): the record of `names` ({fmu: [output names]})
    after each step, as arrays named "<fmu>.<output>"."""
    from ecospy import EcosSimulation, EcosSimulationStructure

    structure = EcosSimulationStructure()
    for name in FMUS:
        structure.add_model(name, str(export.fmu_for(drive_of(name))))
    structure.add_parameter_set("parameters", {f"{n}::solver.step": solver_step(n) for n in FMUS})
    sim = EcosSimulation(structure=structure, step_size=h)
    wanted = {n: sorted(set(names.get(n, [])) | set(coupling_outputs(torque)[n])) for n in FMUS}
    inputs, rows, last = coupling_inputs(tables, start_outputs(tables, torque), torque), [], None
    try:
        for k in range(steps + 1):
            for name in FMUS:
                for x, value in inputs[name].items():
                    sim.set_real(f"{name}::{x}", float(value))
            if k == 0:
                sim.init(0.0, "parameters")
                continue
            sim.step(1)
            out = {n: {x: sim.get_real(f"{n}::{x}") for x in wanted[n]} for n in FMUS}
            inputs, last = coupling_inputs(tables, out, torque, last), out
            rows.append({f"{n}.{x}": v for n in FMUS for x, v in out[n].items()})
        sim.terminate()
    finally:
        sim.free()
    return {key: np.array([r[key] for r in rows]) for key in rows[0]}


def of(record, prefix):
    """One FMU's part of the record, its names without the prefix."""
    return {k[len(prefix) + 1:]: v for k, v in record.items() if k.startswith(prefix + ".")}


def per_cycle(record, spans):
    """Per counted engine cycle (keyed on the crankshaft's angle): the means of the three tensioner
    forces, the primary's tight-span force and each shaft's load, each bank's camshaft timing
    peak-to-peak [deg crank]."""
    crank = record["primary.crankshaft.phi"]
    quantities = {"primary.tensioner.F.mean": ("N", record["primary.tensioner.F"], np.mean),
                  "primary.chain.Ftight.mean": ("N", record["primary.chain.Ftight"], np.mean)}
    for bank, (shaft, offset) in BANKS.items():
        quantities[f"{bank}.tensioner.F.mean"] = ("N", record[f"{bank}.tensioner.F"], np.mean)
        quantities[f"{shaft}.load.mean"] = ("N m", record[f"primary.input.{shaft}.tau"], np.mean)
        timing = np.degrees(CAM_RATIO * record[f"{bank}.intakeCam.phi"] - crank)
        quantities[f"{bank}.intakeCam.timing.peakToPeak_degCA"] = ("deg", timing, np.ptp)
    return {key: (unit, np.array([f(x[i0:i1]) for i0, i1, _ in spans])) for key, (unit, x, f) in quantities.items()}


def balances(record, first, last):
    """Per shaft over samples first..last: the primary's mean chain torque on it against the bank's
    torque it carries; the work the primary does on the shaft (the held load times the primary
    shaft's turn per step) against the work the bank's shaft receives (the same torque times the
    bank shaft's turn); the bank shaft's angle against the primary's, from their difference at the
    start (drift) [deg]. Per FMU: the energy balance."""
    out = {}
    for bank, (shaft, _) in BANKS.items():
        load = record[f"primary.input.{shaft}.tau"][first + 1:last]       # (held over the step ending at its row)
        turn_p = np.diff(record[f"primary.{shaft}.phi"][first:last])
        turn_b = np.diff(record[f"{bank}.shaft.phi"][first:last])
        work_p, work_b = float(np.sum(load * turn_p)), float(np.sum(load * turn_b))
        offset = record[f"{bank}.shaft.phi"] - record[f"primary.{shaft}.phi"]
        drift = np.degrees(offset[first:last] - offset[0])   # (the start's offset: the preload winds the shaft up)
        chain = float(np.mean(record[f"primary.{shaft}.tauChain"][first:last]))
        out[shaft] = {"chainTorque_Nm": chain, "load_Nm": float(np.mean(load)),
                      "torqueError": chain / float(np.mean(load)) - 1.0,
                      "workPrimary_J": work_p, "workBank_J": work_b, "workError": work_b / work_p - 1.0,
                      "driftMax_deg": float(np.max(np.abs(drift))), "driftEnd_deg": float(drift[-1])}
    for name in ("primary", *BANKS):
        out[f"{name}.energyBalance"] = checks.energy_balance_error(of(record, name), first, last - 1)
    return out


def settling(record, run_in):
    """The run-in: the engine cycles until all three tensioners have settled (runin.detect on each
    FMU's stroke over the primary's crank angle; at least 8 cycles, at most `run_in`); per FMU its
    Settling."""
    out = {}
    for name in ("primary", *BANKS):
        sub = {"crankshaft.phi": record["primary.crankshaft.phi"], runin.SIGNAL: record[f"{name}.{runin.SIGNAL}"]}
        out[name] = runin.detect(sub, "crankshaft", RUN_IN_MINIMUM, run_in)
    return max(s.cycles for s in out.values()), out


def warnings_of(result):
    """A study point's warning lines: an energy balance beyond the main job's limit, a tensioner that
    had not settled when the counted cycles began."""
    if "failed" in result:
        return []
    lines = [f"{name}: {w}" for name in FMUS for w in checks.energy_warnings(result["balances"][f"{name}.energyBalance"])]
    lines += [f"{name}: the tensioner had not settled after {v['runInCycles']} cycles"
              for name, v in result["settled"].items() if not v["tensionerSettled"]]
    return lines


def study(rpm, cycles, run_in, step, tables, coupling="jacobi", torque="extrapolated"):
    """One communication step: the coupled run over `run_in` + `cycles` engine cycles, its run-in
    until the three tensioners have settled, then `cycles` counted cycles' statistics, the balances
    and the cost; or, when an FMU refuses a step (a blow-up), {"step_s", "failed": the reason}."""
    wall = time.perf_counter()
    try:
        record, cpu = run_coupled(rpm, cycles, run_in, step, tables, coupling, torque)
    except UserError as e:   # (a blow-up: where explicit coupling stops being stable, a result)
        return {"step_s": step, "failed": str(e)}
    settled_after, settlings = settling(record, run_in)
    spans = cycle_stats.counted_spans(record["primary.crankshaft.phi"], settled_after, cycles)
    stats = {key: (unit, *cycle_stats.interval(values)[:2]) for key, (unit, values) in per_cycle(record, spans).items()}
    return {"step_s": step, "runInCycles": settled_after, "settled": {k: v.json() for k, v in settlings.items()},
            "cycles": len(spans), "stats": stats, "balances": balances(record, spans[0][0], spans[-1][1]),
            "doStepCpu_s": cpu, "wall_s": time.perf_counter() - wall, "simulated_s": float(record["time"][-1])}


def balance_rows(results):
    """The report's balance table: a row per communication step and shaft, a row per failed step."""
    rows = ["| communication step | shaft | chain torque / carried load [N m] | work primary / bank [J] (error) | "
            "drift max [deg] | energy balance primary, left, right | run-in, counted cycles | CPU in fmi2DoStep [s] |",
            "|---|---|---|---|---|---|---|---|"]
    for r in (r for r in results if "failed" not in r):
        b = r["balances"]
        energy = ", ".join(f"{b[f'{n}.energyBalance']:+.2%}" for n in ("primary", *BANKS))
        settled = "" if all(v["tensionerSettled"] for v in r["settled"].values()) else " (not settled)"
        for shaft in (s for s, _ in BANKS.values()):
            x = b[shaft]
            rows.append(f"| {r['step_s'] * 1e6:g} us | {shaft} | {x['chainTorque_Nm']:.3f} / {x['load_Nm']:.3f} "
                        f"({x['torqueError']:+.2%}) | {x['workPrimary_J']:.2f} / {x['workBank_J']:.2f} "
                        f"({x['workError']:+.3%}) | {x['driftMax_deg']:.4f} | {energy} | "
                        f"{r['runInCycles']}{settled}, {r['cycles']} | {r['doStepCpu_s']:.1f} |")
    for r in (r for r in results if "failed" in r):
        rows.append(f"| {r['step_s'] * 1e6:g} us | failed: {r['failed']} | | | | | | |")
    return rows


def stats_rows(results):
    """The report's table of cycle statistics: a row per quantity, a column per step that ran."""
    ran = [r for r in results if "failed" not in r]
    rows = ["| quantity | " + " | ".join(f"{r['step_s'] * 1e6:g} us" for r in ran) + " |", "|---|" + "---|" * len(ran)]
    for key, (unit, *_rest) in ran[0]["stats"].items():
        cells = [f"{r['stats'][key][1]:.4g} +- {r['stats'][key][2]:.2g}" for r in ran]
        rows.append(f"| `{key}` [{unit}] | " + " | ".join(cells) + " |")
    return rows


def report(results, rpm, cycles, run_in, coupling="jacobi", torque="extrapolated"):
    """The study's page (markdown): per communication step the balances, the drift, the cycle
    statistics with their intervals and the cost."""
    steps = " ".join(f"{r['step_s']:g}" for r in results)
    lines = ["# V-engine chains coupled through their shafts", "",
             f"`python -m harness v-engine --coupling {coupling} --torque {torque} --rpm {rpm:g} --cycles {cycles} --run-in {run_in} "
             f"--steps {steps}` "
             "(harness/vengine.py, docs/v_engine.md): the V6's primary drive and its two bank drives, three FMUs "
             f"coupled explicitly through the intermediate shafts at {rpm:g} rpm: a run-in until the three tensioners "
             f"have settled (at most {run_in} engine cycles; the cycles per step in the table), then the counted "
             "cycles.", "", "## Balances across the shafts and drift", ""]
    lines += balance_rows(results)
    lines += ["", "## Cycle statistics (mean +- 95 % half-width over the counted cycles)", ""] + stats_rows(results)
    return "\n".join(lines) + "\n"


def add_arguments(ap):
    ap.add_argument("--rpm", type=float, default=3000.0, help="engine speed (default 3000; the tables are made for it)")
    ap.add_argument("--cycles", type=int, default=48, help="counted engine cycles (default 48)")
    ap.add_argument("--run-in", type=int, default=40,
                    help="the most engine cycles of run-in (default 40): it ends when all three tensioners have "
                         "settled (as the main job's), the run is this long plus the counted cycles")
    ap.add_argument("--steps", type=float, nargs="+", default=[1e-4, 5e-5, 2.5e-5, 1.25e-5],
                    help="communication steps [s] (default 1e-4 5e-5 2.5e-5 1.25e-5); each a whole number of both "
                         "drives' "
                         f"solver steps (1e-4/{SOLVER_DIVISIONS['primary']} and 1e-4/{SOLVER_DIVISIONS['bank']})")
    ap.add_argument("--coupling", choices=COUPLINGS, default="jacobi",
                    help="jacobi (default): every input from the outputs after the step before; speed-first: the "
                         "banks' new speeds first, the primary's loads their chain torques with them")
    ap.add_argument("--torque", choices=tuple(TORQUES), default="extrapolated",
                    help="the bank's chain torque the primary's shaft carries: extrapolated (default: the step mean "
                         "shaft.tauMean carried on to the middle of the next step, 2 m_k - m_k-1), step-mean (the "
                         "plain mean over the step before) or sampled (shaft.tau at the step's end)")
    ap.add_argument("--out", default=str(paths.RESULTS / "v_engine"), help="the results folder")


def check(ap, args):
    for h in args.steps:
        for fmu_name, n in SOLVER_DIVISIONS.items():
            steps = h / (1e-4 / n)
            if abs(steps - round(steps)) > 1e-6 or round(steps) < 1:
                ap.error(f"--steps {h:g}: not a whole number of the {fmu_name} drive's solver steps (1e-4/{n} s)")
    if combination_problem(args.coupling, args.torque):
        ap.error(combination_problem(args.coupling, args.torque))
    if args.cycles < 2 or args.run_in < RUN_IN_MINIMUM:
        ap.error(f"--cycles: at least 2, --run-in: at least {RUN_IN_MINIMUM}")
    return args


def run(args):
    tables = engine_tables(args.rpm)
    results = []
    for h in args.steps:
        results.append(study(args.rpm, args.cycles, args.run_in, h, tables, args.coupling, args.torque))
        for line in warnings_of(results[-1]):
            print(f"warning: step {h:g} s: {line}", flush=True)
        if "failed" in results[-1]:
            print(f"step {h:g} s: failed: {results[-1]['failed']}", flush=True)
            continue
        b = results[-1]["balances"]
        shafts = "; ".join(f"{shaft} torque {b[shaft]['torqueError']:+.2%}, work {b[shaft]['workError']:+.3%}, "
                           f"drift {b[shaft]['driftMax_deg']:.4f} deg" for shaft, _ in BANKS.values())
        print(f"step {h:g} s: {shafts}"
              + f"; CPU {results[-1]['doStepCpu_s']:.1f} s", flush=True)
    out = pathlib.Path(args.out)
    out.mkdir(parents=True, exist_ok=True)
    (out / "v_engine.json").write_text(json.dumps({"coupling": args.coupling, "torque": args.torque, "rpm": args.rpm, "cycles": args.cycles,
                                                   "runIn": args.run_in,
                                                   "results": results}, indent=1) + "\n")
    (out / "v_engine.md").write_text(report(results, args.rpm, args.cycles, args.run_in, args.coupling, args.torque))
    print(f"written: {out / 'v_engine.md'}, {out / 'v_engine.json'}")
    return 0
