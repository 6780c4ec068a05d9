"""The FMUs' binaries for one platform: this repository's CMake project cross-built with zig
(cmake/toolchains) against the platform's dependency prefix (deps.py)."""
import importlib.util
import os

from .. import paths
from . import deps
from .toolchain import cmake_cross_args
from .deps import run_logged

FMUS = ("ChainDrive", "CVTChain")
# the core and each FMU's own sources as one translation unit each (as the FMUs' source builds,
# compare.py): the headers parsed and the templates instantiated once (win64: 288 CPU s against
# 510 in batches of 8); these builds run beside the native build, whose cores are busy anyway
ONE_UNIT = ["-DCMAKE_UNITY_BUILD=ON", "-DCMAKE_UNITY_BUILD_BATCH_SIZE=0", "-DCHAINDRIVE_UNITY_BATCH_SIZE=0"]


def fmi2_include_dir():
    """fmpy's FMI 2 headers, found without importing fmpy (./run.sh test starts these builds
    before pip has installed fmpy's dependencies)."""
    return os.path.join(importlib.util.find_spec("fmpy").submodule_search_locations[0], "c-code")


def build(target, build_root, jobs, log=print):
    """Builds every FMU's binary for `target` in build_root/<platform>; returns {FMU: path}."""
    prefix = deps.prefix(target, log)
    build_dir = build_root / target.platform
    build_dir.mkdir(parents=True, exist_ok=True)
    log_file = build_root / f"{target.platform}.log"
    log_file.write_text("")
    configure = ["cmake", "-S", str(paths.ROOT), "-B", str(build_dir), "-G", "Ninja", "-DCMAKE_BUILD_TYPE=Release",
                 "-DCHAINDRIVE_TESTS=OFF", f"-DCHAINDRIVE_DEPS_PREFIX={prefix}",
                 f"-DFMI2_INCLUDE_DIR={fmi2_include_dir()}"] + ONE_UNIT + cmake_cross_args(target)
    log(f"   building the {target.platform} binaries in {build_dir} (log: {log_file})")
    run_logged(configure, log_file)
    run_logged(["cmake", "--build", str(build_dir), "-j", str(jobs), "--target", *FMUS], log_file)
    return {name: build_dir / f"{name}{target.suffix}" for name in FMUS}
