"""Replicas: the timing drive's main job run K times from starts that differ only as far as the
chaos needs, and the cycle statistics of the ensemble (`python -m harness run --replicas K`,
`python -m harness bench-realtime --replicas K`).

Why: a run's confidence intervals (harness/cycle_stats.py) take its engine cycles as an AR(1)
sequence. Some statistics wander more slowly than that. At 6000 rpm with the hydraulic tensioner,
four 480-cycle replicas of plain Verlet at 0.625 us give guide peak-to-peaks from 0.313 to 0.353
deg, each +- 0.010 by its own interval (docs/study/hydraulic_steps.md). Independent runs see that
variation; the cycles of one run do not.

Replica k (k = 0 .. K-1) runs with its crankshaft-speed input times 1 + k PERTURBATION. The
factor lies far below anything an engine's speed is known to, and two runs that differ by it
separate by a factor e per 1.4 ms (docs/study/chaos.md), so the replicas are unrelated after the
run-in (at least 0.15 s). Replica 0 is the run itself.

The ensemble's statistic per quantity is the mean of the replicas' means. Its 95 % half-width is
the larger of two estimates:
- t_(0.975, K-1) s / sqrt(K), with s the standard deviation of the replicas' means: what
  independent runs show (it needs K >= 2);
- sqrt(sum h_k^2) / K, with h_k the replicas' own half-widths (`withinRuns`): what the runs' cycles
  say. This keeps a small ensemble whose few means happen to agree from claiming more than that.
summary.json keeps both estimates, the replicas' means and `spreadRatio`: the standard deviation
of the replicas' means over the standard error their own intervals give (h_k / 1.96). It is about 1
when a run's cycles vary as its interval assumes; with 4 replicas it exceeds 2 by chance in less
than 1 % of the ensembles (chi-square with 3 degrees of freedom), and the report names every
quantity where it does.
"""
import dataclasses
import json
import math

import numpy as np

from . import cycle_stats, job

PERTURBATION = 1e-9  # relative change of the crankshaft-speed input from one replica to the next
Z95 = 1.96           # a run's half-width over its standard error (its cycles are many)
FLAGGED_RATIO = 2.0  # spreadRatio beyond which the report names a quantity


def replica_config(config, k):
    """Replica k of a run's configuration: its input perturbed, its outputs in replica<k>/."""
    return dataclasses.replace(config, speed_perturbation=k * PERTURBATION, replicas=1,
                               out=config.out / f"replica{k}")


def combine_quantity(stats):
    """The ensemble's statistic of one quantity from the replicas' ({mean, ci95, cycles, unit} each)."""
    means = np.array([s["mean"] for s in stats], float)
    k = len(means)
    within = math.sqrt(sum(s["ci95"] ** 2 for s in stats)) / k
    between = ratio = math.nan
    if k >= 2:  # (independent runs: no autocorrelation to correct for)
        between = cycle_stats.student_half_width(means, float(k))
        ratio = float(np.std(means, ddof=1)) / (within * math.sqrt(k) / Z95) if within > 0 else math.nan
    half = max(between, within) if not math.isnan(between) else within
    return {"mean": float(means.mean()), "ci95": half, "cycles": int(sum(s["cycles"] for s in stats)),
            "unit": stats[0]["unit"], "replicas": k, "betweenRuns": between, "withinRuns": within,
            "spreadRatio": ratio, "replicaMeans": [float(m) for m in means]}


def combine(summaries):
    """The ensemble's summary (the schema of summary.json, with the fields of combine_quantity)
    from the replicas' summaries: the quantities all of them have."""
    keys = [key for key in summaries[0] if all(key in s for s in summaries[1:])]
    return {key: combine_quantity([s[key] for s in summaries]) for key in keys}


def report(summary):
    """Prints the ensemble's statistics, and where the spread between the replicas exceeds what
    their own intervals say."""
    k = next(iter(summary.values()))["replicas"]
    print(f"\nensemble of {k} replicas: mean of the replicas' means +- the 95 % half-width (the larger of the spread "
          f"between the replicas and their own intervals)")
    for key, s in summary.items():
        flag = (f"  (the replicas scatter {s['spreadRatio']:.1f} x as much as their own intervals say)"
                if s["spreadRatio"] > FLAGGED_RATIO else "")
        print(cycle_stats.format_line(key, s) + flag)


def run(config):
    """The main job's replicas into config.out/replica<k>/, the ensemble's summary.json and
    run.json (every replica's run.json) in config.out; exit status: the worst of the replicas'."""
    status, summaries, runs = 0, [], []
    for k in range(config.replicas):
        replica = replica_config(config, k)
        print(f"\n== replica {k + 1} of {config.replicas}")
        status = max(status, job.run(replica))
        summaries.append(json.loads((replica.out / "summary.json").read_text()))
        runs.append(json.loads((replica.out / "run.json").read_text()))
    summary = combine(summaries)
    job.write_summary(config.out, summary, {"replicas": config.replicas, "perturbation": PERTURBATION, "runs": runs})
    report(summary)
    print(f"  outputs: {config.out / 'summary.json'}, {config.out / 'run.json'}, replica0 .. "
          f"replica{config.replicas - 1}/")
    return status
