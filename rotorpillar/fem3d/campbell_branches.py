"""The 3D Campbell diagram's branches: each mode followed across the speeds, named, its whirl read.

rotorpillar.fem3d.campbell feeds ``BranchTracker.add`` the eigenpairs of
each speed (rotorpillar.fem3d.quadratic_eigen); the tracker

- aligns each degenerate cluster with the previous speed's vectors, then
  assigns the previous branches to this speed's modes by the largest MAC
  (rotorpillar.fem3d.campbell_tracking);
- names a mode where its branch starts, in the spatial ROM's words
  (rotorpillar.reduced.spatial_linear): the rotor's, by the coordinate that
  holds most of its kinetic energy, when the rotor holds more than half of
  it ("rotor on its shaft": in-plane and vertical; "rotor along the spin
  axis"; "rotor tilt"), else the tube's shape (rotorpillar.fem3d.identify,
  on MPI rank 0: bending in either plane, torsion, axial, ovalling n, ...);
- reads every mode's whirl from the rotor's orbit (its centre's and its
  spin axis', weighted by m_C and I_d; the spatial ROM's rule).

``branches`` makes the records: frequency Im(s), damping ratio -Re(s) / |s|,
log decrement, whirl per speed (NaN and "none" where the branch is out of
the band), each labelled "<kind> <n>", with " forward" or " backward" when
it turns one way only (as the ROM labels them).
"""

from __future__ import annotations

import numpy as np

from ..reduced.campbell import CampbellBranch, log_decrement
from . import campbell_tracking as tr
from .spatial_modes import kind_words

ROTOR_ON_SHAFT = "rotor on its shaft"
ROTOR_AXIAL = "rotor along the spin axis"
ROTOR_TILT = "rotor tilt"
#: a mode is the rotor's when the rotor holds more than this share of its kinetic energy
ROTOR_MODE = 0.5


class BranchTracker:
    """The branches across the speeds: values, vectors, names (module text)."""

    def __init__(self, system, comm, ops=None):
        from .quadratic_eigen import Products

        self.sys, self.comm = system, comm
        self.ops = Products(system, 0.0, None, comm) if ops is None else ops
        self.items: list[dict] = []
        self.rotor = system.rotor
        lo, hi = system.K.getOwnershipRange()
        self.lo, self.hi = lo, hi

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

    def energies(self, X: np.ndarray) -> np.ndarray:
        """x^H M x of each column (kg per unit**2)."""
        if not X.shape[1]:
            return np.zeros(0)
        MX = self.ops.mass(X.real.copy(order="F")) + 1j * self.ops.mass(X.imag.copy(order="F"))
        return np.real(self.ops._sum_cols(np.conj(X) * MX))

    def quadratic_forms(self, speed: float, Q: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """(q^H M q, q^H (C + speed G) q, q^H K q) of each column (complex)."""
        keep = self.ops.speed
        self.ops.speed = speed
        try:
            return self.ops.forms(Q)
        finally:
            self.ops.speed = keep

    def rayleigh(self, speed: float, Q: np.ndarray, guess: np.ndarray) -> np.ndarray:
        """Each column's eigenvalue by the quadratic Rayleigh quotient: the root of
        (q^H M q) s**2 + (q^H C q) s + q^H K q = 0 nearest the cluster's eigenvalues."""
        a, b, c = self.quadratic_forms(speed, Q)
        out = np.empty(Q.shape[1], complex)
        centre = np.mean(guess)
        for j in range(Q.shape[1]):
            roots = np.roots([a[j], b[j], c[j]])
            out[j] = roots[np.argmin(np.abs(roots - centre))]
        return out

    def whirl(self, r: np.ndarray, energy: float) -> str:
        """The whirl of a mode from its plate-and-rotor rows ``r`` (module text)."""
        rot = self.rotor
        pitch, yaw = (9, 10) if rot.tilts else (3, 5)
        centre, axis = r[[6, 8]], np.array([-r[yaw], r[pitch]])
        return tr.whirl(centre, axis, rot.mass, rot.diametral_inertia, energy)

    def add(self, i: int, speed: float, s: np.ndarray, X: np.ndarray) -> None:
        """The eigenpairs (s, X) of the ``i``-th speed (rad/s)."""
        alive = [b for b in self.items if b["vec"] is not None]
        pairs = []
        P = np.column_stack([b["vec"] for b in alive]) if alive else None
        for members in tr.clusters(s):
            if P is not None:
                X = tr.align_degenerate(P, X, members, self.gram)
            else:
                X = tr.untangle(X, members, self.rows, self.gram)
            s = s.copy()
            s[members] = self.rayleigh(speed, X[:, members], s[members])
        if P is not None:
            pairs = tr.assign(np.abs(self.gram(P, X)) ** 2)
        taken = set()
        for r, c in pairs:
            alive[r]["at"][i] = c
            taken.add(c)
        for b in alive:
            if i not in b["at"]:
                b["vec"] = None  # it left the band
        R = self.rows(X)
        energy = self.energies(X)
        new = [c for c in range(len(s)) if c not in taken]
        kinds = self.kinds(X, R, new, energy) if new else []
        for c, kind in zip(new, kinds):
            self.items.append({"at": {i: c}, "vec": None, "kind": kind, "vals": {}})
        for b in self.items:
            c = b["at"].get(i)
            if c is None:
                continue
            b["vec"] = X[:, c].copy()
            b["vals"][i] = (s[c], self.whirl(R[:, c], energy[c]))

    def kinds(self, X: np.ndarray, R: np.ndarray, cols: list[int], energy: np.ndarray) -> list[str]:
        """The kinds of the modes ``cols``, in their order (module text)."""
        from . import identify

        model = self.sys.model
        out: list[str] = []
        coords = model.gather_coordinates()
        rings = identify.rings_of(coords, model.params.height) if coords is not None else None
        m, Id = self.rotor.mass, self.rotor.diametral_inertia
        for c in cols:
            r = R[:, c]
            shares = {
                ROTOR_ON_SHAFT: m * (abs(r[6]) ** 2 + abs(r[8]) ** 2),
                ROTOR_AXIAL: m * abs(r[7]) ** 2,
                ROTOR_TILT: Id * (abs(r[9]) ** 2 + abs(r[10]) ** 2) if self.rotor.tilts else 0.0,
            }
            if sum(shares.values()) > ROTOR_MODE * energy[c]:
                out.append(max(shares, key=lambda k: shares[k]))
                continue
            v = X[:, c] * np.exp(-0.5j * np.angle(self._sum(np.sum(X[:, c] * X[:, c]))))  # the most real
            u = self._tube_shape(v.real)
            desc = identify.describe_mode(None, u, rings) if u is not None else None
            desc = self.comm.bcast(desc, root=0)
            out.append(kind_words(desc.kind, desc.n_circumferential))
        return out

    def _sum(self, a):
        return a if self.comm.size == 1 else self.comm.allreduce(a)

    def _tube_shape(self, part: np.ndarray) -> np.ndarray | None:
        """The tube's nodal displacement (nodes, 3) of a real system vector, on rank 0."""
        model = self.sys.model
        v = model.K.createVecRight()
        v.setArray(part[: model.K.getLocalSize()[0]])
        g = model.gather_vector(model.tube_displacement(v))
        v.destroy()
        return None if g is None else g.reshape(-1, 3)

    def branches(self, n: int) -> list[CampbellBranch]:
        """The records, ascending by frequency where each branch starts, labelled (module text)."""
        self.items.sort(key=lambda b: (min(b["at"]), abs(b["vals"][min(b["at"])][0])))
        counts: dict[str, int] = {}
        out = []
        for b in self.items:
            freq, zeta = np.full(n, np.nan), np.full(n, np.nan)
            whirl = ["none"] * n
            for i, (s, w) in b["vals"].items():
                freq[i], zeta[i], whirl[i] = s.imag, -s.real / abs(s), w
            counts[b["kind"]] = counts.get(b["kind"], 0) + 1
            label = f"{b['kind']} {counts[b['kind']]}"
            turning = {w for i, w in enumerate(whirl) if i > 0 and w != "none"}
            if len(turning) == 1:
                label += " " + turning.pop()
            b["label"] = label
            out.append(CampbellBranch(label, b["kind"], freq, tuple(whirl), log_decrement(zeta), zeta))
        return out
