"""Design studies: many runs of the reduced models over a product of scene keys, on Dask.

The rooms, bottom up:

- :mod:`.axes`      ``--vary`` parsed and checked; the product of the axes; a run's scene
- :mod:`.batch`     one batch on a worker: runs sharing a model in one compiled batch loop
- :mod:`.boundary`  the capture boundary: averaging theory and exact linear, and as found
- :mod:`.result`    :class:`StudyResult` and :class:`StudyRun` (study.json)
- :mod:`.study`     :func:`design_study`: plan, cache, executor, progress, study.csv

The executor itself (a Dask LocalCluster or a scheduler's address) is
:mod:`rotorpillar.executor`, shared with the convergence study.
"""

from .axes import Axis, parse_axes, parse_vary, points
from .result import StudyResult, StudyRun
from .study import BATCH_RUNS, design_study, plan, study_csv

__all__ = [
    "Axis",
    "parse_axes",
    "parse_vary",
    "points",
    "StudyResult",
    "StudyRun",
    "BATCH_RUNS",
    "design_study",
    "plan",
    "study_csv",
]
