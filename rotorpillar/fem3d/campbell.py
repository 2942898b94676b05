"""The Campbell diagram of the 3D model with the rotor on its top (`rotorpillar campbell --model fem3d`).

The system is rotorpillar.fem3d.spatial_system's: the 3D tube (the chain's
mesh, or the scene's) with the gondola as a rigid body on its rigid top,
the rotor on its shaft (lateral c2, axial, tilt; b2 and the tilt damping on
the motion relative to the gondola), the tip dashpot b1 in both horizontal
directions, ``pillar.damping_ratio`` on every mode of the loaded tube in
the band and past it (twice the band's top), and the gyroscopic matrix
J_C Omega on the spin axis' pitch and yaw.  At each speed Omega,

    (M s**2 + (C + Omega G) s + K) x = 0

for every eigenvalue with |s| up to the band's top (``band_top``), in real
arithmetic, over one factorisation of K (rotorpillar.fem3d.quadratic_eigen:
a block Arnoldi on the linearisation, each speed started from the last
speed's eigenvectors; SLEPc's PEP TOAR with ``method = "toar"``).

The branches are followed by their eigenvectors (rotorpillar.fem3d.
campbell_tracking: degenerate clusters aligned to the previous speed's
vectors first, then the MAC), named at the speed where they appear (the
rotor's share of the kinetic energy, else the tube's shape by
rotorpillar.fem3d.identify), and their whirl read at every speed.  Each
branch's frequency is the damped natural frequency Im(s), its damping
ratio -Re(s) / |s|, its logarithmic decrement 2 pi zeta / sqrt(1 -
zeta**2).  Critical speeds: where Omega equals a tracked (damped) branch's
frequency, linearly interpolated between two of the diagram's speeds;
"excited_by" from the mode's forward circular share of the rotor centre's
motion (static unbalance) or of its spin axis' (couple unbalance).

Before any meshing, the run's size is estimated (``estimate``) and refused
(``check_budget``) above the memory this process may use or a time limit.
"""

from __future__ import annotations

import math
import time

import numpy as np

from ..errors import InputError
from ..records import Record
from ..reduced.campbell import CampbellBranch, CampbellDiagram, CriticalSpeed, log_decrement
from ..reduced.spatial_modes import (
    AXIAL,
    BENDING_ACROSS,
    BENDING_IN_PLANE,
    BREATHING,
    OTHER,
    OVALLING,
    TORSION,
)
from ..scene import Scene
from . import campbell_tracking as tr
from .rotor_spatial import SpatialRotor

#: identify.py's kinds in the words of the spatial side (rotorpillar.reduced.spatial_modes.KINDS)
KIND_WORDS = {
    "bending_x": BENDING_IN_PLANE,
    "bending_y": BENDING_ACROSS,
    "torsion": TORSION,
    "axial": AXIAL,
    "ovalling": OVALLING,
    "breathing": BREATHING,
    "other": OTHER,
}
ROTOR_ON_SHAFT = "rotor on its shaft"
ROTOR_TILT = "rotor tilt"
#: a mode is the rotor's when the rotor holds more than this share of its kinetic energy
ROTOR_MODE = 0.5
#: the forward share of the mode's kinetic energy in the rotor's motion past which the unbalance
#: drives it: ~1e-2 for a bending mode that carries the rotor, ~1e-8 for an ovalling mode of the
#: rigid top
EXCITED = 1e-4
#: the time a 3D Campbell may take before it is refused (s)
MAX_SECONDS = 3600.0
#: seconds per speed per dof**1.5 (measured: 0.6-0.8 s a speed at 24,200 dofs, 2-core machine,
#: shared), and the first speed's extra (no start from a previous one), in speeds
SECONDS_PER_DOF15 = 2.0e-7
FIRST_SPEED = 4.0
#: basis columns of a speed, for the memory estimate (block method: ~60-200 columns, 2 n each)
BASIS_COLUMNS = 200


class CampbellEstimate(Record, frozen=True):
    """The size of a 3D Campbell diagram before it starts."""

    dofs: int
    """estimated unknowns of the tube, its top and the rotor (-)"""
    speeds: int
    """speeds solved (-)"""
    seconds: float
    """estimated wall time (s)"""
    bytes: float
    """estimated peak memory (bytes)"""


def estimate(scene: Scene, n_speeds: int, mesh=None) -> CampbellEstimate:
    """The run's size from the scene alone (no mesh built)."""
    from ..mesh import tube_params

    p = tube_params(scene.pillar, scene.mesh if mesh is None else mesh)
    dofs = int(p.estimated_dofs + 11)
    seconds = SECONDS_PER_DOF15 * dofs**1.5 * (n_speeds + FIRST_SPEED)
    need = p.estimated_bytes + 8.0 * 2 * dofs * BASIS_COLUMNS
    return CampbellEstimate(dofs, int(n_speeds), float(seconds), float(need))


def check_budget(est: CampbellEstimate, max_seconds: float = MAX_SECONDS) -> None:
    """Refuse (InputError, one line) a diagram above this process's memory or ``max_seconds``."""
    from ..provenance import check_memory

    what = f"the 3D Campbell diagram ({est.speeds} speeds on ~{est.dofs:,} DOFs)"
    check_memory(est.bytes, what, "use a coarser mesh")
    if not est.seconds <= max_seconds:
        raise InputError(
            f"{what} would take about {est.seconds / 60:.3g} min, more than {max_seconds / 60:.3g} min: "
            "ask fewer speeds or a coarser mesh"
        )


def campbell_fem3d(
    scene: Scene,
    speeds,
    *,
    band_top: float,
    mesh=None,
    damping_law: str = "gondola",
    method: str = "block",
    running_speed: float | None = None,
    max_seconds: float = MAX_SECONDS,
    comm=None,
    progress=None,
) -> CampbellDiagram:
    """The 3D Campbell diagram at ``speeds`` (rad/s) of the modes up to ``band_top`` (rad/s) on
    ``mesh`` (a scene Mesh section; default ``scene.mesh``); see the module text.  Collective."""
    from mpi4py import MPI

    from . import assemble_pillar
    from .quadratic_eigen import METHODS, solve_quadratic, solve_quadratic_toar, stiffness_factor
    from .spatial_system import assemble_system

    speeds = np.asarray(speeds, dtype=float)
    if speeds.ndim != 1 or len(speeds) < 2 or np.any(~np.isfinite(speeds)) or np.any(np.diff(speeds) <= 0):
        raise InputError("speeds: at least two, finite and ascending (rad/s)")
    if not (math.isfinite(band_top) and band_top > 0):
        raise InputError(f"band_top = {band_top!r}: must be finite and > 0 (rad/s)")
    if method not in METHODS:
        raise InputError(f"method = {method!r}: must be one of {', '.join(METHODS)}")
    if scene.modal.top_model != "rigid":
        raise InputError('the 3D Campbell hangs the rotor on the rigid top plate: modal.top_model must be "rigid"')
    if scene.modal.top_mass != "gondola":
        raise InputError('the 3D Campbell hangs the rotor on its shaft: modal.top_mass must be "gondola"')
    comm = MPI.COMM_WORLD if comm is None else comm
    say = progress or (lambda m: None)
    est = estimate(scene, len(speeds), mesh)
    check_budget(est, max_seconds)
    say(f"campbell (3D): {len(speeds)} speeds on ~{est.dofs:,} DOFs, about {est.seconds:.0f} s (estimate)")
    timings: dict[str, float] = {}
    t0 = time.perf_counter()
    model = assemble_pillar(scene, top=True, mesh=mesh, comm=comm)
    rotor = SpatialRotor.from_scene(scene)
    radius = float(band_top)
    system = assemble_system(
        model,
        rotor,
        tip_damping=scene.pillar.damping,
        damping_ratio=scene.pillar.damping_ratio,
        damped_up_to=2.0 * radius,
        damping_law=damping_law,
        tol=scene.modal.tolerance,
    )
    timings["assembly"] = time.perf_counter() - t0
    ksp = None
    try:
        t0 = time.perf_counter()
        ksp, factor = stiffness_factor(system.K) if method == "block" else (None, None)
        timings["factorisation"] = time.perf_counter() - t0
        t0 = time.perf_counter()
        tracker = _Tracker(system, comm)
        seeds, solves, worst = None, 0, 0.0
        for i, w in enumerate(speeds):
            if method == "block":
                q = solve_quadratic(system, float(w), radius, factor, tol=scene.modal.tolerance, seeds=seeds)
                seeds = q.seeds
            else:
                n_want = max(8, 2 * tracker.alive + 4)
                q = solve_quadratic_toar(system, float(w), radius, n_wanted=n_want, tol=scene.modal.tolerance)
            solves += q.solves
            worst = max(worst, float(np.max(q.backward_error, initial=0.0)))
            tracker.add(i, q.s, q.X)
            if progress and (i + 1) % max(1, len(speeds) // 10) == 0:
                say(f"campbell (3D): speed {i + 1} of {len(speeds)} ({w:.4g} rad/s)")
        timings["speeds"] = time.perf_counter() - t0
    finally:
        if ksp is not None:
            ksp.destroy()
        system.destroy()
        model.K.destroy()
        model.M.destroy()
    branches = tracker.branches(len(speeds))
    criticals = _critical_speeds(speeds, branches, tracker)
    p = model.params
    cells = f"{p.elements_around} x {p.elements_along} x {p.elements_through}"
    description = (
        f"3D tube ({cells} {model.params.cell_type} cells of degree {model.V.ufl_element().degree()}, "
        f"{system.size:,} unknowns) with the gondola on its rigid top and the rotor on its shaft"
        f"{'' if rotor.tilts else ' (tilting with the gondola)'}; "
        f"{'block Arnoldi on the linearisation' if method == 'block' else 'SLEPc PEP TOAR'}, "
        f"real arithmetic, one factorisation of K"
    )
    notes = (
        f"damping: b1 = {scene.pillar.damping:g} N*s/m at the top in both horizontal directions; "
        f"zeta = {scene.pillar.damping_ratio:.4g} on each of the loaded tube's {len(system.d)} modes below "
        f"{2 * radius:.4g} rad/s (modal, the ROM's); the shaft's b2 = {rotor.lateral_damping:g} N*s/m "
        + ("relative to the gondola" if damping_law == "gondola" else "relative to the ground (Eq. 4)"),
        f"timings: assembly {timings['assembly']:.3g} s, factorisation {timings['factorisation']:.3g} s, "
        f"{len(speeds)} speeds {timings['speeds']:.3g} s ({timings['speeds'] / len(speeds):.3g} s a speed, "
        f"{solves / len(speeds):.0f} right-hand sides a speed); largest backward error {worst:.2g}",
        "critical speeds: the root of the tracked damped branch's frequency minus Omega, linear "
        "between two of the diagram's speeds",
    )
    return CampbellDiagram(
        model="fem3d",
        speeds=speeds,
        modes=tuple(branches),
        critical_speeds=tuple(criticals),
        running_speed=running_speed,
        description=description,
        notes=notes,
        warnings=tuple(tracker.warnings),
    )


class _Tracker:
    """The branches across the speeds: values, vectors, names (module text)."""

    def __init__(self, system, comm):
        self.sys, self.comm = system, comm
        self.items: list[dict] = []
        self.warnings: list[str] = []
        self.rotor = system.rotor
        lo, hi = system.K.getOwnershipRange()
        self.lo, self.hi = lo, hi
        self.top_mass = float(system.model.top_block[0, 0])
        self.top_tilt = float(max(system.model.top_block[3, 3], system.model.top_block[5, 5]))

    @property
    def alive(self) -> int:
        return sum(1 for b in self.items if b["vec"] is not None)

    def gram(self, A, B):
        g = A.conj().T @ B
        return g if self.comm.size == 1 else self.comm.allreduce(g)

    def rows(self, X: np.ndarray) -> np.ndarray:
        """The plate's and the rotor's rows of X (6 + rotor dofs, k), on every rank."""
        first = self.sys.plate
        n = 6 + self.rotor.dofs
        out = np.zeros((n, X.shape[1]), complex)
        if self.lo <= first < self.hi:
            out = X[first - self.lo : first - self.lo + n].copy()
        return out if self.comm.size == 1 else self.comm.allreduce(out)

    def add(self, i: int, s: np.ndarray, X: np.ndarray) -> None:
        alive = [b for b in self.items if b["vec"] is not None]
        if alive:
            P = np.column_stack([b["vec"] for b in alive])
            for members in tr.clusters(s):
                X = tr.align_degenerate(P, X, members, self.gram)
            mac = np.abs(self.gram(P, X)) ** 2
            pairs = tr.assign(mac)
        else:
            pairs = []
        taken = set()
        for r, c in pairs:
            alive[r]["at"][i] = c
            taken.add(c)
        for b in alive:
            if i not in b["at"]:
                b["vec"] = None  # it left the band
        R = self.rows(X)
        energy = self._energies(X)
        new = [c for c in range(len(s)) if c not in taken]
        kinds = self._kinds(X, R, new, energy) if new else {}
        for c in new:
            self.items.append({"at": {i: c}, "vec": None, "kind": kinds[c][0], "dir": kinds[c][1], "vals": {}})
        for b in self.items:
            c = b["at"].get(i)
            if c is None:
                continue
            b["vec"] = X[:, c].copy()
            shares = self._shares(R[:, c])
            b["vals"][i] = (s[c], self._whirl(R[:, c]), (shares[0] / energy[c], shares[1] / energy[c]))

    def _energies(self, X: np.ndarray) -> np.ndarray:
        """x^H M x of each column (kg per unit**2): twice the mode's kinetic energy over w**2."""
        M = self.sys.M
        x, y = M.createVecRight(), M.createVecLeft()
        out = np.zeros(X.shape[1])
        for c in range(X.shape[1]):
            for part in (X[:, c].real, X[:, c].imag):
                x.setArray(np.ascontiguousarray(part))
                M.mult(x, y)
                out[c] += x.dot(y)
        x.destroy()
        y.destroy()
        return out

    def _whirl(self, r: np.ndarray) -> str:
        rot = self.rotor
        pitch, yaw = (9, 10) if rot.tilts else (3, 5)
        centre, axis = r[[6, 8]], np.array([-r[yaw], r[pitch]])
        t = tr.whirl(centre, axis, rot.mass, rot.diametral_inertia)
        size = rot.mass * np.sum(np.abs(centre) ** 2) + rot.diametral_inertia * np.sum(np.abs(axis) ** 2)
        plate = self.top_mass * np.sum(np.abs(r[[0, 2]]) ** 2) + self.top_tilt * (abs(r[3]) ** 2 + abs(r[5]) ** 2)
        if size <= tr.ROTOR_SHARE * (size + plate):
            return tr.whirl(r[[0, 2]], np.array([-r[5], r[3]]), self.top_mass, self.top_tilt)
        return t

    def _shares(self, r: np.ndarray) -> tuple[float, float]:
        """(m_C |a_f|**2 of the rotor centre's orbit, I_d |a_f|**2 of its spin axis') (kg, kg*m**2
        per unit**2): over x^H M x, the mode's share of forward rotor motion."""
        rot = self.rotor
        pitch, yaw = (9, 10) if rot.tilts else (3, 5)
        return rot.mass * tr.forward_share(r[6], r[8]), rot.diametral_inertia * tr.forward_share(-r[yaw], r[pitch])

    def _kinds(self, X: np.ndarray, R: np.ndarray, cols: list[int], energy: np.ndarray) -> dict[int, tuple[str, str]]:
        """(kind, direction words) of the new modes: the rotor's when it holds most of the kinetic
        energy, else the tube's shape (identify.describe_mode on rank 0)."""
        from . import identify

        model = self.sys.model
        out: dict[int, tuple[str, str]] = {}
        coords = model.gather_coordinates()
        rings = identify.rings_of(coords, model.params.height) if coords is not None else None
        for c in cols:
            phase = np.exp(-0.5j * np.angle(self._sum(np.sum(X[:, c] * X[:, c]))))  # the most real
            v, r = X[:, c] * phase, R[:, c] * phase
            m, Id = self.rotor.mass, self.rotor.diametral_inertia
            rotor_t = m * np.abs(r[6:9]) ** 2
            rotor_r = Id * np.abs(r[9:11]) ** 2 if self.rotor.tilts else np.zeros(2)
            if (rotor_t.sum() + rotor_r.sum()) > ROTOR_MODE * energy[c]:
                if rotor_r.sum() > rotor_t.sum():
                    out[c] = (ROTOR_TILT, "")
                else:
                    out[c] = (
                        ROTOR_ON_SHAFT,
                        ("in the rotor's plane", "along the spin axis", "vertical")[int(np.argmax(rotor_t))],
                    )
                continue
            u = self._tube_shape(v.real)
            desc = identify.describe_mode(None, u, rings) if u is not None else None
            desc = self.comm.bcast(desc, root=0)
            word = KIND_WORDS[desc.kind]
            if desc.kind == "ovalling":
                word = f"{OVALLING} n={desc.n_circumferential}"
            out[c] = (word, "")
        return out

    def _sum(self, a):
        return a if self.comm.size == 1 else self.comm.allreduce(a)

    def _tube_shape(self, part: np.ndarray) -> np.ndarray | None:
        """The tube's nodal displacement (nodes, 3) of a real system vector, on rank 0."""
        model = self.sys.model
        v = model.K.createVecRight()
        n_model = model.K.getLocalSize()[0]
        v.setArray(part[:n_model])
        g = model.gather_vector(model.tube_displacement(v))
        v.destroy()
        return None if g is None else g.reshape(-1, 3)

    def branches(self, n: int) -> list[CampbellBranch]:
        """The records, ascending by frequency where each branch appears, labelled."""
        items = sorted(self.items, key=lambda b: (min(b["at"]), abs(b["vals"][min(b["at"])][0])))
        counts: dict[str, int] = {}
        out = []
        for b in items:
            freq, zeta = np.full(n, np.nan), np.full(n, np.nan)
            whirl = ["none"] * n
            for i, (s, w, _) in b["vals"].items():
                freq[i], zeta[i], whirl[i] = s.imag, -s.real / abs(s), w
            key = b["kind"] + (f", {b['dir']}" if b["dir"] else "")
            counts[key] = counts.get(key, 0) + 1
            b["label"] = f"{key} {counts[key]}"
            out.append(
                CampbellBranch(
                    label=b["label"],
                    kind=b["kind"],
                    frequency=freq,
                    whirl=tuple(whirl),
                    log_decrement=log_decrement(zeta),
                    damping_ratio=zeta,
                )
            )
        self.items = items
        return out


def _critical_speeds(speeds: np.ndarray, branches: list[CampbellBranch], tracker: _Tracker) -> list[CriticalSpeed]:
    out = []
    for br, b in zip(branches, tracker.items):
        for speed, i in tr.crossings(speeds, br.frequency):
            j = i if i in b["vals"] else min(b["vals"], key=lambda k: abs(k - i))
            static, couple = b["vals"][j][2]
            excited = (
                "static unbalance" if static >= EXCITED else "couple unbalance" if couple >= EXCITED else "neither"
            )
            out.append(
                CriticalSpeed(
                    speed=float(speed),
                    label=br.label,
                    whirl=br.whirl[j],
                    excited_by=excited,
                    method="the tracked damped branch's frequency = Omega, linear between two speeds of the diagram",
                )
            )
    return sorted(out, key=lambda c: c.speed)
