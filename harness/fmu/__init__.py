"""ChainDrive.fmu from Python: fmpy's FMU2Slave for master loops (fmu), and the FMU in other
FMI 2 co-simulation importers (importers: fmpy, libcosim, ecos)."""
