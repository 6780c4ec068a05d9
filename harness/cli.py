"""The command line of the harness: one entry, one subcommand per job.

    python -m harness run            the main job of a scene (harness/run.py: harness/job.py, harness/cvt/job.py)
    python -m harness sweep          speed sweeps and run-ups on Dask, Campbell diagrams (harness/sweep/sweep.py)
    python -m harness study          work-precision charts and stability map (harness/study/study.py)
    python -m harness chaos          divergence rate of twin runs (harness/study/chaos/chaos.py)
    python -m harness fidelity       span model against link model, recommendation (harness/study/fidelity.py)
    python -m harness span-steps     the span model's step convergence (harness/study/span_steps.py)
    python -m harness modes          the drive's modes, link against span, with intervals (harness/study/modes.py)
    python -m harness pulse-response the camshafts' pulse response, link against span (harness/study/pulse_response.py)
    python -m harness tensioner-study the hydraulic tensioner against the spring-damper law (harness/study/tensioner.py)
    python -m harness bench          integrator benchmark (harness/bench/benchmark.py)
    python -m harness bench-realtime the link model's real-time factor through the FMU (harness/bench/realtime.py)
    python -m harness realtime-chart the real-time candidates' work-precision chart (harness/bench/realtime_chart.py)
    python -m harness realtime-floor the floor under the routes to a quarter of real time (harness/bench/realtime_floor.py)
    python -m harness bench-fidelity the span model's cost against the real-time method's (harness/bench/fidelity_cost.py)
    python -m harness bench-loop     the main job's loop compiled against fmpy's calls (harness/bench/master_loop.py)
    python -m harness bench-threads  solver.threads on 1 and 2 threads: wall clock and barriers (harness/bench/threads.py)
    python -m harness bench-lcp      LCP solver against Siconos (harness/bench/benchmark_lcp.py)
    python -m harness bench-sweep    a sweep on 1 and 2 Dask workers and in a plain loop (harness/bench/sweep.py)
    python -m harness tables         the SYNTHESIZED input tables (harness/tables/make_tables.py)
    python -m harness design-drive   the default drive (harness/drive/design.py)
    python -m harness picture        picture of a drive (harness/plots/drive_picture.py)
    python -m harness layout         a drive from centres, teeth and guides (harness/drive/layout.py)
    python -m harness example-drives the example drives and their physics checks (harness/study/example_drives.py)
    python -m harness v-engine       V-engine chains coupled through their shafts (harness/vengine.py)
    python -m harness rig            the hydraulic tensioner's force-displacement loops on the bench (harness/rig/rig.py)
    python -m harness package        the FMUs for download: linux64, win64, sources (harness/package/package.py)
    python -m harness export         the FMU of a drive, its interface generated from it (harness/fmu/export.py)

`python -m harness COMMAND --help` shows a command's options. Each command's module gives its
options (add_arguments(parser)), optionally checks them (check(parser, args), which reports misuse
with parser.error and returns what run takes: the args completed, or a configuration built from
them) and runs (run(args), returning the exit status or None); args.argv holds the command's own
arguments, for the command line that reports record. A module's DESCRIPTION, when it has one, is
its help's description, else its docstring. Only the module of the command given is imported.

A user's mistake (harness/errors.py: UserError, and the misuse a parser reports) ends the command
with one line on stderr, `error: ...`, and exit status 2; --debug, before or after the command,
shows the traceback too.
"""
import argparse
import importlib
import sys
import traceback

from .errors import UserError

PROG = "python -m harness"

# name: (module, one line of help)
COMMANDS = {
    "run": ("harness.run", "the main job: a scene through ChainDrive.fmu with the measured-torque tables"),
    "sweep": ("harness.sweep.sweep", "speed sweeps and run-ups through ChainDrive.fmu on Dask: Campbell diagrams, "
              "order cuts, forces over speed"),
    "study": ("harness.study.study", "work-precision charts on cycle statistics and the stability map"),
    "chaos": ("harness.study.chaos.chaos", "divergence rate of twin runs per damping setting"),
    "fidelity": ("harness.study.fidelity", "the span model against the link model within tolerances: "
                 "the cheapest fidelity that meets them"),
    "span-steps": ("harness.study.span_steps", "the span model's cycle statistics over its step: the evidence "
                   "behind its default step"),
    "drive-steps": ("harness.study.drive_steps", "every test drive at its own default step against half the step, "
                    "closed loop: blow-ups, energy balance, cycle statistics within the scatter"),
    "modes": ("harness.study.modes", "the drive's modes (loaded sprockets in and out of phase, tension guide, "
              "supply), link model against span model, with intervals over twin pairs"),
    "pulse-response": ("harness.study.pulse_response", "the camshafts' response to a torque pulse, link model "
                       "against span model: is there a modal damping to identify"),
    "tensioner-study": ("harness.study.tensioner", "the hydraulic tensioner against the spring-damper law at 1000, "
                        "3000 and 6000 rpm: every cycle statistic with its interval"),
    "bench": ("harness.bench.benchmark", "integrator benchmark of the solver alone"),
    "bench-realtime": ("harness.bench.realtime", "the link model's real-time factor and step-time spread through "
                       "ChainDrive.fmu, its accuracy against a reference"),
    "realtime-chart": ("harness.bench.realtime_chart", "the real-time candidates' cost against their accuracy table, "
                       "from bench-realtime's reports: the work-precision chart"),
    "realtime-floor": ("harness.bench.realtime_floor", "the real-time factor the routes to a quarter of real time "
                       "could at best reach: the links in contact at the longest accurate step, the others free"),
    "bench-fidelity": ("harness.bench.fidelity_cost", "the span model's cost against the link model's real-time "
                       "method through ChainDrive.fmu, in one run"),
    "bench-loop": ("harness.bench.master_loop", "the main job's closed loop compiled against fmpy's calls: each "
                   "one's CPU beyond the FMU's, in one run"),
    "bench-threads": ("harness.bench.threads", "solver.threads: one instance's step on 1 and 2 threads, by turns: "
                      "wall clock, CPU, barriers per step and the pool's own cost"),
    "bench-lcp": ("harness.bench.benchmark_lcp", "our LCP solver against Siconos numerics"),
    "bench-sweep": ("harness.bench.sweep", "the same sweep on 1 and 2 Dask workers and in a plain loop: speed-up and "
                    "Dask's overhead per case"),
    "tables": ("harness.tables.make_tables", "generate the SYNTHESIZED camshaft-torque and crankshaft-speed tables"),
    "design-drive": ("harness.drive.design", "design the default drive (src/drives/default_drive.json)"),
    "picture": ("harness.plots.drive_picture", "picture of a drive at its assembled initial pose"),
    "example-drives": ("harness.study.example_drives", "the example drives: made by the layout aid, their FMU "
                       "interfaces, pictures, main jobs and physics checks (docs/examples/)"),
    "v-engine": ("harness.vengine", "a V6's primary and bank chains, three FMUs coupled through their shafts: "
                 "balances, drift and statistics over the communication step"),
    "layout": ("harness.drive.layout", "a drive from centres, teeth, a chain designation and guides on the spans: "
               "link count, closure, wraps, tensioner margins, picture"),
    "rig": ("harness.rig.rig", "the hydraulic tensioner's force-displacement loops on the bench (chaindrive-rig) at "
            "20-200 Hz"),
    "package": ("harness.package.package", "the FMUs for download (dist/): linux64 (glibc 2.17) and win64 binaries "
                "and sources"),
    "export": ("harness.fmu.export", "the FMU of a drive (dist/<name>.fmu): its interface generated from the drive, "
               "every sprocket, guide and span by name, from the binaries already built"),
}


DEBUG = "--debug"  # the global flag: the traceback of an error too, wherever it stands in the arguments


class Parser(argparse.ArgumentParser):
    """A parser whose misuse is a UserError: one line naming the problem and where the options are
    shown (argparse's own prints the whole usage)."""

    def error(self, message):
        raise UserError(f"{message} ({self.prog} --help shows the options)")


def parser(command=None):
    """The parser with every subcommand; the options of `command` only (its module imported),
    the others with their one line of help. Returns (parser, {name: subparser})."""
    ap = Parser(prog=PROG, description=__doc__.split("\n\n")[0],
                epilog=f"{PROG} COMMAND --help shows the options of a command")
    ap.add_argument(DEBUG, action="store_true", help="on an error, show the traceback too (before or after COMMAND)")
    sub = ap.add_subparsers(dest="command", metavar="COMMAND", required=True, parser_class=Parser)
    subparsers = {}
    for name, (module_name, help_line) in COMMANDS.items():
        if name == command:
            module = importlib.import_module(module_name)
            sp = sub.add_parser(name, help=help_line, description=getattr(module, "DESCRIPTION", module.__doc__),
                                formatter_class=argparse.RawDescriptionHelpFormatter)
            module.add_arguments(sp)
            sp.set_defaults(module=module)
        else:
            sp = sub.add_parser(name, help=help_line, description=help_line)
        subparsers[name] = sp
    return ap, subparsers


def main(argv=None):
    """Runs the command of argv (default: the process's arguments); returns its exit status. A
    user's mistake is reported in one line on stderr and ends it with SystemExit(2)."""
    argv = list(sys.argv[1:] if argv is None else argv)
    debug = DEBUG in argv
    argv = [a for a in argv if a != DEBUG]
    try:
        return run_command(argv)
    except UserError as e:
        if debug:
            traceback.print_exc()
        print(f"error: {e}", file=sys.stderr)
        raise SystemExit(2) from None


def run_command(argv):
    """Parses, checks and runs the command of argv; its exit status."""
    command = argv[0] if argv and argv[0] in COMMANDS else None
    ap, subparsers = parser(command)
    # an option the command does not know is the command's misuse, reported by its own parser
    args, unknown = ap.parse_known_args(argv)
    if unknown:
        subparsers[command].error(f"unrecognized arguments: {' '.join(unknown)}")
    args.argv = argv[1:]
    module = args.module
    check = getattr(module, "check", None)
    checked = args if check is None else check(subparsers[command], args)
    return module.run(checked) or 0
