"""The chain CVT scene (paper example 4.1): its main job (job.py) and plots (plots.py)."""
