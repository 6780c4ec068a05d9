"""Python side of the chain-drive project: the main job, studies, benchmarks, tables, plots.

One command line with subcommands: `python -m harness run|study|chaos|bench|bench-lcp|tables|
design-drive|picture` (harness/cli.py; `python -m harness --help` lists them).

Subpackages by concern:
  fmu/     ChainDrive.fmu from Python (fmpy's FMU2Slave) and in other importers (libcosim, ecos)
  tables/  the measured-input tables: loader, the SYNTHESIZED tables (data/) and their generator
           with the valve-train model
  study/   the work-precision and stability study, and the divergence-rate (chaos) study
  bench/   benchmarks: integrators of the solver, the LCP solver against Siconos
  plots/   the plots engineers read and the drive picture
  drive/   the drive description and the design of the default drive
Modules: job (the main job), cycle_stats (statistics over engine cycles), runs (runs of the
solver alone, chaindrive-run), paths (the repository, the build directory, the results).
"""
