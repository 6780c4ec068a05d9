"""Studies of the solver: speed against accuracy on cycle statistics and the stability map of
every method (study, the command; methods, scenes, errors, stability, realtime, report), and the
divergence rate of twin runs (the chaos subpackage)."""
