"""The source FMU: what goes into an FMU's sources/ folder, and the <SourceFiles> list of its
model description.

An importer (fmpy.build.build_platform_binary, a real-time target's toolchain) compiles every
listed .cpp with sources/ as the only include directory, so sources/ holds:
- the solver's stages (src/ as it is, without the command-line tools);
- the FMU's protocol glue and this FMU's model adapter, side by side in sources/fmu/ (every
  header has a name of its own; the adapter's <adapter>_fmu.cpp includes its <adapter>_adapter.h
  and the glue's fmi2_functions.h from that folder);
- the embedded default descriptions, generated as the CMake build does (cmake/EmbedText.cmake),
  and the hash of the solver's sources (cmake/SourceHash.cmake: the span calibration cache's key);
- the header-only libraries (Eigen/, nlohmann/) and the FMI 2 headers, so it is self-contained.
SUNDIALS is not in it: the files that call SUNDIALS are left out and their *_without_sundials.cpp
stand-ins refuse the adaptive, BDF and event-driven methods by name; the fixed-step methods (the
real-time method among them) and time stepping are complete.
"""
import pathlib
import re
import shutil
import subprocess

from .. import paths
from .binaries import fmi2_include_dir

SUNDIALS_INCLUDE = re.compile(r'#include\s*[<"]((sundials|arkode|cvode|nvector|sunlinsol|sunmatrix|sunnonlinsol)/'
                              r'|integrators/sundials_common\.h)')
EMBEDDED = {"default_drive.json": "kDefaultDriveJson", "default_cvt.json": "kDefaultCvtJson"}
FMI2_HEADERS = ("fmi2Functions.h", "fmi2FunctionTypes.h", "fmi2TypesPlatform.h")
BUILDING = """\
Building this FMU from its sources

Every .cpp file listed in modelDescription.xml (<SourceFiles>) is compiled as C++17 with this
folder as the only include directory, into a shared library named after the modelIdentifier,
for example (fmpy does this with fmpy.build.build_platform_binary):

  g++ -std=c++17 -O2 -ffp-contract=off -fPIC -shared -I. $(list of the .cpp files) -o {name}.so

Compilers: GCC 8 or newer, Clang 10 or newer (GCC's and Clang's vector extensions); x86-64 or
another 64-bit architecture. -ffp-contract=off keeps the results bit-identical to the shipped
binaries: without it a compiler may fuse a*b+c into one instruction where the target has one
(GCC does so by default for -march with FMA and on AArch64). Do not use -ffast-math.

This build has no SUNDIALS: the methods that need it (solver.method cvode-bdf-klu,
cvode-bdf-band, arkode-erk, arkode-erk-fixed, contact.method event-driven) are refused with a
message; the fixed-step methods (fixed-verlet, fixed-verlet-implicit-joint-damping,
fixed-verlet-implicit-damping, fixed-newmark) and time stepping are complete.
"""


def solver_files():
    """The solver's files of a source build, relative to src/: every header and source but the
    command-line tools and the files that call SUNDIALS (their stand-ins instead)."""
    src = paths.ROOT / "src"
    files = []
    for path in sorted(src.rglob("*")):
        rel = path.relative_to(src)
        if path.suffix not in (".h", ".cpp") or rel.parts[0] == "cli":
            continue
        if not SUNDIALS_INCLUDE.search(path.read_text()):
            files.append(rel)
    return files


def fmu_files(adapter):
    """The protocol glue (fmu/) and the adapter's files (fmu/<adapter>/), each with its place in
    sources/fmu/."""
    fmu = paths.ROOT / "fmu"
    glue = sorted(p for p in fmu.iterdir() if p.suffix in (".h", ".cpp"))
    own = sorted(p for p in (fmu / adapter).iterdir() if p.suffix in (".h", ".cpp"))
    return {p: pathlib.Path("fmu") / p.name for p in glue + own}


def write(dest, adapter):
    """Writes the sources/ folder of the FMU whose adapter is fmu/<adapter> into dest; returns
    the .cpp files to list in <SourceFiles>, relative to dest."""
    src = paths.ROOT / "src"
    for rel in solver_files():
        copy(src / rel, dest / rel)
    for path, rel in fmu_files(adapter).items():
        copy(path, dest / rel)
    for json_name, symbol in EMBEDDED.items():
        embed(src / "drives" / json_name, dest / f"{pathlib.Path(json_name).stem}_embedded.cpp", symbol)
    source_hash(dest / "source_hash.cpp")
    shutil.copytree("/usr/include/eigen3/Eigen", dest / "Eigen", dirs_exist_ok=True)
    shutil.copytree("/usr/include/nlohmann", dest / "nlohmann", dirs_exist_ok=True)
    for header in FMI2_HEADERS:
        copy(pathlib.Path(fmi2_include_dir()) / header, dest / header)
    (dest / "BUILDING.txt").write_text(BUILDING)
    return sorted(p.relative_to(dest).as_posix() for p in dest.rglob("*.cpp"))


def copy(path, to):
    to.parent.mkdir(parents=True, exist_ok=True)
    shutil.copyfile(path, to)


def source_hash(out):
    """kSourceHash over the files the CMake build hashes (its core sources, then every header, each
    list in CMake's glob order), by the CMake build's own script: a source build shares the
    shipped binaries' calibration cache."""
    src = paths.ROOT / "src"
    sources = sorted((str(p) for p in src.rglob("*.cpp")
                      if "/src/cli/" not in p.as_posix() and not p.name.endswith("_without_sundials.cpp")))
    headers = sorted(str(p) for p in src.rglob("*.h"))
    listing = out.parent / "source_hash_files.txt"
    listing.write_text(";".join(sources + headers))
    subprocess.run(["cmake", f"-DLIST={listing}", f"-DOUT={out}", "-P", str(paths.ROOT / "cmake" / "SourceHash.cmake")],
                   check=True, capture_output=True)
    listing.unlink()
    pathlib.Path(f"{out}.tmp").unlink()


def embed(json_file, out, symbol):
    """The description as a C++ string, generated by the CMake build's own script."""
    subprocess.run(["cmake", f"-DIN={json_file}", f"-DOUT={out}", f"-DNAME={symbol}", "-P",
                    str(paths.ROOT / "cmake" / "EmbedText.cmake")], check=True, capture_output=True)
