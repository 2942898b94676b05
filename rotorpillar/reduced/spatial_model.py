"""The machine in three dimensions: the pillar's modes in every direction, the rotor a rigid
body on its shaft, gyroscopic, driven, its reaction on the gondola.

Coordinates Z, all relative to the ground (the base moves them by its
inertia), then the spin angle theta:

- eta_1 .. eta_k: the pillar's modes with the gondola on top
  (SpatialPillarModes: bending in the rotor's plane and along the spin axis,
  torsion, axial, and the 3D model's ovalling), each moving the top plate by
  ``top[j]`` = (u_x, u_y, u_z, theta_x, theta_y, theta_z) per unit;
- the rotor centre in the rotor's plane (x, the paper's q2), along the spin
  axis (y), and, with a flexible tilt (``shaft.tilt_stiffness``), its pitch
  (about x) and yaw (about z); last the rotor centre's vertical (z, the
  paper's q3: the integrators' rotor-Y slot).

The shaft acts between the rotor centre and the gondola's point at the rotor's
height h: that point moves as u_top + theta_top x (0, 0, h), so in the rotor's
plane by B_x = u_x + h theta_y, along the spin axis by B_y = u_y - h theta_x,
vertically by B_z = u_z.  Energies (M the pillar's modal masses, e the
eccentricity, theta the spin angle, the unbalance turning from x towards z):

    T = 1/2 sum m_j eta_j'**2 + 1/2 m_C |r'|**2 + 1/2 I_d |a'|**2 + 1/2 J_C W**2
    P = 1/2 sum k_j eta_j**2 + 1/2 c2 (r_x - B_x - e cos theta)**2 + 1/2 c2 (r_z - B_z - e sin theta)**2
        + 1/2 c_a (r_y - B_y)**2 + 1/2 k_t |a - Theta|**2

with a the rotor's tilt and Theta = (theta_x, theta_z) the gondola's; with a rigid
tilt (no tilt spring, the default) a = Theta and I_d rides on the pillar's modes.
The spin vector is x cross z = -y (the paper's +Z: the unbalance turns from x to
z), so the rotor's angular momentum J_C W (a_z, -1, -a_x) gives the gyroscopic
moments I_d a_x'' + J_C W a_z' = M_x, I_d a_z'' - J_C W a_x' = M_z.  The motor's
torque Md turns the rotor; its reaction -Md on the gondola is +Md about y (roll),
which bends the pillar in the rotor's plane.  Damping: the scene's b1 as a dashpot
at the tip in both horizontal directions; the structural ratio zeta
(``pillar.damping_ratio``) on every pillar mode; the shaft's b2 on the rotor's
velocity relative to the gondola (``damping_law="gondola"``; "ground" keeps the
paper's, relative to the ground); the tilt damping on the tilt relative to the
gondola; the axial shaft takes b2 too (the same bearings).  The couple unbalance
U_c is a moment U_c W**2 turning with the rotor, its vector along the eccentricity.

``planes="planar"`` keeps the bending modes in the rotor's plane (tip-scaled), the
rotor in x and vertical, no tilt and no axial: with ``damping_law="ground"``,
no structural ratio and no motor reaction it is today's planar ROM
(rotorpillar.reduced.rotor_models.modal_model), the same matrices.

>>> from rotorpillar.scene import load_scene
>>> from rotorpillar.reduced.spatial_beam import beam_spatial_modes
>>> s = load_scene("paper")
>>> m = spatial_model(beam_spatial_modes(s.pillar, s.gondola, 3), s.rotor, s.shaft, s.pillar.damping)
>>> m.n, m.coordinates[-4:]
(16, ('eta12', 'rotor_x', 'rotor_axial', 'rotor_vertical'))
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np
from numpy.typing import NDArray
from scipy.linalg import eigh

from ..scene import Rotor, Shaft
from .drive import DriveSchedule
from .excitation import GroundMotion
from .ground3d import SpatialGroundMotion, ground_rows
from .rhs import Packed
from .spatial_modes import BENDING_IN_PLANE, SpatialPillarModes

Matrix = NDArray[np.float64]
DAMPING_LAWS = ("gondola", "ground")
PLANES = ("spatial", "planar")
#: What each output of ``SpatialStructure.outputs`` is, in words.
OUTPUTS = {
    "tip_x": "the top in the rotor's plane (m)",
    "tip_y": "the top along the spin axis (m)",
    "tip_z": "the top vertical (m)",
    "top_pitch": "the top's pitch, about x (rad)",
    "top_roll": "the top's roll, about y (rad)",
    "top_yaw": "the top's yaw, about z (rad)",
    "rotor_x": "the rotor centre in the rotor's plane (m)",
    "rotor_y": "the rotor centre along the spin axis (m)",
    "rotor_z": "the rotor centre vertical (m)",
    "rotor_pitch": "the rotor's pitch (rad)",
    "rotor_yaw": "the rotor's yaw (rad)",
    "shaft_x": "the shaft's deflection in the rotor's plane, without e cos theta (m)",
    "shaft_z": "the shaft's vertical deflection, without e sin theta (m)",
}


@dataclass(frozen=True, eq=False)
class SpatialStructure:
    """The spatial rotor-pillar model's matrices (see the module text); Z = q[:nz]."""

    name: str
    """"spatial" or "spatial:planar" """
    coordinates: tuple[str, ...]
    """names of Z, the rotor centre's vertical last"""
    mass: Matrix
    """(nz, nz) M (kg, kg*m**2)"""
    stiffness: Matrix
    """(nz, nz) K without the lateral shaft springs c2 (the integrators add them with the unbalance)"""
    damping: Matrix
    """(nz, nz) C"""
    gyroscopic: Matrix
    """(nz, nz) G per unit spin speed (skew): the moments W G Z' (kg*m**2)"""
    shaft: Matrix
    """(2, nz) d_x, d_v: the shaft's deflection in the rotor's plane and vertical is d.Z - e (cos, sin) theta"""
    reaction: NDArray[np.float64]
    """(nz,) generalised force of the motor's reaction on the gondola per unit torque (1/m, 1)"""
    couple: Matrix
    """(2, nz) b_c, b_s: the couple unbalance's moment U_c W**2 (b_c cos theta + b_s sin theta)"""
    ground: Matrix
    """(3, nz) -M r_d: the force per unit base acceleration along x, y, z (kg)"""
    outputs: dict[str, NDArray[np.float64]]
    """each OUTPUTS quantity as a row vector on Z"""
    shaft_stiffness: float
    """c2 = c3 (N/m)"""
    eccentricity: float
    """e (m)"""
    couple_unbalance: float
    """U_c (kg*m**2)"""
    rotor_mass: float
    """m_C (kg)"""
    rotor_inertia: float
    """J_C (kg*m**2)"""
    diametral_inertia: float
    """I_d (kg*m**2)"""
    modes: SpatialPillarModes
    """the pillar modes kept"""
    planes: str
    """"spatial" or "planar" """
    damping_law: str
    """"gondola" or "ground": what the shaft's b2 is relative to"""
    frame: str = "relative_to_ground"
    notes: tuple[str, ...] = field(default=())

    # ------------------------------------------------------------ sizes
    @property
    def nz(self) -> int:
        return len(self.coordinates)

    @property
    def nx(self) -> int:
        """the coordinates before the rotor's vertical (the integrators' X block)"""
        return self.nz - 1

    @property
    def n(self) -> int:
        """all coordinates: Z and theta"""
        return self.nz + 1

    @property
    def names(self) -> list[str]:
        return list(self.coordinates) + ["theta"]

    @property
    def tip(self) -> NDArray[np.float64]:
        """(nx,) the top in the rotor's plane on the X block (the transients' tip)"""
        out: NDArray[np.float64] = self.outputs["tip_x"][: self.nx]
        return out

    def stiffness_full(self) -> Matrix:
        """K + c2 (d_x d_x^T + d_v d_v^T): the stiffness with the shaft."""
        dx, dv = self.shaft
        out: Matrix = self.stiffness + self.shaft_stiffness * (np.outer(dx, dx) + np.outer(dv, dv))
        return out

    # ------------------------------------------------------------ the integrators' arrays
    def pack(
        self,
        drive: DriveSchedule,
        motion: GroundMotion | SpatialGroundMotion,
        prescribed_speed: bool = False,
        **overrides: float,
    ) -> Packed:
        """The tuple P of rotorpillar.reduced.rhs; ``motion`` a GroundMotion (one component, in the
        rotor's plane) or a SpatialGroundMotion (rotorpillar.reduced.ground3d)."""
        gpar, gtab, directions = ground_rows(motion)
        nz = self.nz
        Minv = np.zeros((self.n, self.n))
        Minv[:nz, :nz] = np.linalg.inv(self.mass)
        if not prescribed_speed:
            Minv[-1, -1] = 1.0 / self.rotor_inertia
        nc = len(directions)
        base = np.zeros((3 * nc + 4, nz))
        for i, d in enumerate(directions):
            base[3 * i + 2] = np.asarray(d) @ self.ground
        base[3 * nc] = self.outputs["tip_x"]
        base[3 * nc + 1] = self.reaction
        base[3 * nc + 2 : 3 * nc + 4] = self.couple
        scal = np.array(
            [
                overrides.get("shaft_stiffness", self.shaft_stiffness),
                overrides.get("eccentricity", self.eccentricity),
                overrides.get("couple_unbalance", self.couple_unbalance),
                drive.load_coefficient,
            ]
        )

        def c(a: NDArray[np.float64]) -> NDArray[np.float64]:
            return np.ascontiguousarray(a, dtype=float)

        return (
            c(Minv),
            c(self.stiffness),
            c(self.damping),
            c(self.gyroscopic),
            c(self.shaft),
            c(base),
            scal,
            c(drive.table()),
            c(gpar),
            c(gtab),
        )

    def energy(self, q: NDArray[np.float64], v: NDArray[np.float64]) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
        """Kinetic and potential energy per row of q, v (J), the rotor's spin included."""
        nz = self.nz
        Z, V, th, W = q[:, :nz], v[:, :nz], q[:, nz], v[:, nz]
        T = 0.5 * np.einsum("ti,ij,tj->t", V, self.mass, V) + 0.5 * self.rotor_inertia * W**2
        e = self.eccentricity
        P = (
            0.5 * np.einsum("ti,ij,tj->t", Z, self.stiffness, Z)
            + 0.5 * self.shaft_stiffness * (Z @ self.shaft[0] - e * np.cos(th)) ** 2
            + 0.5 * self.shaft_stiffness * (Z @ self.shaft[1] - e * np.sin(th)) ** 2
        )
        return T, P

    def undamped_modes_x(self) -> tuple[NDArray[np.float64], Matrix]:
        """omega (ascending, rad/s) and shapes of the structure at rest, shaft included."""
        lam, U = eigh(self.stiffness_full(), self.mass)
        return np.sqrt(np.maximum(lam, 0.0)), U

    def stiffest_frequency(self) -> float:
        """The highest undamped natural frequency (rad/s)."""
        return float(self.undamped_modes_x()[0].max())

    def fastest_rate(self) -> float:
        """The largest |eigenvalue| at rest (1/s): an explicit integrator's stability limit
        (reduced.explicit_limit)."""
        from .explicit_limit import first_order_rate

        return first_order_rate(self.mass, self.stiffness_full(), self.damping)

    def output(self, name: str, Z: NDArray[np.complex128] | NDArray[np.float64]) -> NDArray[np.complex128]:
        """An OUTPUTS quantity of states Z (..., nz)."""
        return np.asarray(np.asarray(Z) @ self.outputs[name], dtype=complex)


def _bending_in_plane_tip_scaled(modes: SpatialPillarModes) -> SpatialPillarModes:
    """The bending modes in the rotor's plane, each scaled to a unit tip deflection (as the
    planar ROM's PillarModes), the others as they are."""
    from ..provenance import replace

    s = np.ones(modes.count)
    idx = modes.of_kind(BENDING_IN_PLANE)
    s[idx] = modes.top[idx, 0]
    s = np.where(np.abs(s) < 1e-300, 1.0, s)

    def cols(a: NDArray[np.float64] | None) -> NDArray[np.float64] | None:
        return None if a is None else a / s

    out: SpatialPillarModes = replace(
        modes,
        modal_mass=modes.modal_mass / s**2,
        top=modes.top / s[:, None],
        participation=modes.participation / s[:, None],
        shear_x=cols(modes.shear_x),
        shear_y=cols(modes.shear_y),
        axial_force=cols(modes.axial_force),
        moment_x=cols(modes.moment_x),
        moment_y=cols(modes.moment_y),
        torque=cols(modes.torque),
        shapes=None if modes.shapes is None else modes.shapes / s[None, :, None],
    )
    return out


def spatial_model(
    modes: SpatialPillarModes,
    rotor: Rotor,
    shaft: Shaft,
    tip_damping: float,
    *,
    damping_ratio: float | None = None,
    damping_law: str = "gondola",
    planes: str = "spatial",
    drive_reaction: bool = True,
) -> SpatialStructure:
    """The spatial model on ``modes`` (see the module text).

    ``tip_damping`` is the pillar's b1 (N*s/m) at the tip in both horizontal
    directions; ``damping_ratio`` replaces the modes' structural ratio (-);
    ``damping_law`` "gondola" (the shaft's b2 relative to the gondola) or
    "ground" (the paper's); ``planes`` "spatial" or "planar" (the rotor's plane
    only); ``drive_reaction`` False leaves the motor's reaction off the gondola.
    """
    if damping_law not in DAMPING_LAWS:
        raise ValueError(f"damping_law must be one of {DAMPING_LAWS}")
    if planes not in PLANES:
        raise ValueError(f"planes must be one of {PLANES}")
    if planes == "planar":
        idx = modes.of_kind(BENDING_IN_PLANE)
        if len(idx) == 0:
            raise ValueError(f"{modes.source}: no bending mode in the rotor's plane")
        modes = modes.select(idx)
    modes = _bending_in_plane_tip_scaled(modes)
    zeta = modes.damping_ratio if damping_ratio is None else np.full(modes.count, float(damping_ratio))
    k = modes.count
    top = modes.top
    h = rotor.height
    flexible_tilt = shaft.tilt_stiffness is not None and planes == "spatial"
    names = [f"eta{j + 1}" for j in range(k)] + ["rotor_x"]
    if planes == "spatial":
        names.append("rotor_axial")
        if flexible_tilt:
            names += ["rotor_pitch", "rotor_yaw"]
    names.append("rotor_vertical")
    nz = len(names)
    at = {name: i for i, name in enumerate(names)}

    def unit(name: str) -> NDArray[np.float64]:
        u = np.zeros(nz)
        u[at[name]] = 1.0
        return u

    def on_eta(row: NDArray[np.float64]) -> NDArray[np.float64]:
        u = np.zeros(nz)
        u[:k] = row
        return u

    bearing = {
        "x": on_eta(top[:, 0] + h * top[:, 4]),
        "y": on_eta(top[:, 1] - h * top[:, 3]),
        "z": on_eta(top[:, 2]),
    }
    pitch, yaw = on_eta(top[:, 3]), on_eta(top[:, 5])
    I_d = rotor.inertia / 2 if rotor.diametral_inertia is None else rotor.diametral_inertia
    J = rotor.inertia
    M = np.zeros((nz, nz))
    M[:k, :k] = np.diag(modes.modal_mass)
    K = np.zeros((nz, nz))
    K[:k, :k] = np.diag(modes.modal_stiffness)
    C = np.zeros((nz, nz))
    C[:k, :k] = np.diag(2 * zeta * modes.omega * modes.modal_mass)
    G = np.zeros((nz, nz))
    tip_x, tip_y = on_eta(top[:, 0]), on_eta(top[:, 1])
    C += tip_damping * (np.outer(tip_x, tip_x) + np.outer(tip_y, tip_y))
    for name in ("rotor_x", "rotor_vertical") + (("rotor_axial",) if planes == "spatial" else ()):
        M[at[name], at[name]] = rotor.mass
    dx = unit("rotor_x") - bearing["x"]
    dv = unit("rotor_vertical") - bearing["z"]
    rel = [dx, dv]
    own = [unit("rotor_x"), unit("rotor_vertical")]
    b2 = shaft.damping
    if planes == "spatial":
        da = unit("rotor_axial") - bearing["y"]
        c_axial = shaft.stiffness if shaft.axial_stiffness is None else shaft.axial_stiffness
        K += c_axial * np.outer(da, da)
        rel.append(da)
        own.append(unit("rotor_axial"))
    for d in rel if damping_law == "gondola" else own:
        C += b2 * np.outer(d, d)
    couple = np.zeros((2, nz))
    if planes == "spatial":
        if flexible_tilt:
            assert shaft.tilt_stiffness is not None
            ax, az = unit("rotor_pitch"), unit("rotor_yaw")
            M[at["rotor_pitch"], at["rotor_pitch"]] = M[at["rotor_yaw"], at["rotor_yaw"]] = I_d
            for d in (ax - pitch, az - yaw):
                K += shaft.tilt_stiffness * np.outer(d, d)
                C += shaft.tilt_damping * np.outer(d, d)
        else:
            ax, az = pitch, yaw
            M += I_d * (np.outer(ax, ax) + np.outer(az, az))
        G = J * (np.outer(ax, az) - np.outer(az, ax))
        couple[0], couple[1] = ax, az
    ground = np.zeros((3, nz))
    for row, rotor_name in enumerate(("rotor_x", "rotor_axial", "rotor_vertical")):
        ground[row, :k] = -modes.participation[:, row]
        if rotor_name in at:
            ground[row, at[rotor_name]] = -rotor.mass
    reaction = on_eta(top[:, 4]) if drive_reaction else np.zeros(nz)
    outputs = {
        "tip_x": tip_x,
        "tip_y": tip_y,
        "tip_z": on_eta(top[:, 2]),
        "top_pitch": pitch,
        "top_roll": on_eta(top[:, 4]),
        "top_yaw": yaw,
        "rotor_x": unit("rotor_x"),
        "rotor_y": unit("rotor_axial") if "rotor_axial" in at else np.zeros(nz),
        "rotor_z": unit("rotor_vertical"),
        "rotor_pitch": couple[0] if planes == "spatial" else np.zeros(nz),
        "rotor_yaw": couple[1] if planes == "spatial" else np.zeros(nz),
        "shaft_x": dx,
        "shaft_z": dv,
    }
    law = "relative to the gondola" if damping_law == "gondola" else "relative to the ground (the paper's)"
    notes = (
        f"{k} pillar modes ({modes.source}), {'both planes, torsion, axial' if planes == 'spatial' else 'the rotor plane only'}",
        f"damping: b1 = {tip_damping:g} N*s/m at the tip in both horizontal directions; structural ratio "
        f"{float(np.max(zeta)) if k else 0.0:.4g} on every pillar mode; b2 = {b2:g} N*s/m on the rotor {law}",
        "rotor tilt: "
        + (
            f"on its own spring {shaft.tilt_stiffness:g} N*m/rad"
            if flexible_tilt
            else ("with the gondola (no tilt spring stated)" if planes == "spatial" else "none (planar)")
        ),
        f"motor reaction on the gondola: {'on' if drive_reaction else 'off'}",
    )
    return SpatialStructure(
        name="spatial" if planes == "spatial" else "spatial:planar",
        coordinates=tuple(names),
        mass=M,
        stiffness=K,
        damping=C,
        gyroscopic=G,
        shaft=np.vstack([dx, dv]),
        reaction=reaction,
        couple=couple,
        ground=ground,
        outputs=outputs,
        shaft_stiffness=shaft.stiffness,
        eccentricity=rotor.eccentricity,
        couple_unbalance=rotor.couple_unbalance if planes == "spatial" else 0.0,
        rotor_mass=rotor.mass,
        rotor_inertia=rotor.inertia,
        diametral_inertia=float(I_d),
        modes=modes,
        planes=planes,
        damping_law=damping_law,
        notes=notes,
    )


def whirl_ratio(x: complex, z: complex) -> float:
    """How circular and which way an orbit x = Re(X e^{i w t}), z = Re(Z e^{i w t}) turns in
    the plane normal to the spin axis: +1 a circle turning from x towards z (with the spin:
    forward), -1 against it (backward), 0 a line (-).

    >>> whirl_ratio(1, -1j), whirl_ratio(1, 1j), whirl_ratio(1, 0.5)
    (1.0, -1.0, 0.0)
    """
    norm = abs(x) ** 2 + abs(z) ** 2
    return 0.0 if norm == 0 else float(-2 * (np.conj(x) * z).imag / norm) + 0.0


def rigid_support_modes(stiffness: float = 1e12) -> SpatialPillarModes:
    """One axial mode of a support that hardly moves (a 1 kg top on ``stiffness`` N/m): with it
    the spatial model is a rigid rotor on its shaft on a rigid support (the tests' reference)."""
    top = np.zeros((1, 6))
    top[0, 2] = 1.0
    return SpatialPillarModes(
        omega=np.array([math.sqrt(stiffness)]),
        kind=("axial",),
        modal_mass=np.array([1.0]),
        top=top,
        participation=np.array([[0.0, 0.0, 1.0]]),
        total_mass=np.array([1.0, 1.0, 1.0]),
        damping_ratio=np.zeros(1),
        source="rigid support",
    )


def tilt_example(tilt_stiffness: float = 2e4, tilt_damping: float = 0.0) -> SpatialStructure:
    """The paper's rotor (1.6 t, J_C = 100, I_d = 50 kg*m**2, c2 = 0.4e6 N/m, undamped) on a
    rigid support, its tilt on a spring ``tilt_stiffness`` (N*m/rad)."""
    rotor = Rotor(mass=1.6e3, inertia=100.0, eccentricity=0.002, diametral_inertia=50.0)
    shaft = Shaft(stiffness=0.4e6, damping=0.0, tilt_stiffness=tilt_stiffness, tilt_damping=tilt_damping)
    return spatial_model(rigid_support_modes(), rotor, shaft, 0.0, damping_ratio=0.0)
