"""The FMUs for download (dist/, written by python -m harness package, which ./run.sh test runs
before these tests): what their binaries ask of the machine that loads them, fmpy's validator,
and the same bits on every platform: the win64 DLL run under wine, the linux64 library, and a
library built from the sources as fmpy builds a source FMU, compared at every step."""
import os
import pathlib
import re
import shutil
import subprocess
import sys
import zipfile

import numpy as np
import pytest
from fmpy import read_model_description
from fmpy.validation import validate_fmu

from harness import job, paths
from harness.errors import UserError
from harness.fmu import export, fmu
from harness.package import compare, inspect

DIST = pathlib.Path(os.environ.get("CHAINDRIVE_DIST", paths.ROOT / "dist"))
FMU_IDS = ("ChainDrive", "CVTChain")
# a drive's own export, compared like the shipped FMUs: drive C of the test drives, a pump sprocket
# between the crankshaft and the camshafts (tests/drives/README.md)
EXPORTED_DRIVE = paths.ROOT / "tests" / "drives" / "diesel_pump.json"
EXPORTED_TABLES = paths.ROOT / "tests" / "drives" / "tables" / "diesel_pump"


def dist_fmu(fmu_id):
    path = DIST / f"{fmu_id}.fmu"
    if not path.exists():
        pytest.fail(f"{path} not found: python -m harness package writes it (./run.sh test and ./run.sh package do)")
    return path


@pytest.fixture(scope="session")
def work(tmp_path_factory):
    path = tmp_path_factory.mktemp("package")
    with compare.wine(path / "wine"):
        yield path


@pytest.fixture(scope="session")
def unpacked(work):
    """{FMU: folder}: each FMU of dist/ unpacked (fmpy loads its linux64 binary here)."""
    return {f: compare.unpack(dist_fmu(f), work / f) for f in FMU_IDS}


@pytest.fixture(scope="session")
def source_built(unpacked, work):
    """{FMU: folder}: each FMU with its linux64 binary built by fmpy from sources/."""
    return compare.sources_built(unpacked, work)


@pytest.fixture(scope="session")
def master(work):
    return compare.build_master(work)


@pytest.mark.parametrize("fmu_id", FMU_IDS)
def test_archive_holds_both_binaries_sources_and_resources(fmu_id):
    names = zipfile.ZipFile(dist_fmu(fmu_id)).namelist()
    assert f"binaries/linux64/{fmu_id}.so" in names
    assert f"binaries/win64/{fmu_id}.dll" in names
    assert any(n.startswith("resources/") and n.endswith(".json") for n in names)
    listed = read_model_description(str(dist_fmu(fmu_id))).buildConfigurations[0].sourceFileSets[0].sourceFiles
    assert len(listed) > 50
    assert all(f"sources/{f}" in names for f in listed)
    assert not any(re.search(r"(arkode_erk|cvode_bdf|sundials_common)\.cpp$", n) for n in names)


@pytest.mark.parametrize("fmu_id", FMU_IDS)
def test_fmpy_validates_the_fmu(fmu_id):
    assert validate_fmu(str(dist_fmu(fmu_id))) == []


@pytest.mark.parametrize("fmu_id", FMU_IDS)
def test_linux64_binary_needs_glibc_2_17_and_nothing_but_libc(fmu_id, unpacked):
    report = inspect.elf(unpacked[fmu_id] / "binaries" / "linux64" / f"{fmu_id}.so")
    assert inspect.glibc_version(report["versions"]) <= (2, 17), sorted(report["versions"])
    assert not [v for v in report["versions"] if v.startswith(("GLIBCXX", "CXXABI"))]
    assert set(report["needed"]) <= inspect.LINUX_ALLOWED_NEEDED, report["needed"]
    assert report["exports"] == inspect.fmi2_functions()
    assert not report["imports"] & inspect.crt_transcendentals()
    assert inspect.problems_elf(report) == []


@pytest.mark.parametrize("platform", ["linux64", "win64"])
def test_nothing_the_binaries_are_linked_from_calls_the_c_runtimes_transcendentals(platform):
    """(the import tables miss what the MinGW runtime links in statically)"""
    build = paths.BUILD / "package" / platform
    if not (build / "libchaindrive_core.a").exists():
        pytest.fail(f"{build} has no build: python -m harness package builds there")
    assert inspect.link_input_problems(build, FMU_IDS) == []


@pytest.mark.parametrize("fmu_id", FMU_IDS)
def test_win64_binary_imports_only_windows_system_dlls(fmu_id, unpacked):
    report = inspect.pe(unpacked[fmu_id] / "binaries" / "win64" / f"{fmu_id}.dll")
    dlls = {d.lower() for d in report["imports"]}
    assert "kernel32.dll" in dlls
    assert all(inspect.WINDOWS_ALLOWED_DLL.match(d) for d in dlls), sorted(dlls)
    assert not dlls & {"libstdc++-6.dll", "libgcc_s_seh-1.dll", "libwinpthread-1.dll"}
    assert report["exports"] == inspect.fmi2_functions()
    assert not set().union(*report["imports"].values()) & inspect.crt_transcendentals()
    assert inspect.problems_pe(report) == []


def assert_identical(comparison, what):
    assert comparison.identical, (f"{what}: {len(comparison.differing)} of {comparison.variables} variables differ "
                                  f"({', '.join(comparison.differing[:6])}); first at {comparison.first}")


@pytest.mark.parametrize("folder", ["plain", "J\u00fcrgen"])
def test_win64_binary_reads_the_resources_a_windows_uri_names(unpacked, master, work, folder):
    """file:///Z:/dir (wine's drive Z: is the Linux root) is the path Z:/dir, not /Z:/dir, also
    where the path has letters beyond ASCII (a user folder C:\\Users\\J\u00fcrgen): the DLL must read
    its resources there, not fall back to the drive built into the binary."""
    fmu_dir = work / folder / "ChainDrive"
    if not fmu_dir.exists():
        shutil.copytree(unpacked["ChainDrive"], fmu_dir, ignore=shutil.ignore_patterns("sources"))
    run = compare.run_timing(fmu_dir, 0.0005)
    windows = compare.replay_on_windows(master, fmu_dir, run, work)
    assert not [m for m in windows.log if "no resources folder" in m], windows.log
    expected = rf"0 logEvents drive: Z:/.*/{folder}/ChainDrive/resources/drive\.json$"
    assert [m for m in windows.log if re.match(expected, m)], windows.log


def test_a_missing_resources_folder_is_an_error(unpacked, work):
    """The FMU's drive and interface are in its resources: without them fmi2Instantiate refuses,
    naming the folder, instead of running another drive."""
    copy = work / "no-resources"
    shutil.copytree(unpacked["ChainDrive"], copy, ignore=shutil.ignore_patterns("resources", "sources"))
    with pytest.raises(UserError, match="has no interface.json"):
        fmu.Slave("no-resources", fmu=copy)


@pytest.mark.parametrize("method,duration", [(None, 0.030), ("fixed-verlet", 0.030),
                                             ("arkode-erk", 0.005), ("cvode-bdf-klu", 0.003)])
def test_chaindrive_win64_under_wine_gives_the_linux64_bits(unpacked, master, work, method, duration):
    linux = compare.run_timing(unpacked["ChainDrive"], duration, method)
    windows = compare.replay_on_windows(master, unpacked["ChainDrive"], linux, work)
    assert_identical(compare.compare(linux, windows), f"ChainDrive {method or 'default method'}")


def test_cvtchain_win64_under_wine_gives_the_linux64_bits(unpacked, master, work):
    linux = compare.run_cvt(unpacked["CVTChain"], 0.020)
    windows = compare.replay_on_windows(master, unpacked["CVTChain"], linux, work)
    assert_identical(compare.compare(linux, windows), "CVTChain")


@pytest.mark.parametrize("method", [None, "fixed-verlet"])
def test_chaindrive_built_from_its_sources_gives_the_linux64_bits(unpacked, source_built, method):
    runs = [compare.run_timing(d, 0.030, method) for d in (unpacked["ChainDrive"], source_built["ChainDrive"])]
    assert_identical(compare.compare(*runs), f"ChainDrive {method or 'default method'}")


def test_cvtchain_built_from_its_sources_gives_the_linux64_bits(unpacked, source_built):
    runs = [compare.run_cvt(d, 0.020) for d in (unpacked["CVTChain"], source_built["CVTChain"])]
    assert_identical(compare.compare(*runs), "CVTChain")


@pytest.mark.parametrize("method", ["arkode-erk", "cvode-bdf-klu"])
def test_source_build_refuses_the_sundials_methods_by_name(source_built, method):
    with pytest.raises(Exception, match=rf"solver.method '{method}' needs SUNDIALS"):
        compare.run_timing(source_built["ChainDrive"], 0.001, method)


@pytest.fixture(scope="session")
def exported(work):
    """Drive C's export made from the packaged binaries (dist/ChainDrive.fmu's), unpacked."""
    made = export.export(EXPORTED_DRIVE, work / "exports")
    assert set(made.binaries) == {"linux64", "win64"} and made.sources, made.binaries
    return compare.unpack(made.path, work / made.model_identifier)


def test_an_exported_drive_gives_the_linux64_bits_on_win64_and_from_its_sources(exported, unpacked, source_built,
                                                                                 master, work):
    """One binary serves every drive, so the export's sources are ChainDrive's (checked) and the
    source build's library, under the export's name, is the binary an importer builds from them."""
    ours = {p.relative_to(exported): p.read_bytes() for p in (exported / "sources").rglob("*") if p.is_file()}
    shipped = {p.relative_to(unpacked["ChainDrive"]): p.read_bytes()
               for p in (unpacked["ChainDrive"] / "sources").rglob("*") if p.is_file()}
    assert ours == shipped
    config = job.run_config(drive=str(EXPORTED_DRIVE), tables=str(EXPORTED_TABLES), rpm=3000.0)
    linux = compare.run_recorded(config, 0.010, exported)[0]
    assert "hpPump.phi" in linux.outputs and "hpPump.tau" in linux.inputs
    windows = compare.replay_on_windows(master, exported, linux, work)
    assert_identical(compare.compare(linux, windows), "the diesel drive's export on win64")
    from_sources = work / "exported-from-sources"
    if not from_sources.exists():
        shutil.copytree(exported, from_sources, ignore=shutil.ignore_patterns("binaries"))
        built = source_built["ChainDrive"] / "binaries" / "linux64" / "ChainDrive.so"
        target = from_sources / "binaries" / "linux64" / f"{compare.model_identifier(exported)}.so"
        target.parent.mkdir(parents=True)
        shutil.copyfile(built, target)
    rebuilt = compare.run_recorded(config, 0.010, from_sources)[0]
    assert_identical(compare.compare(linux, rebuilt), "the diesel drive's export built from its sources")


@pytest.mark.parametrize("fmu_id", FMU_IDS)
def test_a_process_that_unloaded_the_linux64_binary_exits_cleanly(fmu_id, unpacked):
    # fmpy unloads the library when the instance is freed; the packaged binary (zig's link, without
    # the C runtime's start files) once left its exit handlers behind, and the process crashed at
    # its exit (status -11) after everything had passed (fmu/unload.cpp)
    script = (f"from harness.fmu import fmu\n"
              f"s = fmu.Slave('unload', fmu={str(unpacked[fmu_id])!r})\n"
              f"s.initialize()\ns.step(1e-4)\ns.close()\nprint('closed')\n")
    done = subprocess.run([sys.executable, "-c", script], capture_output=True, text=True, cwd=paths.ROOT)
    assert done.returncode == 0 and done.stdout.strip() == "closed", (done.returncode, done.stderr[-2000:])


def test_the_comparison_sees_one_flipped_bit(unpacked):
    run = compare.run_timing(unpacked["ChainDrive"], 0.002)
    flipped = compare.Run(run.parameters, run.inputs, {k: np.array(v, dtype=float) for k, v in run.outputs.items()})
    flipped.outputs["tensioner.F"][7] = np.nextafter(flipped.outputs["tensioner.F"][7], np.inf)
    c = compare.compare(run, flipped)
    assert not c.identical and c.differing == ["tensioner.F"] and c.first.startswith("step 7: tensioner.F")
    assert compare.compare(run, run).identical
