"""A sweep's results as one self-describing xarray Dataset (netCDF, h5netcdf engine) and its
plots: Campbell diagrams (engine order over speed, colour the amplitude in dB) of the tensioner
force and the tension-guide angle, order cuts (orders 2, 4, 6, 8 and the meshing order over speed,
with their 95 % confidence intervals) and the minimum, mean and maximum of the tensioner and span
forces over speed.

Dimension `point`: one point per stationary speed or per engine cycle of a run-up, with the
coordinate `rpm` (the point's mean engine speed) and, when the sweep set them, the hydraulic
tensioner's oil settings `supply_pressure_bar` and `oil_temperature_c` (a case that leaves one
unset has the main job's default there); `order` for the spectra. Variables carry their unit
(attribute `units`); failed cases are points with NaN values, their status and error. A sweep of a
hydraulic tensioner adds the plot hydraulic_over_speed.png."""
import json
import math

import numpy as np

from .. import cycle_stats, job
from .cases import CHAMBER_EXTREMES, FORCE_SIGNALS

CUT_ORDERS = (2, 4, 6, 8)


def dataset(cases, results, attrs):
    """The Dataset of a sweep's cases and results (run_case's dicts), with attrs (the drive's
    parameters, the code version) as global attributes."""
    import xarray as xr
    ok = [r for r in results if r["status"] == "ok"]
    orders = ok[0]["orders"] if ok else []
    units = ok[0]["units"] if ok else {}
    spectrum_units = ok[0]["spectrumUnits"] if ok else {}
    points, spectra, status = [], {name: [] for name in spectrum_units}, []
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
    for name, unit in spectrum_units.items():
        data[name + ".orderAmplitude"] = (("point", "order"), np.array(spectra[name], float).reshape(len(points), -1),
                                          {"units": unit, "long_name": f"engine-order amplitude of {name}"})
    data["status"] = ("point", np.array([s for s, _, _ in status], dtype=object))
    data["case"] = ("point", np.array([c for _, c, _ in status], dtype=object))
    data["error"] = ("point", np.array([e for _, _, e in status], dtype=object))
    coords = {"rpm": ("point", np.array([p["rpm"] for p in points], float), {"units": "rpm"}),
              "order": ("order", np.array(orders, float), {"units": "1", "long_name": "engine order per crankshaft revolution"})}
    coords.update(oil_coordinates(cases, results))
    return xr.Dataset(data, coords=coords, attrs=attrs)


# the oil settings as coordinates: (name, Case field, default, from SI to the coordinate's unit, unit)
OIL_COORDINATES = (("supply_pressure_bar", "supply_pressure", job.SUPPLY_PRESSURE, lambda p: p / job.BAR, "bar"),
                   ("oil_temperature_c", "oil_temperature", job.OIL_TEMPERATURE, lambda T: T - job.ZERO_CELSIUS,
                    "degC"))


def oil_coordinates(cases, results):
    """The coordinates along `point` of the oil settings some case sets (each case's value on each
    of its points; the main job's default where a case leaves it unset)."""
    coords = {}
    for name, field, default, convert, unit in OIL_COORDINATES:
        if all(getattr(c, field) is None for c in cases):
            continue
        per_point = [convert(default if getattr(c, field) is None else getattr(c, field))
                     for c, r in zip(cases, results) for _ in (r["rows"] if r["status"] == "ok" else [None])]
        coords[name] = ("point", np.array(per_point, float), {"units": unit})
    return coords


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


def spectrum_signals(ds):
    """(name, unit) of the signals whose order spectra the dataset holds."""
    return [(v[:-len(".orderAmplitude")], ds[v].attrs["units"]) for v in ds.data_vars if v.endswith(".orderAmplitude")]


def plots(ds, out, meshing, title):
    """Campbell diagrams, order cuts and force ranges over speed: the PNG files written."""
    from ..plots import plt
    ok = ds.where(ds["status"] == "ok", drop=True).sortby("rpm")
    written = [_campbell(plt, ok, out, name, unit, meshing, title) for name, unit in spectrum_signals(ds)]
    written.append(_order_cuts(plt, ok, out, meshing, title))
    written.append(_force_ranges(plt, ok, out, title))
    if cycle_stats.CHAMBER + ".mean_bar" in ok:
        written.append(hydraulic_over_speed(plt, ok, out / "hydraulic_over_speed.png", title))
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
    suffix = "_deg" if name.endswith(".phi") else ""  # (an angle's amplitudes in deg: cycle_stats.order_signals)
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
    for ax, (name, unit) in zip(axes, spectrum_signals(ok)):
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
    forces = [name for name in FORCE_SIGNALS if name + ".mean" in ok]
    fig, axes = plt.subplots(len(forces), 1, figsize=(8.5, 2.6 * len(forces) + 0.8), sharex=True, squeeze=False)
    axes = axes[:, 0]
    rpm = ok["rpm"].values
    for ax, name in zip(axes, forces):
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


def oil_lines(ok):
    """[(label, the points of one oil setting)] of the sweep: one per combination of the oil
    coordinates it has (one line, unlabelled, without them)."""
    names = [name for name, *_ in OIL_COORDINATES if name in ok.coords]
    if not names:
        return [("", ok)]
    settings = sorted({tuple(float(ok[n].values[i]) for n in names) for i in range(ok.sizes["point"])})
    units = {name: unit for name, _, _, _, unit in OIL_COORDINATES}
    lines = []
    for setting in settings:
        at = np.logical_and.reduce([ok[n].values == v for n, v in zip(names, setting)])
        lines.append((", ".join(f"{v:g} {units[n]}" for n, v in zip(names, setting)), ok.isel(point=at)))
    return lines


def _mean_with_band(ax, rpm, mean, ci, label, **style):
    """A mean over speed with its 95 % confidence band (where the points have one); its colour."""
    line, = ax.plot(rpm, mean, "o-", ms=3, label=label, **style)
    if np.any(np.isfinite(ci)):
        ax.fill_between(rpm, mean - ci, mean + ci, color=line.get_color(), alpha=0.2, lw=0)
    return line.get_color()


def hydraulic_over_speed(plt, ok, path, title):
    """The hydraulic tensioner over speed, one colour per oil setting: the tensioner force's mean
    (band: 95 % confidence interval) and maximum; the chamber pressure's mean (band), lowest and
    highest over the counted cycles [bar]."""
    chamber = cycle_stats.CHAMBER
    low, high = CHAMBER_EXTREMES
    fig, (force, pressure) = plt.subplots(2, 1, figsize=(9, 8.5), sharex=True)
    for label, pts in oil_lines(ok):
        pts = pts.sortby("rpm")
        rpm = pts["rpm"].values

        def ci(key):
            return pts[key + ".ci95"].values if key + ".ci95" in pts else np.full(len(rpm), np.nan)
        colour = _mean_with_band(force, rpm, pts["tensioner.F.mean"].values, ci("tensioner.F.mean"),
                                 f"{label}: mean".lstrip(": "))
        force.plot(rpm, pts["tensioner.F.max"].values, "v--", ms=3, lw=0.8, color=colour,
                   label=f"{label}: maximum".lstrip(": "))
        _mean_with_band(pressure, rpm, pts[chamber + ".mean_bar"].values, ci(chamber + ".mean_bar"),
                        f"{label}: mean".lstrip(": "), color=colour)
        pressure.plot(rpm, pts[high].values, "v--", ms=3, lw=0.8, color=colour, label=f"{label}: highest".lstrip(": "))
        pressure.plot(rpm, pts[low].values, "^:", ms=3, lw=0.8, color=colour, label=f"{label}: lowest".lstrip(": "))
    force.set_ylabel("tensioner force [N]")
    pressure.set_ylabel("chamber pressure, gauge [bar]")
    pressure.axhline(0.0, color="k", lw=0.6)
    pressure.set_xlabel("engine speed [rpm]")
    for ax in (force, pressure):
        ax.grid(True, lw=0.3)
        ax.legend(fontsize=7, ncol=3, loc="upper left")
    fig.suptitle(f"hydraulic tensioner over speed: {title}\nmean with its 95 % confidence band; maximum, highest and "
                 "lowest over each point's counted cycles", fontsize=10)
    fig.tight_layout()
    fig.savefig(path, dpi=110, bbox_inches="tight")
    plt.close(fig)
    return path
