"""Plots engineers read: time histories, order spectra, one cycle of a link, cycle statistics."""

import numpy as np

from .. import cycle_stats
from ..drive.description import drive_json, geometry
from . import plt


def order_spectrum(t, x, rpm):
    """Single-sided amplitude spectrum over engine order (per crankshaft revolution), Hann window
    with amplitude correction, over the given samples."""
    x = np.asarray(x) - np.mean(x)
    n = len(x)
    dt = t[1] - t[0]
    w = np.hanning(n)
    X = np.fft.rfft(x * w) * 2.0 / np.sum(w)
    f = np.fft.rfftfreq(n, dt)
    return f / (rpm / 60.0), np.abs(X)


RUN_IN_SHADE = "0.92"  # the run-in's shade in time histories
COMPRESSION_NOTE = "< 0: compression (the joint's pins pushed together)"


def time_histories(path, d, rpm, title, elements, t_end=None, t_counted=None):
    """The outputs of a drive (drive.description.Elements) over time, up to t_end (default: all);
    the run-in, up to t_counted, shaded: the tensioner force, the measured spans' forces, the
    tension guide's angle, every free sprocket's timing (a camshaft) or speed (a pump, an idler),
    the chain's torque on the crankshaft, and a hydraulic tensioner's chamber pressure
    (cycle_stats.has_chamber). Panels whose outputs the drive has not are left out."""
    if t_end is not None:
        d = {k: v[d["time"] <= t_end] for k, v in d.items()}
    t = d["time"] * 1e3
    panels = [p for p in time_panels(d, elements) if p]
    fig, ax = plt.subplots(len(panels), 1, figsize=(10, 2.3 * len(panels)), sharex=True, squeeze=False)
    ax = ax[:, 0]
    for a, (label, lines) in zip(ax, panels):
        for name, y in lines:
            a.plot(t, y, lw=0.6, label=name)
        a.set_ylabel(label)
        if len(lines) > 1:
            a.legend(fontsize=7, loc="upper right")
        a.grid(True, lw=0.3)
    if t_counted is not None:
        for a in ax:
            a.axvspan(t[0], t_counted * 1e3, color=RUN_IN_SHADE, lw=0, zorder=0)
        for text, at in (("run-in (discarded)", 0.5 * (t[0] + t_counted * 1e3)),
                         ("counted cycles", 0.5 * (t_counted * 1e3 + t[-1]))):
            ax[0].annotate(text, (at, 1.0), xycoords=("data", "axes fraction"), ha="center", va="bottom", fontsize=8)
    ax[-1].set_xlabel("time [ms]")
    fig.suptitle(title, fontsize=10)
    fig.tight_layout()
    fig.savefig(path, dpi=110)
    plt.close(fig)


def time_panels(d, elements):
    """(y label, [(legend, values)]) of each panel of time_histories, None for one the drive has not."""
    spans = [(name, d[f"chain.F{name}"]) for name in ("tight", "slack") if f"chain.F{name}" in d]
    if spans:
        spans.append((f"0 N; {COMPRESSION_NOTE}", np.zeros_like(d["time"])))
    cams = [s.name for s in elements.free if cycle_stats.is_camshaft(elements, s.name)]
    others = [s.name for s in elements.free if not cycle_stats.is_camshaft(elements, s.name)]
    guide = elements.tension_guide
    return [("tensioner force [N]", [("tensioner.F", d["tensioner.F"])]) if "tensioner.F" in d else None,
            ("span force [N]", spans) if spans else None,
            (f"{guide} [deg]", [(guide, np.degrees(d[guide + ".phi"]))]) if guide else None,
            ("cam timing dev. [deg CA]", [(n, cycle_stats.timing_deg(d, elements, n)) for n in cams]) if cams else None,
            ("speed [rpm]", [(n, d[n + ".w"] * cycle_stats.RPM_PER_RAD_S) for n in others]) if others else None,
            (f"chain torque on {elements.crank} [N m]", [(elements.crank + ".tau", d[elements.crank + ".tau"])]),
            ("tensioner chamber,\ngauge [bar]", [("chamber", d[cycle_stats.CHAMBER] / cycle_stats.BAR)])
            if cycle_stats.has_chamber(d) else None]


def periodic_window(time, t0):
    """Samples from t0 to the end without the last one: a run over whole engine cycles sampled at
    a fixed step then spans whole cycles, so that engine orders fall on spectral bins."""
    sel = time >= t0 - 1e-12
    idx = np.flatnonzero(sel)
    if len(idx) > 1:
        sel[idx[-1]] = False
    return sel


SPECTRUM_HIGHEST_ORDER = 40  # engine orders drawn in spectra.png (at least the meshing order + 4)


def spectra(path, d, spans, elements, title):
    """Order spectra of the tensioner force and the tension-guide angle over the counted cycles
    (spans, cycle_stats.counted_spans; the paper's Figure 13): every cycle's amplitudes from the
    crank-angle resampling of the summary, their mean over the cycles as the bar and its 95 %
    confidence half-width as the error bar (cycle_stats.order_spectrum), so that the bars at the
    headline orders are the summary's numbers, written above them. Returns {output: (orders, bar
    heights drawn)}."""
    meshing = elements.meshing_order
    orders = cycle_stats.half_orders(max(SPECTRUM_HIGHEST_ORDER, meshing + 4))
    headline = list(cycle_stats.ORDERS) + [meshing]
    signals = cycle_stats.order_signals(elements)
    fig, ax = plt.subplots(len(signals), 1, figsize=(11, 3.6 * len(signals) + 0.8), sharex=True, squeeze=False)
    drawn = {}
    for a, (name, unit, scale, _) in zip(ax[:, 0], signals):
        mean, half = cycle_stats.order_spectrum(d, spans, name, orders, scale, elements.crank)
        colours = ["tab:orange" if o in headline else "tab:blue" for o in orders]
        bars = a.bar(orders, mean, width=0.3, color=colours, yerr=half, error_kw={"lw": 0.6, "ecolor": "0.25"})
        drawn[name] = (np.array(orders), np.array([bar.get_height() for bar in bars.patches]))
        for k in headline:
            i = orders.index(k)
            a.annotate(f"{mean[i]:.4g}", (k, mean[i] + half[i]), xytext=(0, 2), textcoords="offset points",
                       ha="center", va="bottom", fontsize=7)
        a.axvline(meshing, color="tab:red", ls="--", lw=0.8, zorder=0,
                  label=f"meshing order {meshing:g} (crankshaft sprocket's teeth)")
        a.set_ylabel(f"{name} amplitude [{unit}]")
        a.set_ylim(top=1.12 * float(np.nanmax(mean + np.nan_to_num(half))))
        lines, labels = a.get_legend_handles_labels()
        a.legend(lines + [plt.Rectangle((0, 0), 1, 1, color=c) for c in ("tab:orange", "tab:blue")],
                 labels + ["headline orders: the summary's amplitudes (printed above the bars)", "other half orders"],
                 fontsize=7, loc="upper right")
        a.grid(True, lw=0.3)
    ax[-1, 0].set_xlabel("engine order (per crankshaft revolution)")
    fig.suptitle(f"{title}\nmean over {len(spans)} engine cycles of each cycle's order amplitude (crank-angle "
                 f"resampling, {cycle_stats.RESAMPLE} points per 720 deg), error bars: 95 % confidence half-width",
                 fontsize=9)
    fig.tight_layout()
    fig.savefig(path, dpi=110)
    plt.close(fig)
    return drawn


def path_position(g, x, y):
    """Arc length along the nominal chain path of the points (x, y) (nearest path sample)."""
    p = np.array(g["path"])
    L = g["pathLength"]
    s = np.linspace(0.0, L, len(p))
    d2 = (p[None, :, 0] - np.asarray(x)[:, None]) ** 2 + (p[None, :, 1] - np.asarray(y)[:, None]) ** 2
    return s[np.argmin(d2, axis=1)]


def unwrapped_path_position(pos, length):
    """Path positions pos in [0, length) made continuous across the path's origin."""
    steps = np.mod(np.diff(pos) + 0.5 * length, length) - 0.5 * length
    return pos[0] + np.concatenate([[0.0], np.cumsum(steps)])


def one_revolution(pos, length):
    """(first sample, last sample + 1, whole) of one chain revolution of a link at the path
    positions pos: from its first passage through the path's origin when a whole revolution
    follows it (whole), else from the first sample over at most one revolution."""
    u = unwrapped_path_position(pos, length)
    forward = u[-1] >= u[0]
    travelled = np.maximum.accumulate((u - u[0]) if forward else (u[0] - u))
    to_origin = (length - pos[0]) % length if forward else pos[0] % length
    i0, i1 = (int(i) for i in np.searchsorted(travelled, [to_origin, to_origin + length]))
    if i1 < len(pos):
        return i0, i1, True
    return 0, int(np.searchsorted(travelled, length)), False


def broken_at_wraps(s, length, *ys):
    """s and ys with a NaN inserted where s jumps across the path's origin (no line drawn across)."""
    cut = np.flatnonzero(np.abs(np.diff(s)) > 0.5 * length) + 1
    return [np.insert(np.asarray(v, float), cut, np.nan) for v in (s,) + ys]


def monitored_link(drive=None):
    """(index, number of links) of the drive's monitored link (measurement.monitoredLink, the
    FMU's default for its parameter link.index)."""
    description = drive_json(drive)
    return description.get("measurement", {}).get("monitoredLink", 0), description["chain"]["numberOfLinks"]


WRAP_SHADES = {"sprocket": "0.9", "guide": "#dde8f5"}  # the wraps' shades in link_cycle.png


def shade_wraps(ax, g, label_axis):
    """Shades the sprockets' and guides' wraps along the path, each labelled on label_axis."""
    guides = {guide["name"] for guide in g["guides"]}
    for seg in g["segments"]:
        if seg["kind"] != "wrap":
            continue
        colour = WRAP_SHADES["guide" if seg["element"] in guides else "sprocket"]
        for a in ax:
            a.axvspan(seg["start"], seg["start"] + seg["length"], color=colour, lw=0, zorder=0)
        label_axis.annotate(seg["element"], (seg["start"] + 0.5 * seg["length"], 1.0),
                            xycoords=("data", "axes fraction"), ha="center", va="bottom", fontsize=7)


def legends_and_grid(ax, length):
    """Every axis's legend with the wraps' shades, its grid, and the path 0..length as x range."""
    shades = [plt.Rectangle((0, 0), 1, 1, color=c) for c in WRAP_SHADES.values()]
    for a in ax:
        lines, labels = a.get_legend_handles_labels()
        a.legend(lines + shades, labels + [f"{kind} wrap" for kind in WRAP_SHADES], fontsize=7, loc="upper right",
                 ncol=2)
        a.grid(True, lw=0.3)
        a.set_xlim(0.0, length)


def link_cycle(path, d, rpm, title, t0=0.0, drive=None, fidelity=None):
    """One chain revolution of the monitored link around the drive, over its position along the
    chain path 0..L from the path's origin (the start of the crankshaft sprocket's wrap): its
    contact forces with sprockets and guides and its tensile force (the paper's Figure 12). A
    record without any contact force on the link (the span fidelity) says so instead of an empty
    panel. Returns the positions drawn [m]."""
    g = geometry(drive)
    length = g["pathLength"]
    sel = d["time"] >= t0
    pos = path_position(g, d["link.x"][sel], d["link.y"][sel])
    i0, i1, whole = one_revolution(pos, length)
    t = d["time"][sel][i0:i1]
    contact = {key: d[key][sel][i0:i1] for key in ("link.FnSprocket", "link.FnGuide")}
    has_contacts = any(np.any(d[key][sel] != 0.0) for key in contact)
    s, tension, sprocket, guide = broken_at_wraps(pos[i0:i1], length, d["link.F"][sel][i0:i1], *contact.values())
    fig, ax = plt.subplots(2 if has_contacts else 1, 1, figsize=(11, 6.8 if has_contacts else 4.4), sharex=True,
                           squeeze=False)
    ax = ax[:, 0]
    shade_wraps(ax, g, ax[0])
    if has_contacts:
        ax[0].plot(s, sprocket, lw=0.6, label="with sprockets")
        ax[0].plot(s, guide, lw=0.6, label="with guides")
        ax[0].set_ylabel("contact normal force [N]")
    ax[-1].plot(s, tension, lw=0.6, label="link tensile force")
    ax[-1].axhline(0.0, color="k", lw=0.6, label=f"0 N; {COMPRESSION_NOTE}")
    ax[-1].set_ylabel("link tensile force [N]")
    if not has_contacts:
        why = f": the {fidelity} fidelity models no link contacts" if fidelity else ""
        ax[-1].text(0.01, 0.97, f"no contact force on the link in this record{why}", transform=ax[-1].transAxes,
                    va="top", fontsize=8, bbox={"fc": "w", "ec": "0.6", "lw": 0.5})
    legends_and_grid(ax, length)
    ax[-1].set_xlabel(f"position along the chain path [m] (0 to its length {length:.4f} m, from the start of the "
                      f"crankshaft sprocket's wrap)")
    link, links = monitored_link(drive)
    span = t[-1] - t[0]
    what = (f"one chain revolution: {span * 1e3:.1f} ms = {span * rpm / 120.0:.2f} engine cycles" if whole else
            f"{span * 1e3:.1f} ms, less than a chain revolution (the record after the run-in is shorter)")
    fig.suptitle(f"{title}\nlink {link} of {links}, numbered from 0 (the drive's measurement.monitoredLink), {what}",
                 fontsize=10, y=0.995)
    fig.tight_layout()
    fig.savefig(path, dpi=110)
    plt.close(fig)
    return s[np.isfinite(s)]


def dominant_orders(t, x, rpm, count=3):
    """The largest spectral peaks (local maxima, so that the leakage of one order into its
    neighbouring bins is not listed as further orders) between order 0.75 and 40."""
    o, amp = order_spectrum(t, x, rpm)
    padded = np.concatenate(([-np.inf], amp, [-np.inf]))
    peak = (amp >= padded[:-2]) & (amp > padded[2:])
    keep = np.flatnonzero(peak & (o > 0.75) & (o <= 40))
    idx = keep[np.argsort(amp[keep])[::-1][:count]]
    return [(float(o[i]), float(amp[i])) for i in idx]


def cycle_columns(keys):
    """The headline keys in columns: the levels, then each output's order amplitudes."""
    orders = {k: key for key, ks in cycle_stats.order_keys(keys).items() for k in ks}
    columns = [[k for k in keys if k not in orders]]
    columns += [[k for k in keys if orders.get(k) == name] for name in dict.fromkeys(orders.values())]
    return [c for c in columns if c]


def cycle_panel(a, key, values, s):
    """One headline quantity's per-cycle values, its mean and the 95 % confidence band."""
    unit, v = values
    a.plot(np.arange(1, len(v) + 1), v, ".", ms=3, color="tab:blue", label="per cycle")
    a.axhline(s["mean"], color="k", lw=0.8, label="mean")
    a.axhspan(s["mean"] - s["ci95"], s["mean"] + s["ci95"], color="tab:orange", alpha=0.35, lw=0,
              label="95 % confidence band of the mean")
    a.set_title(f"{key}: {s['mean']:.4g} +- {s['ci95']:.3g} {unit}", fontsize=8)
    a.set_ylabel(f"[{unit}]", fontsize=8)
    a.tick_params(labelsize=7)
    a.grid(True, lw=0.3)


def cycle_statistics(path, per_cycle, summary, title, keys=None):
    """Per-cycle values of the headline quantities (default: every one of the summary) over the
    counted cycles, with their mean and 95 % confidence interval, one panel each in columns (levels,
    each output's order amplitudes): a run is stationary when the values scatter about a level line.
    Returns the keys drawn."""
    columns = cycle_columns(list(summary) if keys is None else list(keys))
    rows = max(len(c) for c in columns)
    fig, ax = plt.subplots(rows, len(columns), figsize=(5.0 * len(columns), 1.65 * rows + 1.4), squeeze=False)
    drawn = []
    for j, column in enumerate(columns):
        for i in range(rows):
            if i < len(column):
                cycle_panel(ax[i, j], column[i], per_cycle[column[i]], summary[column[i]])
                drawn.append(column[i])
            else:
                ax[i, j].set_visible(False)
        ax[len(column) - 1, j].set_xlabel("counted engine cycle", fontsize=8)
    fig.legend(*ax[0, 0].get_legend_handles_labels(), fontsize=8, loc="lower right")
    fig.suptitle(f"{title}: mean +- 95 % confidence half-width as in the summary", fontsize=10)
    fig.tight_layout(rect=(0.0, 0.0, 1.0, 1.0 - 0.3 / fig.get_figheight()))  # (the title above the first row's)
    fig.savefig(path, dpi=100)
    plt.close(fig)
    return drawn
