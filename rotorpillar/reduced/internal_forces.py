"""Internal forces of the pillar: shear V(z), bending moment M(z), axial force N(z).

Sign conventions (SI): at a section of height z, V and M are the force in X
and the y-moment about the section's centre that the part above exerts on
the part below; a tip pushed along +X by P gives V = P and M = P (H - z).
N is the axial force, **compression positive**.  The meridional stress at
the extreme fibre on the compressed side, also compression positive, is

    sigma = |M| c / I + N / A       (c the outer radius)

the beam stress a designer checks against yield and against shell buckling
(rotorpillar.reduced.capacity).  It is the largest |meridional stress| of
the section whenever N >= 0.

Dynamic V and M come by modal superposition (the mode displacement method):
M(z, t) = sum_j eta_j(t) M_j(z) with M_j the section resultants of mode j
per unit modal coordinate (``PillarModes.moment_shapes``).  Moments and
shears converge more slowly with the number of modes than the tip does (a
section force weights the higher modes' curvature), so ``force_truncation``
counts the modes the base moment needs for 1 % at every frequency of the
band, against a reference of every mode available plus the static share of the rest (exact
by equilibrium: a tip force P gives M(0) = P H, a base acceleration a the
inertia load of the whole pillar and its top mass).

N is static: self-weight above the section, the gondola and the rotor under
g = 9.80665 m/s**2, plus the rotor's vertical shaft force (-c2 d_y, the
shaft stretched upward unloads the tube), which the axially rigid pillar of
the reduced models carries to the base unchanged.

>>> z = np.array([0.0, 10.0, 20.0])
>>> (axial_force(z, 1000.0, 20.0, 500.0) / STANDARD_GRAVITY).tolist()
[20500.0, 10500.0, 500.0]
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

import numpy as np
from numpy.typing import ArrayLike, NDArray

from ..provenance import Record
from ..scene import Pillar
from .beam_fe import BaseSprings
from .pillar import TubeSection
from .pillar_modes import PillarModes
from .tower import first_moment_above, mass_above, section_at

#: g_n, the standard acceleration of gravity (m/s**2), ISO 80000-3
STANDARD_GRAVITY = 9.80665
#: share of the base moment's peak over the band the forces' modes must reach (-)
FORCE_TOLERANCE = 0.01


# --------------------------------------------------------------------------
# Pure formulas


def axial_force(
    z: ArrayLike, mass_per_length: float, height: float, top_mass: float, g: float = STANDARD_GRAVITY
) -> NDArray[np.float64]:
    """N(z) = g (m_rho (H - z) + m_top): the static axial force, compression positive (N)."""
    zs = np.asarray(z, dtype=float)
    force: NDArray[np.float64] = g * (mass_per_length * (height - zs) + top_mass)
    return force


def extreme_fibre_stress(moment: ArrayLike, axial: ArrayLike, section: TubeSection) -> NDArray[np.float64]:
    """|M| c / I + N / A: the meridional stress at the compressed extreme fibre,
    compression positive (Pa); c = D0 / 2."""
    c = section.outer_diameter / 2
    stress: NDArray[np.float64] = (
        np.abs(np.asarray(moment, dtype=float)) * c / section.second_moment
        + np.asarray(axial, dtype=float) / section.area
    )
    return stress


def superpose(coordinates: ArrayLike, shapes: ArrayLike) -> NDArray[np.float64]:
    """sum_j eta_j(t) S_j(z): (n_t, k) coordinates on (n_z, k) shapes -> (n_t, n_z)."""
    field: NDArray[np.float64] = np.asarray(coordinates, dtype=float) @ np.asarray(shapes, dtype=float).T
    return field


def static_resultants(
    z: ArrayLike, height: float, mass_per_length: float, top_mass: float
) -> dict[str, tuple[NDArray[np.float64], NDArray[np.float64]]]:
    """Exact static resultants (equilibrium) of the two loads of the transients.

    ``tip``: a unit force along +X at the tip, V = 1, M = H - z.
    ``base``: a unit ground acceleration along +X, whose relative-frame load
    is the inertia -m a (the pillar's and the top mass's):
    V = -(m_rho (H - z) + m_top), M = -(m_rho (H - z)**2 / 2 + m_top (H - z)).
    """
    zs = np.asarray(z, dtype=float)
    arm = height - zs
    return {
        "tip": (np.ones_like(zs), arm),
        "base": (-(mass_per_length * arm + top_mass), -(mass_per_length * arm**2 / 2 + top_mass * arm)),
    }


def cantilever_tip_statics(
    youngs_modulus: float,
    second_moment: float,
    shear_stiffness: float,
    height: float,
    mass_per_length: float,
    top_mass: float,
) -> dict[str, float]:
    """Static tip deflection of a Timoshenko cantilever (m): per unit tip force
    (H**3 / 3EI + H / kGA) and per unit ground acceleration along +X (the
    inertia of the pillar and of its top mass, hence negative)."""
    EI, H = youngs_modulus * second_moment, height
    per_force = H**3 / (3 * EI) + H / shear_stiffness
    uniform = mass_per_length * (H**4 / (8 * EI) + H**2 / (2 * shear_stiffness))
    return {"tip": per_force, "base": -(uniform + top_mass * per_force)}


def hermite_peak(t: ArrayLike, f: ArrayLike, dfdt: ArrayLike) -> tuple[float, float]:
    """(max |f|, its time) of a sampled signal with its derivative: the cubic
    Hermite interpolant's largest |value| on every interval (error O(h**4),
    where the samples alone miss up to 1 - cos(pi / samples per period))."""
    t, f, d = (np.asarray(a, dtype=float) for a in (t, f, dfdt))
    i = int(np.argmax(np.abs(f)))
    best, when = abs(float(f[i])), float(t[i])
    if len(t) < 2:
        return best, when
    h = np.diff(t)
    f0, f1, d0, d1 = f[:-1], f[1:], d[:-1] * h, d[1:] * h
    # p(s) = a s^3 + b s^2 + d0 s + f0 on s in [0, 1]
    a = 2 * f0 - 2 * f1 + d0 + d1
    b = -3 * f0 + 3 * f1 - 2 * d0 - d1
    qa, qb, qc = 3 * a, 2 * b, d0
    disc = np.maximum(qb**2 - 4 * qa * qc, 0.0)
    with np.errstate(divide="ignore", invalid="ignore"):
        r1 = np.where(np.abs(qa) > 1e-300, (-qb + np.sqrt(disc)) / (2 * qa), -qc / qb)
        r2 = np.where(np.abs(qa) > 1e-300, (-qb - np.sqrt(disc)) / (2 * qa), -qc / qb)
    for r in (r1, r2):
        ok = np.isfinite(r) & (r > 0) & (r < 1)
        if not ok.any():
            continue
        s = np.where(ok, r, 0.0)
        p = np.abs(((a * s + b) * s + d0) * s + f0)
        p[~ok] = 0.0
        j = int(np.argmax(p))
        if p[j] > best:
            best, when = float(p[j]), float(t[j] + s[j] * h[j])
    return best, when


# --------------------------------------------------------------------------
# Truncation: how many modes the section forces need


class TruncationRow(Record):
    """The k-mode superposition's error over the band, the worse of the two loads."""

    modes: int
    """k (-)"""
    tip: float
    """tip displacement's largest relative error over the band (-)"""
    base_moment: float
    """base moment's largest relative error over the band (-)"""
    base_shear: float
    """base shear's largest relative error over the band (-)"""


class ForceTruncation(Record):
    """How many modes the section forces need (the mode displacement method)."""

    band_top: float
    """highest frequency checked: the forcing band of the run (rad/s)"""
    tolerance: float
    """largest relative error allowed on the base moment in the band (-)"""
    modes_available: int
    """modes of the source, every one of which the reference uses (-)"""
    rows: tuple[TruncationRow, ...]
    """per k = 1 .. modes_available"""
    modes_needed_tip: int | None
    """fewest modes with the tip within the tolerance (None: not reached)"""
    modes_needed_base_moment: int | None
    """fewest modes with the base moment within the tolerance (None: not reached)"""
    modes_needed_base_shear: int | None
    """fewest modes with the base shear within the tolerance (None: not reached)"""
    statement: str
    """what was compared, in words"""

    @property
    def modes_for_forces(self) -> int:
        """The modes the forces use at least: the base moment's need (all when not reached)."""
        return self.modes_needed_base_moment or self.modes_available


def _pillar_response(
    pm: PillarModes, k: int, omega: NDArray[np.float64], damping: ArrayLike, load: ArrayLike
) -> NDArray[np.complex128]:
    """(n_w, k) modal coordinates of the first k modes under a harmonic load
    (per mode: 1 for a unit tip force, -L_j for a unit ground acceleration)."""
    m, kk = np.asarray(pm.modal_mass)[:k], np.asarray(pm.modal_stiffness)[:k]
    f = np.asarray(load, dtype=float)[:k]
    C = np.asarray(damping, dtype=float)[:k, :k]
    D = np.diag(kk)[None] - (omega**2)[:, None, None] * np.diag(m)[None] + 1j * omega[:, None, None] * C[None]
    eta: NDArray[np.complex128] = np.linalg.solve(D, np.broadcast_to(f.astype(complex), (len(omega), k))[..., None])[
        ..., 0
    ]
    return eta


def force_truncation(
    pm: PillarModes,
    band_top: float,
    damping: ArrayLike,
    height: float,
    mass_per_length: float,
    top_mass: float,
    tip_statics: dict[str, float] | UnitLoads,
    tolerance: float = FORCE_TOLERANCE,
    points: int = 600,
    base_statics: UnitLoads | None = None,
) -> ForceTruncation:
    """Errors of the first k modes on the tip, the base moment and the base shear.

    The pillar alone with its top mass, forced harmonically over [0,
    ``band_top``] by a unit tip force and by a unit ground acceleration
    (the two loads of the transients: the shaft's pull and the earthquake),
    damped by ``damping`` (k x k in the modal coordinates, e.g. the tip
    dashpot b1 on every pair).  The reference is every mode of ``pm`` plus
    the static share of the modes beyond them (``static_resultants``,
    ``tip_statics`` from ``cantilever_tip_statics``; a tower's or one on a
    foundation from ``tower_static_resultants`` at the base, ``base_statics``,
    and ``tip_statics_of_beam``): exact for the section forces by
    equilibrium, whatever the mode source.  The error at each
    frequency is taken over the reference's magnitude there, but not less
    than its static value: measured over the peak alone it let 3 modes pass
    a base shear that El Centro shows 3-7 % off (the record's energy lies
    between the resonances, where the missing modes' share is relatively
    large); this measure predicts that.
    """
    if not pm.has_resultants:
        raise ValueError("the pillar modes carry no section resultants")
    n = pm.count
    natural = np.asarray(pm.omega)
    omega = np.unique(np.r_[np.linspace(0.0, band_top, points), natural[natural <= band_top]])
    if not np.any(np.asarray(damping, dtype=float)[:n, :n]):
        # undamped (pillar.damping = 0): the response is infinite at a natural frequency,
        # where every truncation's error is 0/0: measured beside them, not on them
        omega = omega[np.min(np.abs(omega[:, None] - natural[None, :]), axis=1) > 1e-6 * max(band_top, 1.0)]
    i0 = int(np.argmin(np.abs(np.asarray(pm.section_heights))))
    M0, V0 = np.asarray(pm.moment_shapes)[i0], np.asarray(pm.shear_shapes)[i0]
    kk = np.asarray(pm.modal_stiffness)
    statics = base_statics or static_resultants(
        np.asarray(pm.section_heights)[i0 : i0 + 1], height, mass_per_length, top_mass
    )
    loads = {"tip": np.ones(n), "base": -np.asarray(pm.participation)}
    errors = np.zeros((n, 3))
    for name, f in loads.items():
        V_static, M_static = statics[name][0][0], statics[name][1][0]
        # the static share of the modes beyond the source's: exact minus the modes' static sum
        resid = (tip_statics[name] - np.sum(f / kk), M_static - np.sum(f * M0 / kk), V_static - np.sum(f * V0 / kk))
        eta = _pillar_response(pm, n, omega, damping, f)
        ref = (eta.sum(axis=1) + resid[0], eta @ M0 + resid[1], eta @ V0 + resid[2])
        # at each frequency against the response there, never less than the static one:
        # a transient (an accelerogram) weighs every frequency, not only the peaks
        scale = [np.maximum(np.maximum(np.abs(r), abs(r[0])), 1e-300) for r in ref]
        for k in range(1, n + 1):
            e = _pillar_response(pm, k, omega, damping, f)
            got = (e.sum(axis=1), e @ M0[:k], e @ V0[:k])
            for q in range(3):
                errors[k - 1, q] = max(errors[k - 1, q], float(np.max(np.abs(got[q] - ref[q]) / scale[q])))
    rows = tuple(TruncationRow(k + 1, *map(float, errors[k])) for k in range(n))
    need = [next((k + 1 for k in range(n) if errors[k, q] <= tolerance), None) for q in range(3)]
    statement = (
        f"the first k of {n} modes ({pm.source}) against all {n} plus the static share of "
        f"the rest, the pillar forced at its tip and at its base from 0 to "
        f"{band_top:.4g} rad/s; at each frequency, the error over the response there "
        "(never less than the static response)"
    )
    return ForceTruncation(float(band_top), float(tolerance), n, rows, need[0], need[1], need[2], statement)


def tip_dashpot(count: int, tip_damping: float) -> NDArray[np.float64]:
    """The modal damping matrix of a dashpot b1 at the tip (every pair: b1, tip = sum eta) (N*s/m)."""
    return np.full((count, count), float(tip_damping))


def modal_damping(pm: PillarModes, tip_damping: float) -> NDArray[np.float64]:
    """The modal model's damping of the pillar: its modal ratios, else the tip dashpot (N*s/m)."""
    if pm.damping_ratio is not None:
        return np.diag(2 * np.asarray(pm.damping_ratio) * pm.omega * pm.modal_mass)
    return tip_dashpot(pm.count, tip_damping)


# --------------------------------------------------------------------------
# A tower of cans: the same quantities with the section of each height


def tower_axial_force(
    pillar: Pillar, z: ArrayLike, top_mass: float, g: float = STANDARD_GRAVITY
) -> NDArray[np.float64]:
    """N(z) = g (mass of the tube above z + m_top), compression positive (N); the
    uniform tube's is ``axial_force``, to the last digit."""
    if pillar.is_uniform:
        return axial_force(z, section_at(pillar, 0.0).mass_per_length, pillar.height, top_mass, g)
    return g * (mass_above(pillar, z) + top_mass)


@dataclass(frozen=True, eq=False)
class UnitLoads:
    """A quantity under the transients' two unit loads: a tip force along +X and a ground
    acceleration along +X (``static_resultants``' and ``cantilever_tip_statics``' keys)."""

    tip: Any
    base: Any

    def __getitem__(self, load: str) -> Any:
        return getattr(self, load)


def tower_static_resultants(pillar: Pillar, z: ArrayLike, top_mass: float) -> UnitLoads:
    """``static_resultants`` with the tube's mass as it is along the height (exact by
    equilibrium): the base load's V = -(m above z + m_top), M = -(int_z^H m(s) (s - z) ds
    + m_top (H - z)); each a (V, M) pair of arrays at z (N, N*m)."""
    zs = np.atleast_1d(np.asarray(z, dtype=float))
    arm = pillar.height - zs
    return UnitLoads(
        (np.ones_like(zs), arm),
        (-(mass_above(pillar, zs) + top_mass), -(first_moment_above(pillar, zs) + top_mass * arm)),
    )


def tip_statics_of_beam(
    pillar: Pillar, top_mass: float, theory: str, elements: int, base: BaseSprings | None
) -> UnitLoads:
    """``cantilever_tip_statics`` of the beam model: the static tip deflection per unit tip
    force and per unit ground acceleration along +X (m), by the beam's own static solve
    (tapered or stepped, on the foundation's springs): exact for that model."""
    from .beam_fe import assemble
    from .pillar_modes import beam_line

    K, M = assemble(beam_line(pillar, elements), elements, theory, top_mass, 0.0, base)
    f_tip = np.zeros(K.shape[0])
    f_tip[-2] = 1.0
    r = np.zeros(K.shape[0])
    r[0::2] = 1.0
    tip = np.linalg.solve(K, np.column_stack([f_tip, -(M @ r)]))[-2]
    return UnitLoads(float(tip[0]), float(tip[1]))


class CanStress(Record):
    """The largest meridional stress of one can over a run, where and when it occurred."""

    can: int
    """the can's index from the base, 0 first (-)"""
    bottom: float
    """the can's lower end (m)"""
    top: float
    """the can's upper end (m)"""
    stress: float
    """largest |M| c / I + N / A over the can's sections, compression (Pa)"""
    height: float
    """where (m)"""
    time: float
    """when (s)"""
    axial_share: float
    """N / A over that stress there and then (EN 1993-1-6's C_x) (-)"""
    outer_diameter: float
    """D0 at that height (m)"""
    wall_thickness: float
    """t at that height (m)"""
    cone_angle: float
    """the can's half-angle beta, from the axis (rad)"""


def can_stresses(
    pillar: Pillar, t: ArrayLike, heights: ArrayLike, moment: ArrayLike, axial: ArrayLike
) -> tuple[CanStress, ...]:
    """Per can, the largest extreme-fibre stress |M| c / I + N / A over the sections at
    ``heights`` within it (its ends included, each with the can's own section there).

    ``moment`` and ``axial`` are (n_t, n_z) at ``heights`` (m), compression positive."""
    t, z = np.asarray(t, dtype=float), np.asarray(heights, dtype=float)
    Mz, Nz = np.abs(np.asarray(moment, dtype=float)), np.asarray(axial, dtype=float)
    out = []
    for i, seg in enumerate(pillar.segments()):
        tol = 1e-9 * pillar.height
        inside = np.nonzero((z >= seg.bottom - tol) & (z <= seg.top + tol))[0]
        if len(inside) == 0:
            continue
        zi = np.clip(z[inside], seg.bottom, seg.top)
        d0, d1 = np.asarray(seg.outer_diameter(zi), dtype=float), np.asarray(seg.inner_diameter(zi), dtype=float)
        d0, d1 = np.broadcast_to(d0, zi.shape), np.broadcast_to(d1, zi.shape)
        area = np.pi / 4 * (d0**2 - d1**2)
        inertia = np.pi / 64 * (d0**4 - d1**4)
        sigma = Mz[:, inside] * (d0 / 2) / inertia + Nz[:, inside] / area
        j, k = np.unravel_index(int(np.argmax(sigma)), sigma.shape)
        s = float(sigma[j, k])
        out.append(
            CanStress(
                i,
                seg.bottom,
                seg.top,
                s,
                float(zi[k]),
                float(t[j]),
                float(Nz[j, inside[k]] / area[k] / s) if s > 0 else 1.0,
                float(d0[k]),
                float((d0[k] - d1[k]) / 2),
                float(abs(np.arctan(seg.slope()))),
            )
        )
    return tuple(out)
