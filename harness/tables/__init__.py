"""The measured-input tables (camshaft load torques, crankshaft speed): the loader (tables), the
SYNTHESIZED tables shipped in data/ (data/README.md) and, for a second engine, in data_sport/
(data_sport/README.md), their generator (make_tables) and the valve-train model behind them
(valvetrain)."""
