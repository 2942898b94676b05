"""Errors a user can fix: the CLI prints them as one line and exits with 2; and the
interrupts a command received (the CLI's signal handlers record them, any layer may ask).
"""

import signal


class InputError(ValueError):
    """Bad input: the message is one line naming the field and the allowed range."""


class ComputationError(RuntimeError):
    """A numerical tool failed (Gmsh, PETSc, SLEPc): one line saying which and how."""


class StageError(ComputationError):
    """A stage of `rotorpillar run` failed; the stages before it kept their outputs."""


class Terminated(KeyboardInterrupt):
    """SIGTERM: stop as on Ctrl-C (a running stage's process is killed with us)."""


#: The signals received, in order (rotorpillar.cli's handlers append): a library that
#: calls back into Python (VTK's observers, a C loop) may catch the exception the handler
#: raised and carry on; the command is stopped at its end all the same (``stopped``), and
#: sooner where a loop waits on other processes (the report's render workers).
RECEIVED: list[int] = []


def stopped() -> None:
    """Raise the interrupt a library swallowed (``RECEIVED``): the command's result is not
    written, and the exit is 130 or 143 as if it had propagated."""
    if RECEIVED:
        raise Terminated() if RECEIVED[-1] == signal.SIGTERM else KeyboardInterrupt()
