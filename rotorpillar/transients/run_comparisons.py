"""The comparisons `rotorpillar run` makes and the report shows (:data:`COMPARISONS`),
as `rotorpillar compare` arguments: ``commands/run.py`` builds its stages from
them, the report's hints repeat them."""

from __future__ import annotations

COMPARE_COMMAND = "compare"

#: The comparisons `rotorpillar run` makes and the report shows: case -> the
#: arguments of `rotorpillar compare --case <case>` (``commands/run.py`` builds its stages
#: from these, the report's hints repeat them).  compare runs the scene's
#: excitation, so the earthquake sets the record: El Centro on the
#: physically consistent models (the modal ROM and the 3D full order), with
#: the speed-against-accuracy study of every model of the ladder; the run-up
#: puts the ROM beside the 3D full order too, over the window through its
#: resonances (rotorpillar.transients.window).
COMPARISONS = {
    # El Centro from 1 s after the start (the rotor whirling steadily before) over 9 s: its
    # strong motion and the tip's peak (2.6 s into the record on the paper's ROM) inside,
    # at 60 % of the 15 s the 3D run took with the record starting at 5 s
    "earthquake": (
        "--models",
        "modal,fem3d",
        "--pareto",
        "--set",
        "excitation.kind=record",
        "--set",
        "excitation.record=elcentro",
        "--set",
        "excitation.start=1",
        "--set",
        "full_order.earthquake_duration=9",
    ),
    "runup": ("--models", "modal,fem3d"),
}


def comparison_command(case: str) -> str:
    """The compare command line (without the scene) for one of :data:`COMPARISONS`.

    >>> comparison_command("runup")
    'compare --case runup --models modal,fem3d'
    """
    return " ".join((COMPARE_COMMAND, "--case", case, *COMPARISONS[case]))


def comparison_models(case: str) -> list[str]:
    """The models a comparison runs.

    >>> comparison_models("earthquake")
    ['modal', 'fem3d']
    """
    a = COMPARISONS[case]
    return a[a.index("--models") + 1].split(",")


def comparison_overrides(case: str) -> tuple[str, ...]:
    """The scene keys a comparison sets itself (its inputs differ from the
    scene there on purpose).

    >>> comparison_overrides("earthquake")
    ('excitation.kind', 'excitation.record', 'excitation.start', 'full_order.earthquake_duration')
    """
    a = COMPARISONS[case]
    return tuple(a[i + 1].split("=", 1)[0] for i, x in enumerate(a) if x == "--set")
