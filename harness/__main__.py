"""python -m harness COMMAND [options]: the harness's one command line (harness/cli.py)."""
import sys

from harness.cli import main

sys.exit(main())
