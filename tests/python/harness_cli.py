"""The harness's command line as the tests run it (shared by test modules through conftest.py,
which puts this folder on the import path: pytest imports the test modules by path)."""
import subprocess
import sys

from harness import paths


def harness(*argv, cwd=None):
    """python -m harness with argv: (exit status, stdout, stderr)."""
    p = subprocess.run([sys.executable, "-m", "harness", *argv], capture_output=True, text=True, timeout=300,
                       cwd=cwd or paths.ROOT)
    return p.returncode, p.stdout, p.stderr


def one_error_line(status, stderr):
    """The single `error:` line of a refused command (asserted: exit status 2, one line, no traceback)."""
    assert status == 2, stderr
    lines = stderr.splitlines()
    assert len(lines) == 1 and lines[0].startswith("error: "), stderr
    return lines[0]
