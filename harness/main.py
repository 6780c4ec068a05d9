"""The main job: runs the default drive at a mean engine speed with crankshaft vibration and
camshaft load torques, writes the outputs, the plots, and prints a summary.

    python -m harness.main [--rpm 3000] [--cycles 4] [--integrator fixed-verlet] [--out results/]
"""
import argparse
import math
import pathlib

import numpy as np

from . import paths, plots, runs, signals


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--drive", help="drive description (default: the embedded default drive)")
    ap.add_argument("--rpm", type=float, default=3000.0, help="mean crankshaft speed [rpm]")
    ap.add_argument("--cycles", type=float, default=4.0, help="engine cycles (720 deg crank); the first is discarded")
    ap.add_argument("--integrator", default="fixed-verlet")
    ap.add_argument("--step", type=float, default=2e-6, help="fixed step [s]")
    ap.add_argument("--rtol", type=float, default=1e-5, help="relative tolerance of adaptive integrators")
    ap.add_argument("--out", default=str(paths.RESULTS), help="output directory")
    args = ap.parse_args(argv)

    out = pathlib.Path(args.out)
    out.mkdir(parents=True, exist_ok=True)
    cycle = 2.0 * 60.0 / args.rpm
    duration = args.cycles * cycle
    inputs = signals.write_inputs_csv(out / "inputs.csv", args.rpm, duration)
    csv = out / "outputs.csv"
    print(f"running {args.drive or 'the default drive'} at {args.rpm:g} rpm for {args.cycles:g} engine cycles "
          f"({duration * 1e3:.1f} ms) with {args.integrator} ...", flush=True)
    code, text, summary = runs.run(csv, rpm=args.rpm, duration=duration, integrator=args.integrator, step=args.step,
                                   rtol=args.rtol, inputs_csv=inputs, drive=args.drive, output_step=2e-5)
    if code != 0:
        print(text)
        raise SystemExit(f"the run failed: {summary.get('failure', 'see above')}")
    d = runs.read_csv(csv)
    t0 = cycle  # discard the first engine cycle (start transient)
    sel = d["time"] >= t0 - 1e-12
    title = f"default drive, {args.rpm:g} rpm, {args.integrator}"
    plots.drive_picture(out / "drive.png", args.drive)
    plots.time_histories(out / "time_histories.png", d, args.rpm, title)
    plots.spectra(out / "spectra.png", d, args.rpm, t0, title + " (after the first cycle)")
    plots.link_cycle(out / "link_cycle.png", d, args.rpm, title + ", one cycle of the monitored link", t0=t0, drive=args.drive)

    F = d["tensioner.F"][sel]
    orders_F = plots.dominant_orders(d["time"][sel], F, args.rpm)
    orders_phi = plots.dominant_orders(d["time"][sel], d["tensionGuide.phi"][sel], args.rpm)
    print("\nsummary (measured over engine cycles 2..%g)" % args.cycles)
    print(f"  tensioner force: mean {F.mean():.1f} N, peak-to-peak {F.max() - F.min():.1f} N "
          f"(min {F.min():.1f}, max {F.max():.1f})")
    print(f"  tight span: mean {np.nanmean(d['chain.Ftight'][sel]):.1f} N, max {np.nanmax(d['chain.Ftight'][sel]):.1f} N;"
          f" slack span: mean {np.nanmean(d['chain.Fslack'][sel]):.1f} N")
    print(f"  tension guide: mean {math.degrees(d['tensionGuide.phi'][sel].mean()):.3f} deg, peak-to-peak "
          f"{math.degrees(np.ptp(d['tensionGuide.phi'][sel])):.3f} deg")
    print("  dominant orders, tensioner force: " + ", ".join(f"{o:.2f} ({a:.1f} N)" for o, a in orders_F))
    print("  dominant orders, tension guide:  " + ", ".join(f"{o:.2f} ({math.degrees(a) * 1e3:.2f} mdeg)"
                                                           for o, a in orders_phi))
    print(f"  CPU time {summary['cpu']:.2f} s for {summary['simulated'] * 1e3:.1f} ms simulated: "
          f"{summary['cpu_per_sim_s']:.2f} CPU s per simulated s (real-time factor); {summary['steps']} steps")
    print(f"  outputs: {csv}\n  plots: {out / 'drive.png'}, {out / 'time_histories.png'}, {out / 'spectra.png'}, "
          f"{out / 'link_cycle.png'}")


if __name__ == "__main__":
    main()
