"""The rigid rotor on its shaft above the 3D tube's rigid top plate, in space (numpy only).

Axes are the 3D model's (docs/fem3d.md): x horizontal in the rotor's plane,
y horizontal along the spin axis, z vertical.  The top plate's 6 dofs
(rotorpillar.fem3d.model) are q = (U_x, U_y, U_z, Theta_x, Theta_y,
Theta_z) = (in-plane, along the spin axis, vertical, pitch, roll, yaw) at
the top section's centre (0, 0, H).  The rotor adds 5:

    r = (x_r, y_r, z_r, phi_x, phi_z) = (in-plane, along the spin axis, vertical, pitch, yaw)

its centre's displacement and the tilt of its spin axis, the centre at
``height`` h above the top.  Its spin (roll about the spin axis) is the
prescribed speed Omega, not a dof.  With no ``tilt_stiffness`` (None: the
scene's default, the paper models no tilt) the rotor tilts with the
gondola: r = (x_r, y_r, z_r) only, its I_d and its gyroscopic moment act on
the plate's pitch and yaw (exactly, no penalty spring).

The shaft acts between the rotor and the gondola's point at the rotor's
centre, which moves with the plate: u_b = U + Theta x (0, 0, h) = (U_x +
h Theta_y, U_y - h Theta_x, U_z), its tilt (Theta_x, Theta_z).  The
relative motions d = D (q, r) (``shaft_links``): in-plane x_r - U_x - h
Theta_y and vertical z_r - U_z (the lateral stiffness c2 and damping b2
across the spin axis, the paper's c2 = c3 and b2 = b3), along the axis
y_r - U_y + h Theta_x (``axial_stiffness``, and b2: the same bearings, as
the spatial ROM has it), and the tilts phi_x - Theta_x, phi_z - Theta_z
(``tilt_stiffness``, ``tilt_damping``).  Stiffness and damping on (q, r) are D^T diag(k) D and
D^T diag(b) D: every force acts between rotor and gondola, so the pair
carries no net force from the shaft.  ``damping_law = "ground"`` puts b2 on
the rotor centre's absolute velocity instead (all three directions) (the paper's Eq. 4, which
anchors the shaft's dashpot to the ground: in an earthquake a skyhook),
kept for the comparison with Eq. 4 and the planar runs.

Spin direction.  The paper's unbalance force is m_C e Omega**2 (cos theta,
sin theta) along (in-plane, vertical): it turns from +x towards +z.  In the
right-handed (x, y, z) that is a rotation about -y: the rotor's angular
velocity is -Omega e_y and its angular momentum -J_C Omega e_y (plus
I_d times the tilt rates).  d/dt of it equals the moment: for the tilts
(phi_x, phi_z) (small rotations of the rotor's body about x and z),

    I_d phi_x'' + J_C Omega phi_z' = M_x,    I_d phi_z'' - J_C Omega phi_x' = M_z,

the gyroscopic matrix Omega G with G = J_C [[0, 1], [-1, 0]] on (phi_x,
phi_z) (skew: it does no work), or on the plate's (Theta_x, Theta_z) when the
rotor tilts with the gondola.  A steady moment M_x precesses the spin axis
at phi_z' = M_x / (J_C Omega): the angular momentum -J_C Omega e_y grows
along +x, the axis' far end (at -y) tips towards +x.
Forward whirl is an orbit that turns as the unbalance does: from +x towards
+z in the (x, z) plane (``whirl_direction``).

>>> rotor = rotor_example()
>>> D = shaft_links(rotor.height, tilt=True)
>>> D.shape, float(D[0, 4])
((5, 11), -0.5)
>>> K, C, M, G = rotor_blocks(rotor)
>>> bool(np.allclose(K @ np.r_[1, 2, 3, 0, 0, 0, 1, 2, 3, 0, 0], 0))  # a common translation stretches nothing
True
>>> [b.shape for b in rotor_blocks(replace(rotor, tilt_stiffness=None))]
[(9, 9), (9, 9), (9, 9), (9, 9)]
"""

from __future__ import annotations

from dataclasses import dataclass, replace  # noqa: F401  (replace: the doctest's)

import numpy as np

from ..scene import Scene

#: the rotor's dofs after the plate's, in this order (the first three when it tilts with the gondola)
ROTOR_DOFS = ("in_plane", "along_spin_axis", "vertical", "pitch", "yaw")
#: the plate's 6 dofs (rotorpillar.fem3d.model), in this order
PLATE_DOFS = ("in_plane", "along_spin_axis", "vertical", "pitch", "roll", "yaw")
#: the two laws of the shaft's damping b2
DAMPING_LAWS = ("gondola", "ground")


@dataclass(frozen=True)
class SpatialRotor:
    """The rigid rotor and its shaft (SI); see the module text for the dofs."""

    mass: float
    """m_C (kg)"""
    polar_inertia: float
    """J_C about the spin axis (kg*m**2)"""
    diametral_inertia: float
    """I_d about a diameter through its centre (kg*m**2)"""
    height: float
    """its centre above the top section's centre (m)"""
    eccentricity: float
    """e: the static unbalance's arm (m)"""
    couple_unbalance: float
    """U_c: the product of inertia that tilts its principal axis (kg*m**2)"""
    lateral_stiffness: float
    """c2 = c3: the shaft across the spin axis, in-plane and vertical (N/m)"""
    lateral_damping: float
    """b2 = b3 (N*s/m)"""
    axial_stiffness: float
    """the shaft along the spin axis (N/m)"""
    tilt_stiffness: float | None
    """the shaft against the rotor's tilt relative to the gondola (N*m/rad); None: rigid,
    the rotor tilts with the gondola"""
    tilt_damping: float
    """(N*m*s/rad)"""

    @classmethod
    def from_scene(cls, scene: Scene) -> SpatialRotor:
        """The scene's rotor and shaft, with the scene's defaults: I_d = J_C / 2 (a thin
        disc), the axial stiffness c2, the tilt rigid."""
        r, s = scene.rotor, scene.shaft
        Id = r.diametral_inertia
        ka = s.axial_stiffness
        return cls(
            r.mass,
            r.inertia,
            0.5 * r.inertia if Id is None else Id,
            r.height,
            r.eccentricity,
            r.couple_unbalance,
            s.stiffness,
            s.damping,
            s.stiffness if ka is None else ka,
            s.tilt_stiffness,
            s.tilt_damping,
        )

    @property
    def tilts(self) -> bool:
        """Whether the rotor tilts on its own shaft (pitch and yaw dofs of its own)."""
        return self.tilt_stiffness is not None

    @property
    def dofs(self) -> int:
        """the rotor's own dofs: 5, or 3 when it tilts with the gondola"""
        return 5 if self.tilts else 3


def shaft_links(height: float, tilt: bool) -> np.ndarray:
    """D (5 or 3, 6 + 5 or 3): the shaft's relative motions (in-plane, vertical, axial[, pitch,
    yaw]) of the rotor against the gondola's point at ``height`` (m), from (q plate, r rotor)."""
    n = 5 if tilt else 3
    D = np.zeros((n, 6 + n))
    r = 6 + np.arange(n)
    D[0, [0, 4, r[0]]] = -1.0, -height, 1.0  # x_r - (U_x + h Theta_y)
    D[1, [2, r[2]]] = -1.0, 1.0  # z_r - U_z
    D[2, [1, 3, r[1]]] = -1.0, height, 1.0  # y_r - (U_y - h Theta_x)
    if tilt:
        D[3, [3, r[3]]] = -1.0, 1.0  # phi_x - Theta_x
        D[4, [5, r[4]]] = -1.0, 1.0  # phi_z - Theta_z
    return D


def rotor_blocks(rotor: SpatialRotor, damping_law: str = "gondola"):
    """(K, C, M, G): the rotor's and its shaft's blocks on (q plate, r rotor), 6 + rotor.dofs
    square (SI); C by ``damping_law`` (module text), G per unit speed."""
    if damping_law not in DAMPING_LAWS:
        raise ValueError(f"damping_law must be one of {DAMPING_LAWS}")
    tilt, n = rotor.tilts, rotor.dofs
    D = shaft_links(rotor.height, tilt)
    c2 = rotor.lateral_stiffness
    k = [c2, c2, rotor.axial_stiffness]
    if rotor.tilt_stiffness is not None:
        k += [rotor.tilt_stiffness] * 2
    K = D.T @ np.diag(k) @ D
    # b2 across the spin axis and along it (the same bearings, as the spatial ROM has it)
    b2 = rotor.lateral_damping
    b = np.array([b2, b2, b2] + ([rotor.tilt_damping] * 2 if tilt else []))
    if damping_law == "gondola":
        C = D.T @ np.diag(b) @ D
    else:  # b2 on the rotor centre's absolute velocity (Eq. 4), the tilt's still relative
        A = np.zeros((3, 6 + n))
        A[0, 6], A[1, 8], A[2, 7] = 1.0, 1.0, 1.0
        C = A.T @ np.diag(b[:3]) @ A + D[3:].T @ np.diag(b[3:]) @ D[3:]
    M = np.zeros((6 + n, 6 + n))
    M[6:9, 6:9] = rotor.mass * np.eye(3)
    pitch, yaw = (9, 10) if tilt else (3, 5)  # the tilts: the rotor's own, or the plate's
    M[pitch, pitch] += rotor.diametral_inertia
    M[yaw, yaw] += rotor.diametral_inertia
    G = np.zeros((6 + n, 6 + n))
    G[pitch, yaw], G[yaw, pitch] = rotor.polar_inertia, -rotor.polar_inertia
    return K, C, M, G


def tilt_rows(rotor: SpatialRotor) -> tuple[int, int]:
    """The (pitch, yaw) of the rotor's spin axis among (q plate, r rotor): its own, or the
    plate's when it tilts with the gondola."""
    return (9, 10) if rotor.tilts else (3, 5)


def tilt_whirl_frequencies(rotor: SpatialRotor, speed: float) -> tuple[float, float]:
    """(backward, forward) tilt whirl frequencies of the rotor on a rigid support (rad/s):
    the roots of I_d w**2 -+ J_C Omega w - k_t = 0,
    w = -+J_C Omega / (2 I_d) + sqrt((J_C Omega / (2 I_d))**2 + k_t / I_d)."""
    if rotor.tilt_stiffness is None:
        raise ValueError("the rotor tilts with the gondola: no tilt whirl of its own")
    a = rotor.polar_inertia * speed / (2 * rotor.diametral_inertia)
    root = np.sqrt(a * a + rotor.tilt_stiffness / rotor.diametral_inertia)
    return float(root - a), float(root + a)


def whirl_direction(orbit_x: complex, orbit_z: complex, tolerance: float = 1e-3) -> str:
    """ "forward", "backward" or "none" for a complex amplitude (x, z) = (X, Z) e^{i w t}, w > 0.

    The orbit turns from +x to +z (with the unbalance: forward) when Im(conj(X) Z) < 0
    (X = 1, Z = -i: x = cos w t, z = sin w t); "none" when |Im(conj(X) Z)| is below
    ``tolerance`` of |X|**2 + |Z|**2 (a line, no turn).  The tilt's orbit is the spin
    axis' end, (-phi_z, phi_x) (module text).

    >>> whirl_direction(1.0, -1j), whirl_direction(1.0, 1j), whirl_direction(1.0, 0.5)
    ('forward', 'backward', 'none')
    """
    turn = -float(np.imag(np.conj(orbit_x) * orbit_z))
    size = float(abs(orbit_x) ** 2 + abs(orbit_z) ** 2)
    if size == 0.0 or abs(turn) <= tolerance * size:
        return "none"
    return "forward" if turn > 0 else "backward"


def rotor_example() -> SpatialRotor:
    """A rotor for the doctests (SI)."""
    return SpatialRotor(1600.0, 100.0, 50.0, 0.5, 0.002, 0.0, 0.4e6, 11e3, 0.4e6, 0.4e6, 0.0)
