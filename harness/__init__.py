"""Python side of the chain-drive project: runs, tables, plots, benchmarks."""
