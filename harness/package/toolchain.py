"""The platforms the FMUs ship for and the compiler that builds them: zig's Clang (PyPI's
ziglang), one compiler for all of them. Why zig: its glibc target chooses the symbol versions
(x86_64-linux-gnu.2.17 links against glibc 2.17's, so the binary loads on RHEL 7 and later,
Ubuntu 14.04 and later, SLES 12 and later), it cross-compiles for Windows with the MinGW-w64 C
runtime and LLVM's libc++ built in (nothing to ship beside the DLL), and it installs from PyPI
like the rest of the harness. Debian's MinGW GCC would serve Windows too, but Linux would then
still need a second compiler, and GCC spills 32-byte AVX registers to a stack that the Win64
ABI aligns to 16 bytes only (GCC PR 49001)."""
import functools
import subprocess
import sys
from dataclasses import dataclass

from .. import paths


@dataclass(frozen=True)
class Target:
    platform: str    # the FMU's binaries/<platform> folder
    zig_target: str  # zig's target triple
    suffix: str      # the shared library's file suffix

    @property
    def toolchain_file(self):
        return paths.ROOT / "cmake" / "toolchains" / f"zig-{self.zig_target}.cmake"


LINUX64 = Target("linux64", "x86_64-linux-gnu.2.17", ".so")
WIN64 = Target("win64", "x86_64-windows-gnu", ".dll")
TARGETS = {t.platform: t for t in (LINUX64, WIN64)}


def cmake_cross_args(target):
    """CMake's options for a cross build of `target` with zig from this Python's ziglang."""
    return [f"-DCMAKE_TOOLCHAIN_FILE={target.toolchain_file}", f"-DZIG_PYTHON={sys.executable}"]


@functools.lru_cache(maxsize=None)
def zig_version():
    try:
        out = subprocess.run([sys.executable, "-m", "ziglang", "version"], capture_output=True, text=True, check=True)
    except (subprocess.CalledProcessError, FileNotFoundError) as e:
        raise RuntimeError(f"zig is not installed in {sys.executable} (pip install -e '.[package]'; "
                           "./run.sh package does)") from e
    return out.stdout.strip()
