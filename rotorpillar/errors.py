"""Errors a user can fix: the CLI prints them as one line and exits with 2."""


class InputError(ValueError):
    """Bad input: the message is one line naming the field and the allowed range."""


class ComputationError(RuntimeError):
    """A numerical tool failed (Gmsh, PETSc, SLEPc): one line saying which and how."""


class StageError(ComputationError):
    """A stage of `rotorpillar run` failed; the stages before it kept their outputs."""
