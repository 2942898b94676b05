"""Mesh convergence and speed versus accuracy: which model does a scene need?

A ladder of pillar models, each refined in steps, computes the bare tube's
first bending and first ovalling frequencies; each run records its DOFs,
wall time and peak memory and is cached on disk.  From the runs: reference
values by Richardson extrapolation, each run's error, the Pareto fronts of
error against cost, where each method fails, and the cheapest model that
meets a tolerance over the band the scene excites.

The rooms, bottom up:

- :mod:`.ladder`      the families of models and their rungs (:class:`Case`)
- :mod:`.compute`     what one run computes (closed forms, beams, shell, 3D)
- :mod:`.runner`      the run cache and its hash, the subprocess worker, time and memory
- :mod:`.richardson`  Richardson extrapolation, observed orders, Roache's error estimates
- :mod:`.selection`   errors per run, Pareto fronts, the band, the choice of a model
- :mod:`.failures`    where each method fails, in words
- :mod:`.result`      :class:`ConvergenceStudy`, what convergence.json holds, typed to its leaves
- :mod:`.study`       the whole study (:func:`study`) and the 3D mesh for `modal --tolerance`

``python -m rotorpillar.converge CASE.json RESULT.json`` is the subprocess
worker (``__main__``).  Submodules share names with their main function
(``ladder``, ``richardson``, ``failures``, ``study``): the package attribute
is the function; reach a module's other names with ``from .X import``.
"""

from .compute import compute_fe, compute_in_process
from .failures import case_degree, drop_aliases, failures, nyquist
from .ladder import (
    ALONG_PER_AROUND,
    AROUND_LEVELS,
    EULER_LEVELS,
    FAMILIES,
    N_MODES,
    ORDER_NOTES,
    QUANTITIES,
    SOLID_AROUND_LEVELS,
    SOLID_SWEEP_AROUND,
    SWEEP_ALONG,
    SWEEP_AROUND,
    TIMOSHENKO_LEVELS,
    Case,
    Family,
    estimated_dofs,
    estimated_seconds,
    ladder,
    solid_mesh,
    study_cases,
)
from .result import (
    ConvergenceRun,
    ConvergenceStudy,
    ExcitationBand,
    Extrapolation,
    FamilyExtrapolation,
    FamilyInfo,
    Fronts,
    ModalModelSelection,
    Mode,
    ModelSelection,
    OvallingAlias,
    ParetoFronts,
    ReferenceValue,
    RejectedRun,
    RichardsonCheck,
    RunBrief,
    StudyCounts,
)
from .richardson import GCI_SAFETY, family_extrapolations, family_series, reference_values, richardson
from .runner import CACHE_VERSION, UNAVAILABLE_EXIT, ModelUnavailable, case_key, run_point, run_study, worker
from .selection import (
    attach_errors,
    band_error,
    excitation_band,
    needed_quantities,
    pareto_front,
    reference_uncertainty,
    select_model,
)
from .study import StudyAnalysis, analyse, model_for_modal, study

__all__ = [
    # ladder
    "QUANTITIES",
    "AROUND_LEVELS",
    "ALONG_PER_AROUND",
    "SOLID_AROUND_LEVELS",
    "SWEEP_AROUND",
    "SOLID_SWEEP_AROUND",
    "SWEEP_ALONG",
    "EULER_LEVELS",
    "TIMOSHENKO_LEVELS",
    "N_MODES",
    "Family",
    "FAMILIES",
    "ORDER_NOTES",
    "Case",
    "ladder",
    "study_cases",
    "estimated_dofs",
    "estimated_seconds",
    "solid_mesh",
    # compute
    "compute_in_process",
    "compute_fe",
    # runner
    "CACHE_VERSION",
    "case_key",
    "ModelUnavailable",
    "UNAVAILABLE_EXIT",
    "worker",
    "run_point",
    "run_study",
    # richardson
    "GCI_SAFETY",
    "richardson",
    "family_series",
    "family_extrapolations",
    "reference_values",
    # selection
    "attach_errors",
    "pareto_front",
    "excitation_band",
    "reference_uncertainty",
    "needed_quantities",
    "band_error",
    "select_model",
    # failures
    "nyquist",
    "case_degree",
    "failures",
    "drop_aliases",
    # result and study
    "ConvergenceStudy",
    "ConvergenceRun",
    "ExcitationBand",
    "Extrapolation",
    "FamilyExtrapolation",
    "FamilyInfo",
    "Fronts",
    "ModalModelSelection",
    "Mode",
    "ModelSelection",
    "OvallingAlias",
    "ParetoFronts",
    "ReferenceValue",
    "RejectedRun",
    "RichardsonCheck",
    "RunBrief",
    "StudyCounts",
    "StudyAnalysis",
    "analyse",
    "study",
    "model_for_modal",
]
