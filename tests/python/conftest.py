"""Test helpers shared between test modules (harness_cli.py) are imported from this folder."""
import pathlib
import sys

sys.path.insert(0, str(pathlib.Path(__file__).parent))
