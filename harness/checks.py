"""A run's own checks and what its fidelity was checked for: the lines a run prints as `warning:`
(a check that missed its limit; with --strict the run's exit status is 1) and `note:` (a fidelity
used outside the accuracy it was checked for), also written to the run's JSON.

The timing drive's check is its energy balance over the counted cycles: the input work equals the
dissipated energy plus the change of kinetic and elastic energy. The explicit schemes' balance
error grows with the step and the speed; with the spring-damper tensioner plain Verlet at 2.5 us
measured 0.5 % at 1000 rpm, 1.3 % at 3000 rpm and 2.7 % at 6000 rpm, the real-time method 2.4 % at
3000 rpm, all with cycle statistics within the scatter of their finer references
(docs/study/report.md). With the hydraulic tensioner the real-time method, the link fidelity's
default, measured 1.6 % at 3000 rpm and 4.7 % at 6000 rpm, its statistics within the scatter of
the finer ensembles (docs/study/hydraulic_steps.md): near the limit at 6000 rpm, so a faster
engine warns. (The CVT's checks: harness/cvt/job.py.)
"""
import json
import math

from . import paths

ENERGY_BALANCE_LIMIT = 0.05  # |error| of the energy balance over the counted cycles, of the dissipated energy
# the committed fidelity ladder of the default drive: one comparison per speed (python -m harness fidelity)
FIDELITY_CHECKS = paths.ROOT / "docs" / "study" / "fidelity_hydraulic"
EXIT_STRICT = 1  # the exit status of a run with --strict whose checks missed a limit


def energy_balance_error(record, first, last):
    """(input work - dissipated energy - change of kinetic and elastic energy) / dissipated
    energy between samples first and last of a record of ChainDrive.fmu's outputs."""
    def change(name):
        return record[name][last] - record[name][first]
    dissipated = change("energy.dissipated")
    stored = change("energy.kinetic") + change("energy.elastic")
    return (change("energy.input") - dissipated - stored) / dissipated if dissipated > 0.0 else math.nan


def energy_warnings(error, step=None):
    """The warning lines of an energy-balance error (none when within the limit); `step`: the run's
    fixed solver step [s], whose half it offers (what a drive's dynamic roller forces may need,
    docs/defaults.md#a-step-that-fits-the-drive)."""
    if abs(error) <= ENERGY_BALANCE_LIMIT:
        return []
    shorter = f", e.g. --solver-step {step / 2:.6g}" if step else ""
    return [f"energy balance {100 * error:+.2f} % of the dissipated energy over the counted cycles misses its limit "
            f"{100 * ENERGY_BALANCE_LIMIT:g} %: the results are not accurate (a smaller --solver-step{shorter}, or a "
            f"tighter --rtol)"]


def fidelity_notes(fidelity, drive):
    """The note on a fidelity other than the link model: how far it was from the link model where
    it was checked (the committed fidelity ladder), and that it was checked on the default drive only."""
    if fidelity == "link":
        return []
    ladder = sorted((json.loads(f.read_text()) for f in FIDELITY_CHECKS.glob("fidelity-*.json")),
                    key=lambda speed: speed["rpm"])
    if not ladder:
        return [f"{fidelity} fidelity: not checked against the link model; its accuracy is unknown"]
    rows = [row for speed in ladder for row in speed["rows"]]
    missed = [row for row in rows if not row["meets"]]
    worst = sorted(missed, key=lambda row: -abs(row["difference"]))[:2]
    speeds = ", ".join(f"{speed['rpm']:g}" for speed in ladder)
    examples = "; ".join(f"{row['key']} {row['difference']:+.0f} {row['differenceUnit']}" for row in worst)
    where = "" if drive is None else " (on the default drive only; this drive is unchecked)"
    return [f"{fidelity} fidelity: outside the accuracy it was checked for: against the link model at {speeds} rpm"
            f"{where} it missed {len(missed)} of {len(rows)} tolerances (docs/study/fidelity_hydraulic.md), the largest: "
            f"{examples}; use --fidelity link where these quantities matter"]


def print_lines(warnings, notes):
    """Prints the warnings and notes of a run, one line each."""
    for line in warnings:
        print(f"warning: {line}")
    for line in notes:
        print(f"note: {line}")
