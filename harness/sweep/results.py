"""A sweep's results as one self-describing xarray Dataset (netCDF, h5netcdf engine) and its
plots: Campbell diagrams (engine order over speed, colour the amplitude) of the tensioner force
and the tension-guide angle, order cuts (orders 2, 4, 6, 8 and the meshing order over speed) and
the minimum, mean and maximum of the tensioner and span forces over speed.

Dimension `point`: one point per stationary speed or per engine cycle of a run-up, with the
coordinate `rpm` (the point's mean engine speed); `order` for the spectra. Variables carry their
unit (attribute `units`); failed cases are points with NaN values, their status and error."""
import json
import math

import numpy as np

from .cases import FORCE_SIGNALS, SPECTRUM_SIGNALS

CUT_ORDERS = (2, 4, 6, 8)


def dataset(cases, results, attrs):
    """The Dataset of a sweep's cases and results (run_case's dicts), with attrs (the drive's
    parameters, the code version) as global attributes."""
    import xarray as xr
    points, spectra, status = [], {name: [] for name, _, _ in SPECTRUM_SIGNALS}, []
    ok = [r for r in results if r["status"] == "ok"]
    orders = ok[0]["orders"] if ok else []
    units = ok[0]["units"] if ok else {}
    for case, r in zip(cases, results):
        if r["status"] == "ok":
            points += r["rows"]
            for name in spectra:
                spectra[name] += r["spectra"][name]
            status += [("ok", case.label(), "")] * len(r["rows"])
        else:
            points.append({"rpm": case.rpm})
            for name in spectra:
                spectra[name].append([math.nan] * len(orders))
            status.append(("failed", case.label(), r["error"]))
    keys = sorted({k for p in points for k in p if k != "rpm"})
    data = {k: ("point", np.array([p.get(k, math.nan) for p in points], float),
                {"units": units.get(k.removesuffix(".ci95"), "1")}) for k in keys}
    for (name, unit, _) in SPECTRUM_SIGNALS:
        data[name + ".orderAmplitude"] = (("point", "order"), np.array(spectra[name], float).reshape(len(points), -1),
                                          {"units": unit, "long_name": f"engine-order amplitude of {name}"})
    data["status"] = ("point", np.array([s for s, _, _ in status], dtype=object))
    data["case"] = ("point", np.array([c for _, c, _ in status], dtype=object))
    data["error"] = ("point", np.array([e for _, _, e in status], dtype=object))
    coords = {"rpm": ("point", np.array([p["rpm"] for p in points], float), {"units": "rpm"}),
              "order": ("order", np.array(orders, float), {"units": "1", "long_name": "engine order per crankshaft revolution"})}
    return xr.Dataset(data, coords=coords, attrs=attrs)


def write_netcdf(ds, path):
    ds.to_netcdf(path, engine="h5netcdf")


def attributes(drive, case, version, command):
    """Global attributes: what ran (fidelity, method, step, tables), the drive's main parameters
    and its whole description (JSON), the code version and the command."""
    chain = drive.get("chain", {})
    return {"title": f"ChainDrive sweep: {drive.get('name', 'drive')}", "fidelity": case.fidelity,
            "method": case.method, "solver_step_s": case.solver_step or math.nan, "cycles_per_speed": case.cycles,
            "tables": case.tables or "harness/tables/data", "links": chain.get("links", 0),
            "pitch_m": chain.get("pitch", math.nan), "drive_json": json.dumps(drive), "code_version": version,
            "command": command}


def plots(ds, out, meshing, title):
    """Campbell diagrams, order cuts and force ranges over speed: the PNG files written."""
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    ok = ds.where(ds["status"] == "ok", drop=True).sortby("rpm")
    written = []
    for name, unit, _ in SPECTRUM_SIGNALS:
        fig, ax = plt.subplots(figsize=(8, 5))
        amp = ok[name + ".orderAmplitude"].values
        mesh = ax.pcolormesh(ok["rpm"].values, ok["order"].values, amp.T, shading="nearest", cmap="viridis")
        fig.colorbar(mesh, ax=ax, label=f"amplitude [{unit}]")
        for k in list(CUT_ORDERS) + [meshing]:
            ax.axhline(k, color="w", lw=0.4, ls=":")
        ax.set(xlabel="engine speed [rpm]", ylabel="engine order", title=f"Campbell diagram: {name}, {title}")
        path = out / f"campbell_{name.replace('.', '_')}.png"
        fig.savefig(path, dpi=110, bbox_inches="tight")
        plt.close(fig)
        written.append(path)
    written.append(_order_cuts(plt, ok, out, meshing, title))
    written.append(_force_ranges(plt, ok, out, title))
    return written


def _order_cuts(plt, ok, out, meshing, title):
    fig, axes = plt.subplots(1, 2, figsize=(12, 4.5))
    for ax, (name, unit, _) in zip(axes, SPECTRUM_SIGNALS):
        for k in list(CUT_ORDERS) + [meshing]:
            cut = ok[name + ".orderAmplitude"].sel(order=float(k), method="nearest")
            ax.plot(ok["rpm"], cut, "o-" if ok.sizes["point"] < 40 else "-", ms=3,
                    label=f"order {k:g}" + (" (meshing)" if k == meshing else ""))
        ax.set(xlabel="engine speed [rpm]", ylabel=f"amplitude [{unit}]", title=f"order cuts: {name}")
        ax.legend(fontsize=8)
    fig.suptitle(title)
    path = out / "order_cuts.png"
    fig.savefig(path, dpi=110, bbox_inches="tight")
    plt.close(fig)
    return path


def _force_ranges(plt, ok, out, title):
    fig, ax = plt.subplots(figsize=(8, 5))
    for name in FORCE_SIGNALS:
        line, = ax.plot(ok["rpm"], ok[name + ".mean"], "-", label=f"{name} mean")
        ax.fill_between(ok["rpm"], ok[name + ".min"], ok[name + ".max"], color=line.get_color(), alpha=0.2,
                        label=f"{name} min-max")
    ax.set(xlabel="engine speed [rpm]", ylabel="force [N]", title=f"forces over speed: {title}")
    ax.legend(fontsize=8)
    path = out / "forces_over_speed.png"
    fig.savefig(path, dpi=110, bbox_inches="tight")
    plt.close(fig)
    return path
