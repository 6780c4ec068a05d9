"""The FMUs a user downloads: ./run.sh package (python -m harness package) writes
dist/ChainDrive.fmu and dist/CVTChain.fmu, each with

  binaries/linux64/<id>.so   any Linux with glibc 2.17 or newer (x86-64), nothing else needed
  binaries/win64/<id>.dll    64-bit Windows 10 or newer (the universal C runtime), nothing else needed
  sources/                   the C++ sources (FMI 2.0 source FMU, listed in <SourceFiles>), for
                             importers and real-time targets that compile the FMU themselves

both binaries cross-built with zig (harness/package/toolchain.py), SUNDIALS and KLU in them
(deps.py), every transcendental function the project's own, so that every platform and the
source build compute the same bits. Prints what each binary asks of the machine that loads it
(symbol versions, libraries, exports) and fails if that breaks a promise (inspect.py); checks
each FMU with fmpy's validator. The native build (./run.sh main and test) is not touched.
"""
import os
import pathlib
import shutil
import time
from concurrent.futures import ThreadPoolExecutor

from .. import paths
from ..fmu import export
from . import archive, binaries, inspect, sources
from .toolchain import TARGETS

# (fmpy's validator and compare.py, which need numpy, are imported where they are used:
# ./run.sh test starts --binaries-only with fmpy and zig installed, before the rest of pip's)

# id: (adapter folder fmu/<adapter>, model description, default description in resources/);
# ChainDrive's model description and resources are generated from the default drive, as every
# drive's export is (harness/fmu/export.py)
FMUS = {"ChainDrive": ("chaindrive", None, None),
        "CVTChain": ("cvt", "modelDescription/CVTChain.xml", "src/drives/default_cvt.json")}


def add_arguments(ap):
    ap.add_argument("--out", type=pathlib.Path, default=paths.ROOT / "dist", help="folder of the FMUs (default dist/)")
    ap.add_argument("--build", type=pathlib.Path, default=paths.BUILD / "package",
                    help="folder of the cross builds (default: package/ in the build directory)")
    ap.add_argument("--platforms", nargs="+", choices=sorted(TARGETS), default=sorted(TARGETS),
                    help="the platforms' binaries to build (default: all)")
    ap.add_argument("--jobs", type=int, default=os.cpu_count() or 1, help="parallel compile jobs (per platform)")
    ap.add_argument("--binaries-only", action="store_true",
                    help="build the platforms' binaries into --build and stop (./run.sh test builds them beside "
                    "its native build, then packages)")
    ap.add_argument("--compare", action="store_true",
                    help="then run each FMU with every binary (win64 under wine) and a binary built from its "
                    "sources, and compare the outputs of every step bit for bit")


def run(args):
    start = time.monotonic()
    args.build.mkdir(parents=True, exist_ok=True)
    built = build_platforms(args.platforms, args.build, args.jobs)  # {platform: {FMU id: binary}}
    if args.binaries_only:
        print(f"\nbinaries built in {time.monotonic() - start:.0f} s")
        return 0
    failures = 0
    for fmu_id in FMUS:
        fmu_file = assemble(fmu_id, built, args.build / "stage" / fmu_id, args.out)
        failures += report(fmu_id, fmu_file, built)
    print(f"\npackaged in {time.monotonic() - start:.0f} s" + (f"; {failures} problems" if failures else ""))
    if args.compare:
        failures += compare_platforms(args.out, args.build / "compare")
    return 1 if failures else 0


def build_platforms(platforms, build_root, jobs):
    """Builds every platform's binaries at the same time; returns {platform: {FMU id: binary}}.
    Most of a first build is zig compiling the platform's C runtime and libc++, one source at a
    time: two platforms side by side keep two cores busy. Each platform's lines are printed whole."""
    def build_one(platform):
        t0 = time.monotonic()
        lines = [f"== {platform}"]
        binaries_of = binaries.build(TARGETS[platform], build_root, jobs, log=lines.append)
        lines.append(f"   built in {time.monotonic() - t0:.0f} s")
        return binaries_of, lines

    built = {}
    with ThreadPoolExecutor(max_workers=len(platforms)) as pool:
        for platform, (binaries_of, lines) in zip(platforms, pool.map(build_one, platforms)):
            print("\n".join(lines))
            built[platform] = binaries_of
    return built


def assemble(fmu_id, built, stage, out):
    """Stages the FMU's parts and writes out/<id>.fmu; returns its path."""
    adapter, model_description, resource = FMUS[fmu_id]
    if stage.exists():
        shutil.rmtree(stage)
    source_files = sources.write(stage / "sources", adapter)
    if model_description is None:
        export.fmu_files(None, stage)
    else:
        shutil.copyfile(paths.ROOT / model_description, stage / "modelDescription.xml")
        (stage / "resources").mkdir()
        shutil.copyfile(paths.ROOT / resource, stage / "resources" / pathlib.Path(resource).name)
    (stage / "modelDescription.xml").write_text(archive.with_source_files(stage / "modelDescription.xml", source_files))
    for platform, fmu_binaries in built.items():
        binary = fmu_binaries[fmu_id]
        target = stage / "binaries" / platform / f"{fmu_id}{TARGETS[platform].suffix}"
        target.parent.mkdir(parents=True)
        shutil.copyfile(binary, target)
    archive.stage_licenses(stage)
    fmu_file = out / f"{fmu_id}.fmu"
    archive.write_zip(stage, fmu_file)
    return fmu_file


def report(fmu_id, fmu_file, built):
    """Prints what the FMU's binaries ask of a machine and the problems found; returns their count."""
    print(f"\n{fmu_file} ({fmu_file.stat().st_size / 1e6:.1f} MB)")
    problems = []
    for platform, fmu_binaries in built.items():
        binary = fmu_binaries[fmu_id]
        if platform == "linux64":
            r = inspect.elf(binary)
            glibc = ".".join(str(x) for x in inspect.glibc_version(r["versions"]))
            print(f"   linux64: {binary.stat().st_size / 1e6:.1f} MB, newest symbol version GLIBC_{glibc}, "
                  f"needs {', '.join(r['needed'])}; exports {len(r['exports'])} functions")
            found = inspect.problems_elf(r)
        else:
            r = inspect.pe(binary)
            print(f"   win64: {binary.stat().st_size / 1e6:.1f} MB, imports {', '.join(sorted(r['imports']))}; "
                  f"exports {len(r['exports'])} functions")
            found = inspect.problems_pe(r)
        found += inspect.link_input_problems(binary.parent, [fmu_id])
        problems += [f"{platform}: {p}" for p in found]
    from fmpy.validation import validate_fmu
    problems += [f"fmpy validate: {p}" for p in validate_fmu(str(fmu_file))]
    for p in problems:
        print(f"   PROBLEM {p}")
    if not problems:
        print("   no problems found (symbol versions, libraries, exports, imports, fmpy validate)")
    return len(problems)


# (FMU, method or None for the default, simulated seconds): what the comparison runs
COMPARISONS = [("ChainDrive", None, 0.030), ("ChainDrive", "fixed-verlet", 0.030),
               ("ChainDrive", "arkode-erk", 0.005), ("ChainDrive", "cvode-bdf-klu", 0.003), ("CVTChain", None, 0.020)]


def compare_platforms(dist, work):
    """Prints, per FMU and method, whether the win64 binary (under wine) and the source build give
    the linux64 binary's bits at every step; returns the number of runs that do not."""
    print("\n== the same bits on every platform (every output after every 0.1 ms step)")
    from . import compare
    with compare.wine(work / "wine"):
        master = compare.build_master(work)
        unpacked = {fmu_id: compare.unpack(dist / f"{fmu_id}.fmu", work / fmu_id) for fmu_id in FMUS}
        t0 = time.monotonic()
        built = compare.sources_built(unpacked, work)
        print(f"   {', '.join(FMUS)}: built from their sources by fmpy in {time.monotonic() - t0:.0f} s")
        return sum(compare_runs(fmu_id, method, duration, unpacked[fmu_id], built[fmu_id], master, work)
                   for fmu_id, method, duration in COMPARISONS)


def compare_runs(fmu_id, method, duration, unpacked, built, master, work):
    """One comparison's two lines; returns how many of them fail."""
    from . import compare
    run = (lambda d: compare.run_cvt(d, duration)) if fmu_id == "CVTChain" else \
          (lambda d: compare.run_timing(d, duration, method))
    linux = run(unpacked)
    label = f"   {fmu_id}, {method or 'default method'}, {duration * 1e3:g} ms:"
    return (show(f"{label} win64 (wine)", lambda: compare.replay_on_windows(master, unpacked, linux, work), linux)
            + show(f"{label} source build", lambda: run(built), linux))


def show(label, run_other, linux):
    """Prints how the other run compares with linux64's; returns 1 if it differs or fails (a
    source build's refusal of a SUNDIALS method is what it must do, not a failure)."""
    from . import compare
    try:
        c = compare.compare(linux, run_other())
    except Exception as e:
        refused = "needs SUNDIALS" in str(e)
        print(f"{label} {'refused, as it must be' if refused else 'FAILED'}: {str(e).splitlines()[-1][:160]}")
        return 0 if refused else 1
    print(f"{label} " + (f"bit-identical to linux64 ({c.variables} outputs x {c.steps} steps)" if c.identical else
                         f"{len(c.differing)} of {c.variables} outputs differ from linux64; first at {c.first}"))
    return 0 if c.identical else 1
