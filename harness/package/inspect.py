"""What a shipped binary asks of the machine that loads it, read with binutils' objdump (which
reads ELF and PE alike): an ELF shared library's symbol versions, needed libraries, exports and
imports; a DLL's imported DLLs and functions and its exports. The package command prints these
and tests/python/package checks them against what docs/fmu.md promises."""
import functools
import os
import pathlib
import re
import subprocess

from .. import paths
from .binaries import fmi2_include_dir

# the libraries an FMU for old Linux systems may need: the C library, its parts and the loader
LINUX_ALLOWED_NEEDED = {"libc.so.6", "libm.so.6", "libpthread.so.0", "libdl.so.2", "ld-linux-x86-64.so.2"}
GLIBC_FLOOR = (2, 17)  # manylinux2014
# Windows system DLLs only: the kernel and the universal C runtime's API sets
WINDOWS_ALLOWED_DLL = re.compile(r"^(kernel32\.dll|api-ms-win-crt-[a-z0-9-]+\.dll)$", re.IGNORECASE)


def objdump(*args):
    return subprocess.run(["objdump", *args], capture_output=True, text=True, check=True).stdout


@functools.lru_cache(maxsize=None)
def fmi2_functions():
    """Every function an FMI 2.0 binary exports (fmi2Functions.h's FMI2_Export declarations)."""
    header = open(os.path.join(fmi2_include_dir(), "fmi2Functions.h")).read()
    return frozenset(re.findall(r"FMI2_Export\s+\w+TYPE\s+(fmi2\w+)\s*;", header))


@functools.lru_cache(maxsize=None)
def crt_transcendentals():
    """The C runtime's transcendental functions no shipped binary may import (the list the link
    guard of cmake/Determinism.cmake wraps), with their float and long double variants."""
    text = (paths.ROOT / "cmake" / "Determinism.cmake").read_text()
    names = re.search(r"set\(CHAINDRIVE_CRT_TRANSCENDENTALS\s+([^)]*)\)", text).group(1).split()
    return frozenset(n + v for n in names for v in ("", "f", "l"))


def elf(path):
    """An ELF shared library's dynamic symbols: {'versions': {'GLIBC_2.14', ...}, 'needed': [...],
    'exports': {...}, 'imports': {...}}."""
    versions, exports, imports = set(), set(), set()
    for line in objdump("-T", str(path)).splitlines():
        # "<value> <flags> <section>\t<size> [(<version>)|<version>] <name>"
        if "\t" not in line:
            continue
        left, right = line.split("\t", 1)
        section, fields = left.split()[-1], right.split()
        name = fields[-1]
        version = fields[-2].strip("()") if len(fields) >= 3 else ""
        if version and version != "Base":
            versions.add(version)
        (imports if section == "*UND*" else exports).add(name)
    needed = re.findall(r"^\s*NEEDED\s+(\S+)", objdump("-p", str(path)), re.MULTILINE)
    return {"versions": versions, "needed": needed, "exports": exports, "imports": imports}


def glibc_version(versions):
    """The newest GLIBC_x.y among the versions, as a tuple (0,) if none."""
    found = [tuple(int(x) for x in v.split("_", 1)[1].split(".")) for v in versions if v.startswith("GLIBC_")]
    return max(found, default=(0,))


def pe(path):
    """A DLL's import and export tables: {'imports': {dll: {functions}}, 'exports': {...}}."""
    imports, exports, dll, in_exports = {}, set(), None, False
    for line in objdump("-p", str(path)).splitlines():
        if m := re.match(r"^\s*DLL Name:\s*(\S+)", line):
            dll = m.group(1)
            imports[dll] = set()
        elif not line.strip():
            dll = None
        elif dll and (m := re.match(r"^\s+[0-9a-f]+\s+\d+\s+(\S+)", line)):
            imports[dll].add(m.group(1))
        elif line.startswith("[Ordinal/Name Pointer] Table"):
            in_exports = True
        elif in_exports and (m := re.match(r"^\s+\[\s*\d+\]\s+(\S+)$", line)):
            exports.add(m.group(1))
    return {"imports": imports, "exports": exports}


def problems_elf(report):
    """What keeps a linux64 binary from loading on an old system or from being sealed, as lines."""
    out = []
    if glibc_version(report["versions"]) > GLIBC_FLOOR:
        newer = sorted(v for v in report["versions"] if v.startswith("GLIBC_")
                       and glibc_version({v}) > GLIBC_FLOOR)
        out.append(f"glibc symbol versions above 2.17: {', '.join(newer)}")
    cxx = sorted(v for v in report["versions"] if not v.startswith("GLIBC_"))
    if cxx:
        out.append(f"versions of other libraries (a C++ runtime not linked in?): {', '.join(cxx)}")
    extra = sorted(set(report["needed"]) - LINUX_ALLOWED_NEEDED)
    if extra:
        out.append(f"needs libraries beyond libc, libm, libpthread, libdl and the loader: {', '.join(extra)}")
    out += export_problems(report["exports"])
    out += math_problems(report["imports"])
    return out


def problems_pe(report):
    """What keeps a win64 DLL from loading on a plain Windows or from giving the same bits."""
    out = []
    extra = sorted(d for d in report["imports"] if not WINDOWS_ALLOWED_DLL.match(d))
    if extra:
        out.append(f"imports DLLs beyond KERNEL32 and the C runtime: {', '.join(extra)}")
    out += export_problems(report["exports"])
    out += math_problems(set().union(*report["imports"].values()) if report["imports"] else set())
    return out


def export_problems(exports):
    expected = fmi2_functions()
    out = []
    if exports - expected:
        out.append(f"exports beyond the fmi2 functions: {', '.join(sorted(exports - expected)[:10])}")
    if expected - exports:
        out.append(f"fmi2 functions not exported: {', '.join(sorted(expected - exports))}")
    return out


def link_input_problems(build_dir, binary_names):
    """The C runtime's transcendental functions referenced by what the binaries were linked from
    (their objects, the solver's library and the dependencies' archives in build_dir), as lines.
    The import tables do not show them all: the MinGW runtime links some of them in statically,
    and the link guard of cmake/Determinism.cmake (--wrap) is not applied by zig's Windows linker."""
    build_dir = pathlib.Path(build_dir)
    files = [build_dir / "libchaindrive_core.a", *sorted((build_dir / "redirected-archives").glob("*.a"))]
    for name in binary_names:
        files += sorted(p for p in (build_dir / "CMakeFiles" / f"{name}.dir").rglob("*") if p.suffix in (".o", ".obj"))
    out = []
    for f in files:
        undefined = {line.split()[-1] for line in subprocess.run(["nm", "-u", str(f)], capture_output=True, text=True,
                                                                  check=True).stdout.splitlines()
                     if line.strip().startswith("U ")}
        used = sorted(undefined & crt_transcendentals())
        if used:
            out.append(f"{f.relative_to(build_dir)} references the C runtime's {', '.join(used)}")
    return out


def math_problems(imports):
    used = sorted(set(imports) & crt_transcendentals())
    return [f"imports the C runtime's transcendental functions: {', '.join(used)}"] if used else []
