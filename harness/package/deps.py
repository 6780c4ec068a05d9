"""The dependencies of a shipped binary, per target, in one prefix (a cross build's
CHAINDRIVE_DEPS_PREFIX): include/ with eigen3/, nlohmann/, suitesparse/ and SUNDIALS' folders,
lib/ with the static archives of SUNDIALS and KLU.

- linux64 (x86_64-linux-gnu.2.17): Debian's own archives and headers, the ones the native build
  links (position-independent code that calls nothing of glibc newer than 2.17; the linked
  binary's symbol versions are checked, harness/package/inspect.py).
- win64 (x86_64-windows-gnu): SUNDIALS 6.4.1 and SuiteSparse 5.12.0, the versions of Debian's
  packages, cross-built with zig from Debian's source packages (checked against their SHA-256),
  cached outside the checkout keyed by the versions, the compiler and this recipe; without the
  cache they are built again (about a minute on two cores).
"""
import hashlib
import os
import pathlib
import shutil
import subprocess
import tarfile
import tempfile
import urllib.request

from .. import paths
from .toolchain import Target, cmake_cross_args, zig_version

DEBIAN_POOL = "https://deb.debian.org/debian/pool/main/s"


class SourcePackage:
    """An upstream tarball of a Debian source package: where it is, what it must hash to, the
    folder it unpacks to."""

    def __init__(self, package, file, sha256, folder):
        self.package, self.file, self.sha256, self.folder = package, file, sha256, folder

    @property
    def url(self):
        return f"{DEBIAN_POOL}/{self.package}/{self.file}"


SUNDIALS = SourcePackage("sundials", "sundials_6.4.1+dfsg1.orig.tar.xz",
                         "c61157f1d4be06c704bea40cb131eb63ba2dada161989071604d0a0959cdf04a", "sundials-6.4.1")
SUITESPARSE = SourcePackage("suitesparse", "suitesparse_5.12.0+dfsg.orig.tar.xz",
                            "bb106c43049138c19675cd70322e72ff8e4fd8bdcab3a096307fd78488913faf", "SuiteSparse-5.12.0")
# (only these parts of SuiteSparse are unpacked: KLU and what it needs)
SUITESPARSE_PARTS = ("KLU", "AMD", "COLAMD", "BTF", "SuiteSparse_config")

# SUNDIALS 6.4.1 casts its 64-bit indices to `long int *` for KLU, which is 32 bits wide on
# Windows (LLP64); SuiteSparse_long is the 64-bit type KLU's long routines take everywhere.
SUNDIALS_KLU_INDEX_FIX = ("#define KLU_INDEXTYPE long int", "#define KLU_INDEXTYPE SuiteSparse_long",
                          "src/sunlinsol/klu/sunlinsol_klu.c")

SUNDIALS_OPTIONS = [
    "-DBUILD_SHARED_LIBS=OFF", "-DBUILD_STATIC_LIBS=ON", "-DEXAMPLES_ENABLE_C=OFF", "-DEXAMPLES_ENABLE_CXX=OFF",
    "-DEXAMPLES_INSTALL=OFF", "-DBUILD_ARKODE=ON", "-DBUILD_CVODE=ON", "-DBUILD_CVODES=OFF", "-DBUILD_IDA=OFF",
    "-DBUILD_IDAS=OFF", "-DBUILD_KINSOL=OFF", "-DBUILD_FORTRAN_MODULE_INTERFACE=OFF", "-DSUNDIALS_INDEX_SIZE=64",
    "-DENABLE_KLU=ON"]
KLU_ARCHIVES = ("klu", "amd", "colamd", "btf", "suitesparseconfig")
# Debian's headers and archives the linux64 prefix links to
DEBIAN_SUNDIALS_HEADERS = ("sundials", "arkode", "cvode", "nvector", "sunlinsol", "sunmatrix", "sunnonlinsol",
                           "sunmemory")
DEBIAN_LIB = pathlib.Path("/usr/lib/x86_64-linux-gnu")
KLU_RECIPE = paths.ROOT / "cmake" / "deps" / "suitesparse_klu" / "CMakeLists.txt"


def cache_root():
    """Where downloaded sources and cross-built prefixes are kept (outside the checkout)."""
    if os.environ.get("CHAINDRIVE_DEPS_CACHE"):
        return pathlib.Path(os.environ["CHAINDRIVE_DEPS_CACHE"])
    xdg = os.environ.get("XDG_CACHE_HOME") or pathlib.Path.home() / ".cache"
    return pathlib.Path(xdg) / "chaindrive" / "deps"


def zig_environment():
    """The environment of every zig run: zig's cache (ZIG_GLOBAL_CACHE_DIR, unless set) kept with
    the cross-built dependencies, not in zig's default place: on a fresh machine most of a cross
    build's time is zig compiling each platform's C runtime and libc++ into it (some 750 s for
    win64's MinGW runtime on a busy 2-core machine), and it belongs with what is cached here.
    (It serves one installation of zig only: zig finds a runtime it compiled by its library's
    files, and missed with the same library in another checkout's virtual environment, under a
    link of the same name, and copied with its times kept.)"""
    env = dict(os.environ)
    env.setdefault("ZIG_GLOBAL_CACHE_DIR", str(cache_root() / "zig-cache"))
    return env


def prefix(target, log=print):
    """The dependency prefix of `target` (a Target), built if it is not in the cache."""
    if target.platform == "linux64":
        return debian_prefix(cache_root() / target.platform, log)
    dest = cache_root() / f"{target.platform}-{cross_build_key(target)}"
    if (dest / "lib" / "libsundials_generic.a").exists():
        log(f"   dependencies of {target.platform}: cached in {dest}")
        return dest
    log(f"   dependencies of {target.platform}: cross-building SUNDIALS and KLU into {dest}")
    with tempfile.TemporaryDirectory(prefix="chaindrive-deps-") as work:
        build = pathlib.Path(work) / "prefix"
        cross_build(target, pathlib.Path(work), build)
        if dest.exists():
            shutil.rmtree(dest)
        dest.parent.mkdir(parents=True, exist_ok=True)
        shutil.move(str(build), dest)  # whole or not at all: a half-built prefix is never cached
    return dest


def cross_build_key(target):
    """Versions, compiler and recipe of a cross-built prefix, as a cache key."""
    recipe = hashlib.sha256()
    for part in (SUNDIALS.sha256, SUITESPARSE.sha256, " ".join(SUNDIALS_OPTIONS), repr(SUNDIALS_KLU_INDEX_FIX),
                 KLU_RECIPE.read_text(), target.zig_target, zig_version()):
        recipe.update(part.encode())
    return f"sundials-6.4.1-suitesparse-5.12.0-zig-{zig_version()}-{recipe.hexdigest()[:12]}"


def debian_prefix(dest, log):
    """A prefix of links to Debian's headers and archives (linux64)."""
    include, lib = dest / "include", dest / "lib"
    include.mkdir(parents=True, exist_ok=True)
    lib.mkdir(parents=True, exist_ok=True)
    links = {include / name: pathlib.Path("/usr/include") / name for name in DEBIAN_SUNDIALS_HEADERS}
    links.update({include / "eigen3": pathlib.Path("/usr/include/eigen3"),
                  include / "nlohmann": pathlib.Path("/usr/include/nlohmann"),
                  include / "suitesparse": pathlib.Path("/usr/include/suitesparse")})
    links.update({lib / a.name: a for a in DEBIAN_LIB.glob("libsundials_*.a")})
    links.update({lib / f"lib{name}.a": DEBIAN_LIB / f"lib{name}.a" for name in KLU_ARCHIVES})
    for link, real in links.items():
        if not real.exists():
            raise FileNotFoundError(f"{real} not found: install Debian's libsundials-dev, libsuitesparse-dev, "
                                    "libeigen3-dev and nlohmann-json3-dev (./run.sh does)")
        if link.is_symlink() or link.exists():
            link.unlink()
        link.symlink_to(real)
    log(f"   dependencies of linux64: Debian's archives and headers, linked from {dest}")
    return dest


def cross_build(target, work, dest):
    """SuiteSparse's KLU, then SUNDIALS with it, for `target` into dest; the header-only
    libraries linked in."""
    sundials = unpack(SUNDIALS, work)
    suitesparse = unpack(SUITESPARSE, work, parts=SUITESPARSE_PARTS)
    old, new, file = SUNDIALS_KLU_INDEX_FIX
    patched = sundials / file
    text = patched.read_text()
    if old not in text:
        raise RuntimeError(f"{patched}: '{old}' not found (another SUNDIALS version?)")
    patched.write_text(text.replace(old, new))
    cmake_build(target, KLU_RECIPE.parent, work / "build-klu", dest, [f"-DSUITESPARSE_SOURCE_DIR={suitesparse}"])
    lib = dest / "lib"
    klu = [f"-DKLU_INCLUDE_DIR={dest / 'include' / 'suitesparse'}", f"-DKLU_LIBRARY_DIR={lib}"]
    klu += [f"-D{name.upper()}_LIBRARY={lib / f'lib{name}.a'}" for name in KLU_ARCHIVES]
    cmake_build(target, sundials, work / "build-sundials", dest, SUNDIALS_OPTIONS + klu)
    for name in ("eigen3", "nlohmann"):
        (dest / "include" / name).symlink_to(pathlib.Path("/usr/include") / name)


def cmake_build(target, source, build, dest, options):
    configure = ["cmake", "-S", str(source), "-B", str(build), "-G", "Ninja", "-DCMAKE_BUILD_TYPE=Release",
                 f"-DCMAKE_INSTALL_PREFIX={dest}"] + cmake_cross_args(target) + options
    run_logged(configure, build.parent / f"{build.name}.log")
    run_logged(["cmake", "--build", str(build), "--target", "install"], build.parent / f"{build.name}.log")


def run_logged(cmd, log_file):
    """Runs cmd with its output into log_file; on failure, raises with the output's tail."""
    with open(log_file, "a") as out:
        p = subprocess.run(cmd, stdout=out, stderr=subprocess.STDOUT, env=zig_environment())
    if p.returncode != 0:
        tail = "".join(open(log_file).readlines()[-30:])
        raise RuntimeError(f"{' '.join(cmd)} failed ({p.returncode}):\n{tail}")


def unpack(source, work, parts=None):
    """The source package's tarball (downloaded once into the cache, its hash checked) unpacked
    into work; only the folders `parts` of it if given. Returns the unpacked folder."""
    tarball = download(source)
    with tarfile.open(tarball) as tar:
        members = [m for m in tar.getmembers()
                   if parts is None or any(f"/{p}/" in f"/{m.name}/" for p in parts)]
        tar.extractall(work, members=members, filter="data")
    return work / source.folder


def download(source):
    path = cache_root() / "sources" / source.file
    if path.exists() and sha256_of(path) == source.sha256:
        return path
    path.parent.mkdir(parents=True, exist_ok=True)
    partial = path.with_suffix(".part")
    with urllib.request.urlopen(source.url, timeout=120) as response, open(partial, "wb") as out:
        shutil.copyfileobj(response, out)
    digest = sha256_of(partial)
    if digest != source.sha256:
        partial.unlink()
        raise RuntimeError(f"{source.url}: SHA-256 {digest}, expected {source.sha256}")
    partial.rename(path)
    return path


def sha256_of(path):
    h = hashlib.sha256()
    with open(path, "rb") as f:
        for block in iter(lambda: f.read(1 << 20), b""):
            h.update(block)
    return h.hexdigest()
