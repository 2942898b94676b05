"""The compiled kernels of the transients, in one namespace (rotorpillar.reduced.integration uses it).

- rotorpillar.reduced.rhs: the rotor-structure model's right-hand side
  ``deriv_flat`` on the model flattened by ``flatten``, its Jacobians, the
  ground motion and drive schedule, the status codes;
- rotorpillar.reduced.dp5: the adaptive Dormand-Prince 5(4) ``dp5_solve``
  and ``dp5_batch``;
- rotorpillar.reduced.fixed_step: ``genalpha_solve`` (Newmark, HHT,
  Chung-Hulbert, parameters by ``genalpha_parameters``) and ``cd_solve``
  (central difference).
"""

from .dp5 import dp5_batch, dp5_solve
from .fixed_step import cd_solve, genalpha_parameters, genalpha_solve
from .rhs import (
    MAX_STEPS,
    N_WORK,
    NEWTON_FAILED,
    NOT_FINITE,
    OK,
    STEP_TOO_SMALL,
    deriv_flat,
    flatten,
    jac_first_order,
    jacobians,
    rhs_first_order,
    shaft_deflection_into,
)

__all__ = [
    "MAX_STEPS",
    "NEWTON_FAILED",
    "NOT_FINITE",
    "N_WORK",
    "OK",
    "STEP_TOO_SMALL",
    "cd_solve",
    "deriv_flat",
    "dp5_batch",
    "dp5_solve",
    "flatten",
    "genalpha_parameters",
    "genalpha_solve",
    "jac_first_order",
    "jacobians",
    "rhs_first_order",
    "shaft_deflection_into",
]
