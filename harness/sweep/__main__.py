"""python -m harness.sweep [options]: the same as python -m harness sweep."""
import sys

from harness.cli import main

sys.exit(main(["sweep"] + sys.argv[1:]))
