"""A face of the tube tied to a rigid plate: the rigid top, and the base on the foundation's springs.

Every node of a tied face follows the plate's rigid motion q = (U_x, U_y,
U_z, Theta_x, Theta_y, Theta_z) about the plate's centre (0, 0, z_c),
u_i = U + Theta x (x_i - (0, 0, z_c)): the face's dofs are eliminated, K~ =
T^T K T and M~ = T^T M T with T mapping the model's unknowns to the tube's
dofs (identity off the faces), exact, no penalty; a face's own rows stay as
inert placeholders (K~_ii = 1, M~_ii = 0: infinite eigenvalues the
shift-invert solve never returns).  Each plate carries a 6 x 6 mass block
(the bodies on the top) and a 6 x 6 stiffness block (the foundation's
springs against the ground, at the base).

Where a plate's q lives among the unknowns: the top plate's 6 dofs are
appended after the tube's (owned by the last rank); the base plate's take
the rows of six of the base face's own dofs (``carriers``: the x, y, z rows
of two base nodes, in q's order), so the model's size and the top plate's
place, which the full-order transients and the rotor's coupling rely on,
stay as they are.  A motion the foundation holds rigidly (no vertical or
torsional spring stated) is left out of the base plate: that carrier is a
placeholder too.

The foundation's springs at the base (rotorpillar.reduced.foundation, the
sign of its coupling: the base force K_H u + K_HR theta with theta turning
the tube's upper part the way u goes): on (U_x, Theta_y) the 2 x 2 [[K_H,
K_HR], [K_HR, K_R]]; on (U_y, Theta_x), where +Theta_x turns the upper part
along -y, K_HR changes sign; K_V on U_z, K_T on Theta_z.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

#: a plate's degrees of freedom
PLATE_DOFS = 6


def rigid_links(coords: np.ndarray, centre_z: float) -> np.ndarray:
    """R (3 n, 6): nodal displacements of a rigid motion q of a plate about (0, 0, centre_z)."""
    d = coords - np.array([0.0, 0.0, centre_z])
    R = np.zeros((len(d), 3, 6))
    R[:, 0, 0] = R[:, 1, 1] = R[:, 2, 2] = 1.0
    # Theta x d = -[d]x Theta
    R[:, 0, 4], R[:, 0, 5] = d[:, 2], -d[:, 1]
    R[:, 1, 3], R[:, 1, 5] = -d[:, 2], d[:, 0]
    R[:, 2, 3], R[:, 2, 4] = d[:, 1], -d[:, 0]
    return R.reshape(-1, 6)


def foundation_block(springs) -> tuple[np.ndarray, np.ndarray]:
    """(K6, free): the 6 x 6 spring matrix on the base plate's q and which of q's six
    components the foundation lets move (see the module text)."""
    K = np.zeros((6, 6))
    K[0, 0] = K[1, 1] = springs.horizontal
    K[3, 3] = K[4, 4] = springs.rocking
    K[0, 4] = K[4, 0] = springs.coupling
    K[1, 3] = K[3, 1] = -springs.coupling
    free = np.ones(6, dtype=bool)
    for i, k in ((2, springs.vertical), (5, springs.torsional)):
        if k is None:
            free[i] = False
        else:
            K[i, i] = k
    return K, free


@dataclass
class RigidFace:
    """One face of the tube tied to a rigid plate."""

    nodes: np.ndarray
    """this rank's owned nodes on the face (local indices)"""
    centre_z: float
    """height of the plate's reference point (0, 0, z) (m)"""
    columns: np.ndarray
    """(6,) global indices of the unknowns holding q; -1 where that component is held fixed"""
    mass: np.ndarray
    """6 x 6 mass block on q (kg, kg*m, kg*m**2)"""
    stiffness: np.ndarray
    """6 x 6 stiffness block on q, against the ground (N/m, N, N*m/rad)"""


def base_carriers(V, comm, base_nodes: np.ndarray, free: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """(columns, rotation_rows): the global rows of the two lowest-numbered owned base nodes
    of the first rank holding two, in q's order (x, y, z of the first node for U, of the
    second for Theta; -1 where ``free`` is False), and this rank's local rows carrying the
    rotations (the influence of a rigid translation is 0 there)."""
    start = 3 * V.dofmap.index_map.local_range[0]
    counts = comm.allgather(len(base_nodes))
    owner = next((r for r, c in enumerate(counts) if c >= 2), None)
    if owner is None:
        raise RuntimeError("no rank owns two nodes of the base face")
    if comm.rank == owner:
        a, b = np.sort(base_nodes)[:2]
        local = np.r_[3 * a + np.arange(3), 3 * b + np.arange(3)]
        cols = np.where(free, start + local, -1)
    else:
        cols = None
    cols = comm.bcast(cols, root=owner)
    rotation_rows = local[3:][free[3:]] if comm.rank == owner else np.empty(0, dtype=np.int64)
    return np.asarray(cols, dtype=np.int64), rotation_rows


def tie_faces(K, M, V, comm, faces: list[RigidFace], tube_dofs: int, extra_dofs: int):
    """(K~, M~, T): the tube with its faces tied to their plates (see the module text).

    ``extra_dofs``: unknowns appended after the tube's (the top plate's 6, or 0),
    owned by the last rank."""
    from petsc4py import PETSc

    n_local = 3 * V.dofmap.index_map.size_local
    start = 3 * V.dofmap.index_map.local_range[0]
    last = comm.rank == comm.size - 1
    N = tube_dofs
    coords = V.tabulate_dof_coordinates()
    # per row: its columns and values; a face row maps to its plate's q, off the faces the identity
    counts = np.ones(n_local, dtype=np.int64)
    face_cols, face_vals, face_rows_all = [], [], []
    for face in faces:
        R = rigid_links(coords[face.nodes], face.centre_z)  # (3 n_face, 6)
        rows = (3 * face.nodes[:, None] + np.arange(3)).ravel()
        free = face.columns >= 0
        cols = np.broadcast_to(face.columns[free], (len(rows), int(free.sum())))
        vals = R[:, free]
        # an explicit 0 on the row's own column keeps K~'s diagonal slot (inserting one later is slow)
        own = (start + rows)[:, None]
        has_own = (cols == own).any(axis=1)
        cols = np.column_stack([cols, own[:, 0]])
        vals = np.column_stack([vals, np.zeros(len(rows))])
        keep = np.ones(cols.shape, dtype=bool)
        keep[has_own, -1] = False
        face_rows_all.append(rows)
        face_cols.append((cols, keep))
        face_vals.append(vals)
        counts[rows] = keep.sum(axis=1)
    indptr = np.zeros(n_local + 1, dtype=PETSc.IntType)
    np.cumsum(counts, out=indptr[1:])
    indices = np.empty(indptr[-1], dtype=PETSc.IntType)
    values = np.empty(indptr[-1], dtype=PETSc.ScalarType)
    indices[indptr[:-1]] = start + np.arange(n_local)
    values[indptr[:-1]] = 1.0
    carriers = {int(c) for face in faces for c in face.columns if c >= 0}
    placeholders = []
    for rows, (cols, keep), vals in zip(face_rows_all, face_cols, face_vals):
        for i, row in enumerate(rows):
            c, v = cols[i][keep[i]], vals[i][keep[i]]
            order = np.argsort(c, kind="stable")
            s0 = indptr[row]
            indices[s0 : s0 + len(c)] = c[order]
            values[s0 : s0 + len(c)] = v[order]
        placeholders += [int(start + r) for r in rows if int(start + r) not in carriers]
    T = PETSc.Mat().createAIJ(
        ((n_local, N), (n_local + (extra_dofs if last else 0), N + extra_dofs)),
        csr=(indptr, indices, values),
        comm=comm,
    )
    T.assemble()
    Kt, Mt = _congruence(K, T), _congruence(M, T)
    for A in (Kt, Mt):
        A.setOption(PETSc.Mat.Option.NEW_NONZERO_ALLOCATION_ERR, False)
    for g in placeholders:
        Kt.setValue(g, g, 1.0, addv=PETSc.InsertMode.ADD_VALUES)  # its diagonal holds an explicit 0
    lo, hi = Kt.getOwnershipRange()
    for face in faces:
        for k, ck in enumerate(face.columns):
            if ck < 0 or not lo <= ck < hi:
                continue  # each plate row is added by the rank that owns it
            for j, cj in enumerate(face.columns):
                if cj < 0:
                    continue
                if face.mass[k, j]:
                    Mt.setValue(ck, cj, face.mass[k, j], addv=PETSc.InsertMode.ADD_VALUES)
                if face.stiffness[k, j]:
                    Kt.setValue(ck, cj, face.stiffness[k, j], addv=PETSc.InsertMode.ADD_VALUES)
    Kt.assemble()
    Mt.assemble()
    K.destroy()
    M.destroy()
    return Kt, Mt, T


def _congruence(A, T):
    """T^T A T, as T^T (A T): PETSc's PtAP for AIJ is ~6x slower on these matrices."""
    AT = A.matMult(T)
    try:
        return T.transposeMatMult(AT)
    finally:
        AT.destroy()
