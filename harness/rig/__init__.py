"""The hydraulic tensioner on the suppliers' bench: chaindrive-rig's loops (rig.py) and their
plots (plots.py)."""
