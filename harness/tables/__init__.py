"""The measured-input tables (camshaft load torques, crankshaft speed): the loader (tables), the
SYNTHESIZED tables shipped in data/ (data/README.md), their generator (make_tables) and the
valve-train model behind them (valvetrain)."""
