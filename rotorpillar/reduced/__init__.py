"""The reduced models: closed forms, averaging, rotor-pillar ODEs, integrators.

numpy, scipy and numba only; imports nothing above it (no fem3d, mesh,
commands): the 3D model's pillar modes come in as arguments.  Nothing is
imported here, so that ``import rotorpillar.reduced.pillar`` does not pay
for numba.

Where the paper's equations live (the first line of each function's
docstring carries the tag, so ``grep -rn "Eq. 19" rotorpillar`` lands there):

Eq. 1    rotorpillar.reduced.pillar.omega_euler_bernoulli
Eq. 2    rotorpillar.reduced.pillar.tip_mass_continuous
Eq. 3    rotorpillar.reduced.rotor_models.RotorStructure.energy
Eq. 4    rotorpillar.reduced.rhs.deriv_flat
Eq. 5    rotorpillar.reduced.system.omega_pair
Eq. 5    rotorpillar.reduced.system.omega_y
Eq. 6    rotorpillar.reduced.system.modal_vector
Eq. 7    rotorpillar.reduced.system.linear_modes
Eq. 19   rotorpillar.reduced.averaging.amplitude
Eq. 20   rotorpillar.reduced.averaging.resistance_increment
Eq. 21   rotorpillar.reduced.averaging.total_resistance
Eq. 22   rotorpillar.reduced.averaging.Characteristic
Eq. 23   rotorpillar.reduced.averaging.branch_is_stable
Eq. 24   rotorpillar.reduced.averaging.peak_resistance_ratio

The averaged Eq. 8-18 have no function of their own: their
stationary solution is Eq. 19 and 20.  Eq. 4's entry is the compiled
right-hand side the transients integrate (deriv_flat: Eq. 4 in a generic
form that also carries the modal model); ``rhs.eq4_rhs`` is Eq. 4 as
published in plain numpy, the reference tests/test_equation_index.py checks
it against.  Eq. 2's entry is the reduction the models use (the continuous
first mode; the chain applies the same energy balance to its 3D or beam
mode); ``pillar.tip_mass_lumped`` is Eq. 2 with n lumped masses, for the
paper's table.
"""

__all__ = [
    "accuracy",
    "averaging",
    "band",
    "batch",
    "base_forcing",
    "beam_fe",
    "bode",
    "capacity",
    "cylinder",
    "drive",
    "dp5",
    "excitation",
    "fixed_step",
    "integration",
    "internal_forces",
    "kernels",
    "margins",
    "models",
    "pillar",
    "pillar_modes",
    "reduction",
    "rhs",
    "rotor_models",
    "stationary",
    "system",
]
