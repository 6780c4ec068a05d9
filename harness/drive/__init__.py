"""The drive: its description and assembled geometry (description) and the design of the default
drive (design)."""
