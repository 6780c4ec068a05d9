"""An FMU archive from its parts: the model description with its <SourceFiles> list, a binary per
platform, the sources, the resources and the licenses of what the binaries contain. The archive
is reproducible: entries in sorted order, one fixed time stamp, fixed permissions."""
import pathlib
import re
import shutil
import zipfile

# (1980-01-01, the earliest time a zip entry can carry)
ZIP_TIME = (1980, 1, 1, 0, 0, 0)
# what the binaries contain, with the Debian package whose copyright file states its license
LICENSES = {"SUNDIALS": "libsundials-dev", "KLU": "libklu1", "AMD": "libamd2", "COLAMD": "libcolamd2",
            "BTF": "libbtf1", "SuiteSparse_config": "libsuitesparseconfig5", "Eigen": "libeigen3-dev",
            "nlohmann-json": "nlohmann-json3-dev"}


def with_source_files(model_description, source_files):
    """The model description's text with <SourceFiles> listing source_files in <CoSimulation>
    (FMI 2.0: the files an importer compiles, relative to sources/)."""
    text = pathlib.Path(model_description).read_text()
    files = "".join(f'\n      <File name="{f}"/>' for f in source_files)
    listing = f"\n    <SourceFiles>{files}\n    </SourceFiles>\n  "
    m = re.search(r"<CoSimulation\b[^>]*?(/>|>)", text)
    if not m:
        raise ValueError(f"{model_description}: no <CoSimulation> element")
    if m.group(1) == "/>":
        head = text[:m.start()] + m.group(0)[:-2].rstrip() + ">"
        return head + listing + "</CoSimulation>" + text[m.end():]
    return text[:m.end()] + listing + text[m.end():]


def stage_licenses(stage):
    folder = stage / "documentation" / "licenses"
    folder.mkdir(parents=True, exist_ok=True)
    for name, package in LICENSES.items():
        shutil.copyfile(f"/usr/share/doc/{package}/copyright", folder / f"{name}.txt")


def write_zip(stage, fmu_file):
    """The staged folder as an FMU (zip) archive, reproducibly."""
    fmu_file.parent.mkdir(parents=True, exist_ok=True)
    partial = fmu_file.with_suffix(".fmu.part")
    with zipfile.ZipFile(partial, "w", zipfile.ZIP_DEFLATED, compresslevel=9) as z:
        for path in sorted(p for p in stage.rglob("*") if p.is_file()):
            info = zipfile.ZipInfo(path.relative_to(stage).as_posix(), date_time=ZIP_TIME)
            info.compress_type = zipfile.ZIP_DEFLATED
            executable = path.suffix in (".so", ".dll")
            info.external_attr = (0o755 if executable else 0o644) << 16
            z.writestr(info, path.read_bytes())
    partial.replace(fmu_file)
