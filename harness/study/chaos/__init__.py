"""The divergence-rate study: twin runs that differ by one rounding, per damping setting (chaos,
the command; twins: the runs; analysis: the measures; charts; report; damping: the damping values
against the literature)."""
