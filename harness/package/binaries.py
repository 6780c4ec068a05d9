"""The FMUs' binaries for one platform: this repository's CMake project cross-built with zig
(cmake/toolchains) against the platform's dependency prefix (deps.py)."""
import os

from .. import paths
from . import deps
from .toolchain import cmake_cross_args
from .deps import run_logged

FMUS = ("ChainDrive", "CVTChain")


def fmi2_include_dir():
    import fmpy
    return os.path.join(os.path.dirname(fmpy.__file__), "c-code")


def build(target, build_root, jobs, log=print):
    """Builds every FMU's binary for `target` in build_root/<platform>; returns {FMU: path}."""
    prefix = deps.prefix(target, log)
    build_dir = build_root / target.platform
    build_dir.mkdir(parents=True, exist_ok=True)
    log_file = build_root / f"{target.platform}.log"
    log_file.write_text("")
    configure = ["cmake", "-S", str(paths.ROOT), "-B", str(build_dir), "-G", "Ninja", "-DCMAKE_BUILD_TYPE=Release",
                 "-DCHAINDRIVE_TESTS=OFF", f"-DCHAINDRIVE_DEPS_PREFIX={prefix}",
                 f"-DFMI2_INCLUDE_DIR={fmi2_include_dir()}"] + cmake_cross_args(target)
    log(f"   building the {target.platform} binaries in {build_dir} (log: {log_file})")
    run_logged(configure, log_file)
    run_logged(["cmake", "--build", str(build_dir), "-j", str(jobs), "--target", *FMUS], log_file)
    return {name: build_dir / f"{name}{target.suffix}" for name in FMUS}
