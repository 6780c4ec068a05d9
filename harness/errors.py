"""What a user gets wrong, as one line.

A UserError is a mistake in what the user gave: an option out of its range, a missing folder, a
field of a description file, a parameter the FMU refused. Its message is the whole report, one
line naming the option or field, the value and what is allowed; harness/cli.py prints it as
`error: MESSAGE` with exit status 2 and no traceback (--debug shows the traceback too). Any other
exception is a fault of the harness and keeps its traceback.
"""


class UserError(Exception):
    """A mistake in the user's input; str(error) is the one line that reports it."""


class ToolFailure(UserError, RuntimeError):
    """A command-line tool of the build (chaindrive-cvt, ...) that ended with an error: a bad input
    file or a failed run (RuntimeError for the callers that go on after a failed run)."""


def tool_failure(tool, stderr, limit=4):
    """The ToolFailure of a command-line tool: its message (stderr) in one line, the tool's own
    'TOOL: error: ' prefixes dropped, at most `limit` problems and the count of the others."""
    lines = [line.strip() for line in str(stderr).splitlines() if line.strip()]
    for prefix in (f"{tool}: error: ", f"{tool}: "):
        lines = [line[len(prefix):] if line.startswith(prefix) else line for line in lines]
    lines = [part for line in lines for part in line.split(" | ")]  # (the tools' own one-line lists)
    shown = lines[:limit] + ([f"and {len(lines) - limit} more"] if len(lines) > limit else [])
    return ToolFailure(f"{tool}: {' | '.join(shown) or 'failed without a message'}")


class MissingBuild(UserError, FileNotFoundError):
    """A file of the build (a tool, an FMU) that is not there: the build has not run yet."""
