"""The commands behind the CLI, one module each.

A command is a function ``(scene, args, timings, context) -> (result, summary)``:
``result`` a JSON-ready dict written to ``<out>/<command>.json``, ``summary``
the readable text printed instead of the JSON.  ``context`` carries results
between the stages of ``rotorpillar run``.  Commands stay thin: the physics
lives in the library modules they call.
"""

import sys


def progress(message: str) -> None:
    """A stage line on stderr (stdout may carry --json)."""
    print(f"[rotorpillar] {message}", file=sys.stderr, flush=True)
