"""A sweep's results as one self-describing xarray Dataset (netCDF, h5netcdf engine) and its
plots: Campbell diagrams (engine order over speed, colour the amplitude in dB) of the tensioner
force and the tension-guide angle, order cuts (orders 2, 4, 6, 8 and the meshing order over speed,
with their 95 % confidence intervals) and the minimum, mean and maximum of the tensioner and span
forces over speed.

Dimension `point`: one point per stationary speed or per engine cycle of a run-up, with the
coordinate `rpm` (the point's mean engine speed); `order` for the spectra. Variables carry their
unit (attribute `units`); failed cases are points with NaN values, their status and error."""
import json
import math

import numpy as np

from .. import cycle_stats
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


CAMPBELL_RANGE_DB = 40.0  # [dB] colour range of the Campbell diagrams below their largest amplitude
RUNUP_BLOCK = 8  # run-up: consecutive engine cycles per mean with a confidence interval in the order cuts
COMPRESSION_NOTE = "< 0: compression (the joint's pins pushed together)"


def plots(ds, out, meshing, title):
    """Campbell diagrams, order cuts and force ranges over speed: the PNG files written."""
    from ..plots import plt
    ok = ds.where(ds["status"] == "ok", drop=True).sortby("rpm")
    written = [_campbell(plt, ok, out, name, unit, meshing, title) for name, unit, _ in SPECTRUM_SIGNALS]
    written.append(_order_cuts(plt, ok, out, meshing, title))
    written.append(_force_ranges(plt, ok, out, title))
    return written


def decibels(amplitude, reference=1.0):
    """20 log10(amplitude / reference) [dB]; zero amplitudes give -inf (drawn below the range)."""
    with np.errstate(divide="ignore"):
        return 20.0 * np.log10(np.asarray(amplitude, float) / reference)


def _campbell(plt, ok, out, name, unit, meshing, title):
    """Engine order over speed, the amplitude in dB re 1 unit over CAMPBELL_RANGE_DB below its
    largest, with the cut orders and the meshing order marked."""
    level = decibels(ok[name + ".orderAmplitude"].values)
    top = float(np.nanmax(level[np.isfinite(level)]))
    fig, ax = plt.subplots(figsize=(8.5, 5))
    mesh = ax.pcolormesh(ok["rpm"].values, ok["order"].values, level.T, shading="nearest", cmap="viridis",
                         vmin=top - CAMPBELL_RANGE_DB, vmax=top)
    fig.colorbar(mesh, ax=ax, label=f"amplitude [dB re 1 {unit}]", extend="min", pad=0.1)
    for k in list(CUT_ORDERS) + [meshing]:
        ax.axhline(k, color="w", lw=0.7, ls="--", alpha=0.8)
        ax.annotate(f"{k:g}" + (" meshing" if k == meshing else ""), (1.0, k), xycoords=("axes fraction", "data"),
                    xytext=(3, 0), textcoords="offset points", va="center", fontsize=7)
    ax.set(xlabel="engine speed [rpm]", ylabel="engine order (per crankshaft revolution)",
           title=f"Campbell diagram: {name}, {title}")
    path = out / f"campbell_{name.replace('.', '_')}.png"
    fig.savefig(path, dpi=110, bbox_inches="tight")
    plt.close(fig)
    return path


def block_intervals(rpm, values, block=RUNUP_BLOCK):
    """(mean speed, mean, 95 % confidence half-width) of every run of `block` consecutive points
    (a run-up's single engine cycles), arrays over the runs."""
    runs = [slice(i, i + block) for i in range(0, len(values) - block + 1, block)]
    stats = [cycle_stats.interval(values[r])[:2] for r in runs]
    return (np.array([np.mean(rpm[r]) for r in runs]), np.array([m for m, _ in stats]),
            np.array([h for _, h in stats]))


def order_cut_keys(name, meshing):
    """{order: the headline key of its amplitude} of an output (harness/cycle_stats.py's keys)."""
    suffix = next(s for n, _, _, s in cycle_stats.ORDER_SIGNALS if n == name)
    return {k: f"{name}.order{k:g}{suffix}" for k in list(CUT_ORDERS) + [meshing]}


def _order_cut(ax, ok, key, label):
    """One order's amplitude over speed with its 95 % confidence interval: a stationary sweep's
    per speed (its .ci95), a run-up's single cycles as dots and means of RUNUP_BLOCK cycles."""
    rpm, values = ok["rpm"].values, ok[key].values
    ci = ok[key + ".ci95"].values if key + ".ci95" in ok else np.full_like(values, np.nan)
    if np.any(np.isfinite(ci)):
        line, = ax.plot(rpm, values, "o-", ms=3, label=label)
        ax.fill_between(rpm, values - ci, values + ci, color=line.get_color(), alpha=0.18, lw=0)
        return "per speed: mean over its counted cycles, band: 95 % confidence interval"
    line, = ax.plot(rpm, values, ".", ms=2, alpha=0.4)
    at, mean, half = block_intervals(rpm, values)
    ax.errorbar(at, mean, yerr=half, fmt="o-", ms=3, lw=1, capsize=2, color=line.get_color(), label=label)
    return (f"dots: single engine cycles; lines: means of {RUNUP_BLOCK} consecutive cycles, error bars: 95 % "
            "confidence interval")


def _order_cuts(plt, ok, out, meshing, title):
    fig, axes = plt.subplots(1, 2, figsize=(12.5, 5))
    for ax, (name, unit, _) in zip(axes, SPECTRUM_SIGNALS):
        for k, key in order_cut_keys(name, meshing).items():
            what = _order_cut(ax, ok, key, f"order {k:g}" + (" (meshing)" if k == meshing else ""))
        ax.set(xlabel="engine speed [rpm]", ylabel=f"amplitude [{unit}]", title=f"order cuts: {name}")
        ax.set_ylim(bottom=0.0)
        ax.grid(True, lw=0.3)
        ax.legend(fontsize=8)
    fig.suptitle(f"{title}\n{what}", fontsize=10)
    fig.tight_layout()
    path = out / "order_cuts.png"
    fig.savefig(path, dpi=110, bbox_inches="tight")
    plt.close(fig)
    return path


def _force_ranges(plt, ok, out, title):
    """Per force a panel: its mean (with its 95 % confidence interval where the points have one)
    and the band from its minimum to its maximum over the counted cycles."""
    fig, axes = plt.subplots(len(FORCE_SIGNALS), 1, figsize=(8.5, 2.6 * len(FORCE_SIGNALS) + 0.8), sharex=True)
    rpm = ok["rpm"].values
    for ax, name in zip(axes, FORCE_SIGNALS):
        mean = ok[name + ".mean"].values
        ci = ok[name + ".mean.ci95"].values if name + ".mean.ci95" in ok else np.full_like(mean, np.nan)
        ax.fill_between(rpm, ok[name + ".min"], ok[name + ".max"], color="tab:blue", alpha=0.2, lw=0,
                        label="minimum to maximum")
        ax.errorbar(rpm, mean, yerr=None if np.all(np.isnan(ci)) else ci, fmt="-", color="tab:blue", lw=1,
                    capsize=2, label="mean" + ("" if np.all(np.isnan(ci)) else " +- 95 % confidence half-width"))
        ax.axhline(0.0, color="k", lw=0.6, label=f"0 N; {COMPRESSION_NOTE}")
        ax.set_ylabel(f"{name} [N]")
        ax.grid(True, lw=0.3)
        ax.legend(fontsize=7, loc="upper left")
    axes[-1].set_xlabel("engine speed [rpm]")
    fig.suptitle(f"forces over speed: {title}\nminimum and maximum over each point's counted cycles (a run-up's "
                 "point: one engine cycle)", fontsize=10)
    fig.tight_layout()
    path = out / "forces_over_speed.png"
    fig.savefig(path, dpi=110, bbox_inches="tight")
    plt.close(fig)
    return path
