"""Every drive its own FMU: python -m harness export --drive FILE [--out DIR] (./run.sh export)
writes DIR/<model identifier>.fmu, whose interface is generated from the drive (src/interface/,
docs/fmu.md): every sprocket's load input and motion outputs, every guide's and the tensioner's
outputs, a force per span, by the elements' own names.

The model description and the resources (the drive and its interface table) come from the build's
chaindrive-info --fmu-files; the binaries are those already built, no compiler runs: the packaged
ones of dist/ChainDrive.fmu (linux64 for glibc 2.17, win64 and the sources, ./run.sh package) when
they are of the sources the native build was made from, else the native build's linux64 binary.
One binary serves every drive: it reads the interface table at instantiation and checks it against
the drive beside it. The default drive's export is ChainDrive.fmu itself (its model identifier,
GUID and value references).

    python -m harness export --drive tests/drives/idler.json            -> dist/idler_drive.fmu
    python -m harness export --drive FILE --out DIR [--span-calibration]
"""
import dataclasses
import json
import os
import pathlib
import shutil
import subprocess
import tempfile
import time
import zipfile

from .. import paths
from ..errors import UserError, tool_failure
from ..package import archive, sources

DIST = paths.ROOT / "dist"
PACKAGED = DIST / "ChainDrive.fmu"           # ./run.sh package's, with every platform's binary
NATIVE_BINARY = "ChainDrive.so"             # the native build's (build/)
SHIPPED = ("ChainDrive", "CVTChain")        # the FMUs ./run.sh package writes into dist/


@dataclasses.dataclass
class Export:
    """An exported FMU: its file, interface (resources/interface.json) and where its binaries came from."""
    path: pathlib.Path
    interface: dict
    binaries: dict          # platform: where its binary came from
    sources: bool           # the FMU carries its sources
    seconds: float
    span_calibration: str = ""  # where the calibration in resources/ came from and its cost ("": none)

    @property
    def model_identifier(self):
        return self.interface["modelIdentifier"]

    def variables(self, causality):
        return [v["name"] for v in self.interface["variables"] if v["causality"] == causality]


def fmu_files(drive, stage):
    """chaindrive-info --fmu-files: stage/modelDescription.xml and stage/resources/ of the drive (a
    file; None: the default drive); returns the interface table. A drive without an FMU interface
    is a UserError naming the field."""
    cmd = [paths.executable("chaindrive-info"), "--fmu-files", str(stage)]
    if drive is not None:
        cmd += ["--drive", str(drive)]
    p = subprocess.run(cmd, capture_output=True, text=True)
    if p.returncode != 0:
        raise tool_failure("chaindrive-info", p.stderr)
    return json.loads((stage / "resources" / "interface.json").read_text())


def stale_source(packaged):
    """The first solver or adapter source of the repository whose copy in the packaged FMU's
    sources/ differs or is missing ("" when the package is of these sources)."""
    expected = {pathlib.PurePosixPath("sources", rel.as_posix()): paths.ROOT / "src" / rel
                for rel in sources.solver_files()}
    expected.update({pathlib.PurePosixPath("sources", rel.as_posix()): path
                     for path, rel in sources.fmu_files("chaindrive").items()})
    with zipfile.ZipFile(packaged) as z:
        names = set(z.namelist())
        for name, path in sorted(expected.items()):
            if str(name) not in names or z.read(str(name)) != path.read_bytes():
                return str(path.relative_to(paths.ROOT))
    return ""


def packaged_binaries():
    """The packaged FMU (dist/ChainDrive.fmu) when it is of the repository's sources, else None and
    the reason it is not used."""
    if not PACKAGED.exists():
        return None, f"{PACKAGED} not found: ./run.sh package makes the win64 binary and the sources"
    stale = stale_source(PACKAGED)
    if stale:
        return None, f"{PACKAGED} is of other sources ({stale} differs; ./run.sh package makes it again)"
    return PACKAGED, ""


def stage_binaries(stage, model_identifier, native=False):
    """The binaries (and sources) into stage: the packaged FMU's where they fit (unless native),
    else the native linux64 binary. Returns ({platform: origin}, sources)."""
    packaged, why_not = (None, "asked for") if native else packaged_binaries()
    if packaged is None:
        native = paths.BUILD / NATIVE_BINARY
        if not native.exists():
            raise UserError(f"{native} not found; build first (./run.sh builds it)")
        target = stage / "binaries" / "linux64" / f"{model_identifier}.so"
        target.parent.mkdir(parents=True)
        shutil.copyfile(native, target)
        return {"linux64": f"{native} (native build; {why_not})"}, False
    origins = {}
    with zipfile.ZipFile(packaged) as z:
        for name in z.namelist():
            part = pathlib.PurePosixPath(name)
            if part.parts[0] == "binaries":
                suffix = part.suffix
                target = stage / "binaries" / part.parts[1] / f"{model_identifier}{suffix}"
                origins[part.parts[1]] = f"{packaged}:{name}"
            elif part.parts[0] in ("sources", "documentation"):
                target = stage / name
            else:
                continue
            target.parent.mkdir(parents=True, exist_ok=True)
            target.write_bytes(z.read(name))
    return origins, (stage / "sources").is_dir()


def listed_sources(stage):
    """The .cpp files of stage/sources, relative to it (the model description's <SourceFiles>)."""
    return sorted(p.relative_to(stage / "sources").as_posix() for p in (stage / "sources").rglob("*.cpp"))


def destination(out, model_identifier, default_drive):
    """out/<id>.fmu; never over a file ./run.sh package wrote unless the export is that FMU."""
    path = pathlib.Path(out) / f"{model_identifier}.fmu"
    if model_identifier in SHIPPED and not (default_drive and model_identifier == "ChainDrive"):
        raise UserError(f"{path}: the export of this drive would replace the shipped {model_identifier}.fmu; give the "
                        f"drive another name")
    return path


def export(drive=None, out=DIST, span_calibration=False, native=False):
    """The drive's FMU (drive: a file; None: the default drive) written into out; returns an Export.
    native: the native build's binary even where the packaged ones fit (the harness's own runs)."""
    t0 = time.monotonic()
    with tempfile.TemporaryDirectory(prefix="chaindrive-export-") as tmp:
        stage = pathlib.Path(tmp)
        interface = fmu_files(drive, stage)
        model_identifier = interface["modelIdentifier"]
        path = destination(out, model_identifier, interface["guid"] == DEFAULT_GUID)
        origins, with_sources = stage_binaries(stage, model_identifier, native)
        if with_sources:
            text = archive.with_source_files(stage / "modelDescription.xml", listed_sources(stage))
            (stage / "modelDescription.xml").write_text(text)
        calibration = calibrate_into(drive, stage / "resources") if span_calibration else ""
        archive.write_zip(stage, path)
    return Export(path, interface, origins, with_sources, time.monotonic() - t0, calibration)


DEFAULT_GUID = "{b6f8c2a4-7d1e-4f3a-9e2b-5c8d1a0f4e21}"  # src/interface/drive_interface.h, kDefaultDriveGuid


def interface_of(drive):
    """The drive's FMU interface (chaindrive-info --interface): a dict with modelIdentifier, guid and
    variables. A drive without one is a UserError naming the field."""
    p = subprocess.run([paths.executable("chaindrive-info"), "--interface", "--drive", str(drive)],
                       capture_output=True, text=True)
    if p.returncode != 0:
        raise tool_failure("chaindrive-info", p.stderr)
    return json.loads(p.stdout)


def fmu_for(drive=None):
    """The FMU that runs a drive in the harness: the build's ChainDrive.fmu for the default drive
    (None, or a file of the same content), else the drive's own export with the native binary, made
    once per drive content and binary into the build (build/exports/)."""
    from . import fmu
    if drive is None:
        return fmu.fmu_path()
    interface = interface_of(drive)
    if interface["guid"] == DEFAULT_GUID:
        return fmu.fmu_path()
    binary = paths.BUILD / NATIVE_BINARY
    if not binary.exists():
        raise UserError(f"{binary} not found; build first (./run.sh builds it)")
    key = f"{interface['guid'].strip('{}')}-{binary.stat().st_mtime_ns}"
    path = paths.BUILD / "exports" / key / f"{interface['modelIdentifier']}.fmu"
    if not path.exists():
        # (made beside and renamed: runs in parallel processes may export the same drive at once)
        with tempfile.TemporaryDirectory(dir=paths.BUILD, prefix="export-") as tmp:
            made = export(drive, pathlib.Path(tmp), native=True).path
            path.parent.mkdir(parents=True, exist_ok=True)
            os.replace(made, path)
    return path


def calibrate_into(drive, resources):
    """The span model's calibration of the drive (a file; None: the default drive) into
    resources/span_calibration.json (chaindrive-info --span-calibration: from the calibration cache,
    else computed now, up to a minute, and kept in the cache too). An instance in the span fidelity
    reads it instead of calibrating, as long as its key is the instance's (the drive with the
    parameters that override it, and the solver's sources); otherwise it calibrates as without it and
    logs a warning. Returns chaindrive-info's lines on the poses and the cost. A drive whose span
    model cannot be calibrated is a ToolFailure with chaindrive-info's reason."""
    cmd = [paths.executable("chaindrive-info"), "--quiet", "--span-calibration",
           str(pathlib.Path(resources) / "span_calibration.json")]
    if drive is not None:
        cmd += ["--drive", str(drive)]
    p = subprocess.run(cmd, capture_output=True, text=True)
    if p.returncode != 0:
        raise tool_failure("chaindrive-info", p.stderr)
    wanted = ("calibration: engagement laws ", "calibration: this call ")
    return "; ".join(line.removeprefix("calibration: ") for line in p.stdout.splitlines() if line.startswith(wanted))


def add_arguments(ap):
    ap.add_argument("--drive", help="the drive description (default: the default drive, whose export is ChainDrive.fmu)")
    ap.add_argument("--out", type=pathlib.Path, default=DIST, help="folder of the FMU (default dist/)")
    ap.add_argument("--span-calibration", action="store_true",
                    help="carry the span model's calibration in resources/, so that the FMU's span fidelity does not "
                         "compute it at instantiation (from the calibration cache, else computed now: seconds to "
                         "under a minute of CPU)")


def check(ap, args):
    if args.drive is not None and not pathlib.Path(args.drive).is_file():
        ap.error(f"--drive {args.drive}: no such file")
    return args


def run(args):
    from fmpy.validation import validate_fmu
    e = export(args.drive, args.out, args.span_calibration)
    problems = validate_fmu(str(e.path))
    print(f"{e.path}: {e.model_identifier}, GUID {e.interface['guid']}, {len(e.interface['variables'])} variables "
          f"({e.seconds:.1f} s)")
    print(f"  inputs: {', '.join(e.variables('input'))}")
    print(f"  outputs: {', '.join(e.variables('output'))}")
    for platform, origin in sorted(e.binaries.items()):
        print(f"  binaries/{platform}: from {origin}")
    print(f"  sources: {'yes' if e.sources else 'no (only the packaged FMU carries them: ./run.sh package)'}")
    print(f"  resources/span_calibration.json: {e.span_calibration or 'no (--span-calibration adds it)'}")
    for p in problems:
        print(f"  PROBLEM fmpy validate: {p}")
    return 1 if problems else 0
