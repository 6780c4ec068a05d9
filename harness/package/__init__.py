"""The FMUs as users download them: cross-built binaries for every platform, sources, checks."""
