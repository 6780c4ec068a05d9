"""The main job of a scene: `python -m harness run [--scene timing|cvt] [options]`.

  timing (default)  the roller-chain timing drive through ChainDrive.fmu with the measured-torque
                    tables (harness/job.py)
  cvt               the chain CVT, paper example 4.1, through the solver alone (harness/cvt/job.py)

The options --rpm, --method, --solver-step, --rtol, --out and --strict are both scenes'; their defaults are
the scene's own. The other options are one scene's; the timing drive's are refused by the CVT
scene when set.
"""
from . import defaults, job, paths, replicas
from .cvt import job as cvt_job

JOBS = {"timing": job, "cvt": cvt_job}  # --scene: its job's module
# the help's description (harness/cli.py): this module's docstring, then each scene's job's
DESCRIPTION = "\n".join([__doc__, job.__doc__, cvt_job.__doc__])


def add_arguments(ap):
    """The scene, the options both scenes take (their defaults None: each scene resolves its own)
    and each scene's own options, in a group per scene."""
    ap.add_argument("--scene", choices=tuple(JOBS), default="timing",
                    help="timing: the roller-chain timing drive through ChainDrive.fmu (default); cvt: the chain CVT "
                    "(paper example 4.1, harness/cvt/job.py)")
    ap.add_argument("--rpm", type=float, help=f"mean engine speed [rpm], 1000-6000 (tables; default "
                    f"{job.DEFAULT_RPM:g}); cvt: the driving-pulley speed (default {cvt_job.DEFAULT_RPM:g})")
    ap.add_argument("--method", help="FMU parameter solver.method (default: the scene's and fidelity's, as "
                    "--solver-step)")
    ap.add_argument("--solver-step", type=float, help="FMU parameter solver.step [s] (default per scene and fidelity, "
                    f"the same in every entry point: timing {defaults.described('timing')}; cvt "
                    f"{defaults.described('cvt')}; a drive whose joints have clearance or whose contacts are rigid: "
                    "the table's row for it; a method named without a step: its row's step, else that row's)")
    ap.add_argument("--rtol", type=float, help="FMU parameter solver.tolerance (default: the scene's and fidelity's)")
    ap.add_argument("--out", default=str(paths.RESULTS), help="output directory")
    ap.add_argument("--strict", action="store_true", help="exit status 1 when one of the run's checks (energy and "
                    "torque balances) misses its limit (always: a warning line and the run's JSON)")
    job.add_arguments(ap.add_argument_group("the timing drive (--scene timing)"))
    cvt_job.add_arguments(ap.add_argument_group("the chain CVT (--scene cvt)"))


def check(ap, args):
    """The configuration of the scene's job, built once from the options; misuse reported by ap.error."""
    return JOBS[args.scene].config_of(ap, args)


def run(config):
    """Runs the job the configuration is for."""
    if isinstance(config, cvt_job.CVTConfig):
        return cvt_job.run(config)
    return replicas.run(config) if config.replicas > 1 else job.run(config)
