"""The 3D full order's time loop (rotorpillar.fem3d.full_order): one factorisation, the spin by Newton.

Each scalar dof's equation (rotor centre x, y; the plate's dashpots) is
Step.history + the new-time couplings; the tube's is

    Keff u1 = M (cm u~ - am a - sum_d r_d a_d) - af K u + C_modal (cc u~ - wf v~ - af v) + the plate's rows,

Keff = wf K + cm M + cc C_modal + the plate's rows, with C_modal = W D W^T
the structural ratio on the loaded tube's modes (rank k, kept as W: the
factorisation is of the sparse part, the low-rank part by Woodbury's
identity, ``_Solver``).  The plate's rows: b1 on U_x and U_y (the tip
dashpot both ways), and the rotor centre condensed onto U_x and U_z
through the shaft's element between them, the spring c2 and, with
``damping_law = "gondola"``, the dashpot b2 on the motion relative to the
plate (kappa = wf c2 + cc b2 couples them; "ground": b2 on the rotor's own
velocity, kappa = wf c2, the paper's Eq. 4 and today's runs).  The rotor
centre (x, z) = kr^-1 (rho + kappa U + wf c2 e (cos, sin)), kr = cm m_C +
wf c2 + cc b2; condensed, the plate takes kappa - kappa**2 / kr on its
diagonal, kappa rho / kr (less the relative dashpot's history) on its
right-hand side and the unbalance -wf c2 e (1 - kappa / kr) (cos, sin).

One matrix product a step: the right-hand side takes M u, M v, M a and K u from
the step before, and of K u1 and M u1 one is the product, the other follows
from the step's equation.  The product is M u1 on M's nonzeros
(``without_zeros``: the consistent mass couples no two directions, a third of
the entries K's pattern stores; on the 8 x 15 P2 reference mesh 0.21 ms
against K's 1.31 ms); K u1 = (R + the unbalance - cm M u1 - the plate's rows -
cc C_modal u1) / wf loses ~cm M / K ~ 1 / (beta (h omega)**2) of its digits
to cancellation, but it enters the next right-hand side as af K u beside
cm M u~, which is that much larger: its error is of the size of the
right-hand side's own rounding (the histories agree with the stepping by
K's product to the problem's rounding, a few 1e-9 of a 0.3 mm tip on a coarse
tube: tests/test_full_order_step.py).

The ground moves along x, y and z (a SpatialGroundMotion; a GroundMotion is
along x): -M r_d a_d on tube and plate, -m_C a_d on the rotor's x and
vertical; along the spin axis the rotor rides on the plate (its mass on
the plate's U_y: the axial shaft is not a dof of this model).

With ``drive_reaction`` the motor's reaction acts on the plate, as on the
spatial ROM's gondola (rotorpillar.reduced.spatial_model): the stator takes
-Md about the spin vector -y, a moment +Md = M0 - s W about y on the plate's
Theta_y (the load's torque is the air's or the generator's, not the
stator's).  Md at the new time takes the speed predicted from the old
step's acceleration (W + h W'): the moment lags the implicit spin solve by
O(h**2 W''), against a moment that follows the slow drive.  ``reaction_start``
starts the tube on the static deflection under the starting speed's Md
(K u = Md e_Theta_y, one more factorisation), the rotor's whirl carried
along with the plate, as the spatial ROM starts a run at speed
(rotorpillar.transients.cases.on_reaction).
"""

from __future__ import annotations

import math
import time
from typing import Any

import numpy as np

from .rotor_top import (
    Affine,
    RotorOnTop,
    Step,
    coupling_torque,
    drive_torque,
    plate_and_rotor,
    rotor_start,
    rotor_step_stiffness,
    solve_spin,
)
from .step_operator import Plate, add_shaft_acceleration, step_operator, without_zeros


class _Solver:
    """Keff^-1 with Keff = the factorised sparse part + s W D W^T (Woodbury; collective)."""

    def __init__(self, ksp, Keff, W: np.ndarray, d: np.ndarray, scale: float, comm):
        self.ksp, self.comm, self.W = ksp, comm, W
        self.k = len(d)
        if self.k:
            x, b = Keff.createVecRight(), Keff.createVecLeft()
            Y = np.empty_like(W)
            for j in range(self.k):
                b.setArray(np.ascontiguousarray(W[:, j]))
                ksp.solve(b, x)
                Y[:, j] = x.getArray(readonly=True)
            x.destroy()
            b.destroy()
            self.Y = Y
            cap = np.diag(1.0 / (scale * d)) + self._sum(W.T @ Y)
            self.cap = np.linalg.inv(cap)

    def _sum(self, a):
        return a if self.comm.size == 1 else self.comm.allreduce(a)

    def solve(self, b, x) -> None:
        self.ksp.solve(b, x)
        if self.k:
            arr = x.getArray()
            arr -= self.Y @ (self.cap @ self._sum(self.W.T @ arr))


def ground_accelerations(motion, t: np.ndarray) -> np.ndarray:
    """(3, n) the ground's acceleration along x, y, z at ``t`` (m/s**2): a SpatialGroundMotion's
    components, or a GroundMotion along x."""
    values = np.asarray(motion.evaluate(t), dtype=float)
    if values.ndim == 3:  # SpatialGroundMotion: (displacement, velocity, acceleration) x (x, y, z)
        return values[2]
    out = np.zeros((3, len(t)))
    out[0] = values[2]
    return out


def ground_x_displacement(motion, t: np.ndarray) -> np.ndarray:
    """The ground's displacement along x whose second derivative is the applied acceleration (m)."""
    if hasattr(motion, "components"):
        return sum(
            (
                d[0] * np.asarray(c.inertial_displacement(t), dtype=float)
                for c, d in zip(motion.components, motion.directions)
            ),
            np.zeros(len(t)),
        )
    return np.asarray(motion.inertial_displacement(t), dtype=float)


def integrate(
    model,
    rotor: RotorOnTop,
    b1: float,
    drive,
    motion,
    step: Step,
    steps: int,
    stride: int,
    theta0: float,
    W0: float,
    prescribed: bool,
    progress,
    observer=None,
    damping_law: str = "ground",
    modal: tuple[np.ndarray, np.ndarray] | None = None,
    drive_reaction: bool = False,
    reaction_start: bool = False,
    mass_product: bool = True,
):
    """The generalized-alpha ``step`` over ``steps`` steps; see the module text.

    ``modal`` = (W, d): this rank's rows of M phi_j and 2 zeta omega_j of the loaded tube's
    modes (rotorpillar.fem3d.spatial_system), or None (no structural ratio, today's runs).
    ``mass_product``: each step's one product is M u1 on M's nonzeros, K u1 taken from the
    step's equation (the default: a sixth of K's cost); False: K u1 by the product, M u1
    from the equation (the stepping before, kept as the reference the tests hold it to)."""
    K, M = model.K, model.M
    N = model.tube_dofs
    rows = (N, N + 1, N + 2)  # the plate's U_x, U_y, U_z
    c2, b2, mC, J, e = (rotor.shaft_stiffness, rotor.shaft_damping, rotor.mass, rotor.inertia, rotor.eccentricity)
    h, am, af, wf = step.h, step.alpha_m, step.alpha_f, step.new_weight
    cm, cc = step.mass_coefficient, step.damping_coefficient
    relative = damping_law == "gondola"
    kr = rotor_step_stiffness(rotor, step)
    kappa = wf * c2 + (cc * b2 if relative else 0.0)
    W_modal, d_modal = modal if modal is not None else (np.zeros((K.getLocalSize()[0], 0)), np.zeros(0))
    comm = model.comm

    def dots(arr):  # W^T x summed over the ranks
        out = W_modal.T @ arr
        return out if comm.size == 1 else comm.allreduce(out)

    t0 = time.perf_counter()
    condensed = kappa - kappa**2 / kr
    ksp, Keff, (d_x, d_y, d_z) = step_operator(
        K, M, {N: cc * b1 + condensed, N + 1: cc * b1, N + 2: condensed}, wf, cm, model.comm
    )
    solver = _Solver(ksp, Keff, W_modal, d_modal, cc, comm)
    M_nz = without_zeros(M) if mass_product else None
    vecs = [K.createVecRight() for _ in range(14)]
    u, v, a, w, R, u1, gN, gZ, tmp, pred, Ku, Mu, Mv, Ma = vecs
    plate = Plate(u, rows, model.comm)
    roll = Plate(u, (N + 4,), model.comm)  # the plate's Theta_y, about the spin axis
    for x in vecs:
        x.set(0.0)
    for g, i in ((gN, 0), (gZ, 2)):  # the plate under a unit load on U_x, U_z
        unit = [0.0, 0.0, 0.0]
        unit[i] = 1.0
        plate.add(R, unit)
        solver.solve(R, g)
        R.set(0.0)
    gx, gz = plate.get(gN), plate.get(gZ)
    gcoef = (gx[0], gz[0], gx[2], gz[2])
    gamma = -wf * c2 * e * (1 - kappa / kr)
    setup = time.perf_counter() - t0
    r_dirs = [model.influence(d) for d in range(3)]
    Mr = [M.createVecLeft() for _ in range(3)]
    for r, m in zip(r_dirs, Mr):
        M.mult(r, m)
    mask = M.getDiagonal()  # rows with mass: not clamped, not placeholders
    mask.getArray()[:] = mask.getArray(readonly=True) != 0.0
    vecs += r_dirs + Mr + [mask]

    tg = h * np.arange(steps + 1)
    ag = ground_accelerations(motion, tg)
    ug = ground_x_displacement(motion, tg)
    M0s, slopes = (np.asarray(x, dtype=float) for x in drive.at(tg))
    kload = drive.load_coefficient
    # start (rotorpillar.fem3d.full_order)
    x, y, vx, vy = rotor_start(rotor, theta0, W0)
    P = np.zeros((3, 3))  # the plate's U_x, U_y, U_z: displacement, velocity, acceleration (rows)
    th, W = theta0, W0

    def motor(n_: int, W_: float) -> float:  # Md alone (N*m): its reaction is the stator's
        return float(M0s[n_] - slopes[n_] * W_) if drive_reaction else 0.0

    Md = motor(0, W0)
    if reaction_start and Md:
        t_static = time.perf_counter()
        _static_deflection(K, roll, Md, u, tmp, model.comm)
        K.mult(u, Ku)
        M.mult(u, Mu)
        P[:, 0] = plate.get(u)
        x, y = x + P[0, 0], y + P[2, 0]  # the whirl rides on the displaced plate
        setup += time.perf_counter() - t_static
    Theta = float(roll.get(u)[0])
    a.set(0.0)
    for d in range(3):
        tmp.pointwiseMult(r_dirs[d], mask)
        a.axpy(-ag[d, 0], tmp)
    t_start = time.perf_counter()
    sx0, sy0 = x - P[0, 0] - e * math.cos(th), y - P[2, 0] - e * math.sin(th)  # the shaft's stretch
    add_shaft_acceleration(M, mask, plate, a, (c2 * sx0, 0.0, c2 * sy0))
    setup += time.perf_counter() - t_start
    P[:, 2] = plate.get(a)
    ax = (-c2 * sx0 - b2 * vx - mC * ag[0, 0]) / mC
    ay = (-c2 * sy0 - b2 * vy - mC * ag[2, 0]) / mC
    tau = drive_torque(M0s[0], slopes[0], kload, W0)
    Tc = coupling_torque(rotor, x - P[0, 0], y - P[2, 0], th)
    alpha = 0.0 if prescribed else (tau + Tc) / J
    work = np.zeros(4)
    n_out = steps // stride + (1 if steps % stride else 0) + 1
    keys = ("t", "Omega", "theta", "tip_x", "rotor_x", "rotor_y", "plate_z", "shaft_x", "shaft_y", "energy")
    out: dict[str, Any] = {k: np.zeros(n_out) for k in keys}
    out["work"] = np.zeros((n_out, 4))
    peaks = dict.fromkeys(
        (
            "tip_x",
            "tip_x_absolute",
            "tip_y",
            "rotor_x",
            "rotor_y",
            "shaft_deflection_x",
            "shaft_deflection_y",
            "plate_z",
        ),
        0.0,
    )

    M.mult(a, Ma)
    Wu, Wv = dots(u.getArray(readonly=True)), dots(v.getArray(readonly=True))

    def energy():
        E = 0.5 * u.dot(Ku) + 0.5 * v.dot(Mv) + 0.5 * mC * (vx * vx + vy * vy)
        E += 0.5 * c2 * ((x - P[0, 0] - e * math.cos(th)) ** 2 + (y - P[2, 0] - e * math.sin(th)) ** 2)
        return E + (0.0 if prescribed else 0.5 * J * W * W)

    def record(j, t):
        for k, val in (
            ("t", t),
            ("Omega", W),
            ("theta", th),
            ("tip_x", P[0, 0]),
            ("rotor_x", x),
            ("rotor_y", y),
            ("plate_z", P[2, 0]),
            ("shaft_x", x - P[0, 0] - e * math.cos(th)),
            ("shaft_y", y - P[2, 0] - e * math.sin(th)),
            ("energy", energy()),
        ):
            out[k][j] = val
        out["work"][j] = work
        if observer is not None:
            observer.record(t, u)

    def relative_history(xr, vr, ar, U):
        """b2's history on the rotor's motion relative to the plate (N)."""
        xt, vt = step.predict(xr, vr, ar)
        Ut, Vt = step.predict(U[0], U[1], U[2])
        return b2 * (cc * (xt - Ut) - wf * (vt - Vt) - af * (vr - U[1]))

    record(0, 0.0)
    j, newton, newton_max, status = 1, 0, 0, "ok"
    bu, bv, ba = h, h * h * (0.5 - step.beta), h * (1 - step.gamma)
    t_int = time.perf_counter()
    for n in range(1, steps + 1):
        t = n * h
        agw = wf * ag[:, n] + af * ag[:, n - 1]
        sx0, sy0 = x - P[0, 0] - e * math.cos(th), y - P[2, 0] - e * math.sin(th)
        # R = M (cm u~ - am a - r a_g) - af K u + C_modal (cc u~ - wf v~ - af v) + the plate's rows,
        # from the products M u, M v, M a, K u the last step left (no product here)
        u.copy(pred)
        pred.axpy(bu, v)
        pred.axpy(bv, a)  # pred = u~
        Mu.copy(w)
        w.axpy(bu, Mv)
        w.axpy(bv, Ma)  # w = M u~
        w.copy(R)
        R.scale(cm)
        if am:
            R.axpy(-am, Ma)
        for d in range(3):
            if agw[d]:
                R.axpy(-agw[d], Mr[d])
        if af:
            R.axpy(-af, Ku)
        if len(d_modal):
            Wa = dots(a.getArray(readonly=True))
            hist = cc * (Wu + bu * Wv + bv * Wa) - wf * (Wv + ba * Wa) - af * Wv
            R.getArray()[:] += W_modal @ (d_modal * hist)
        if relative:
            rho_x = step.history(mC, 0.0, x, vx, ax, -c2 * sx0) + relative_history(x, vx, ax, P[0]) - mC * agw[0]
            rho_y = step.history(mC, 0.0, y, vy, ay, -c2 * sy0) + relative_history(y, vy, ay, P[2]) - mC * agw[2]
            back = (relative_history(x, vx, ax, P[0]), relative_history(y, vy, ay, P[2]))
        else:
            rho_x = step.history(mC, b2, x, vx, ax, -c2 * sx0) - mC * agw[0]
            rho_y = step.history(mC, b2, y, vy, ay, -c2 * sy0) - mC * agw[2]
            back = (0.0, 0.0)
        dash = [step.history(0.0, b1, P[i, 0], P[i, 1], P[i, 2], 0.0) for i in (0, 1)]
        Md1 = motor(n, W + h * alpha)  # the new time's, on the predicted speed (module text)
        if drive_reaction:
            roll.add(R, (af * Md + wf * Md1,))
        plate.add(
            R,
            (
                dash[0] + af * c2 * sx0 + kappa * rho_x / kr - back[0],
                dash[1],
                af * c2 * sy0 + kappa * rho_y / kr - back[1],
            ),
        )
        solver.solve(R, u1)
        ux_hat, _, uz_hat = plate.get(u1)
        UxA, UzA, xA, yA = plate_and_rotor(rotor, kr, ux_hat, uz_hat, rho_x, rho_y, gamma, gcoef, wf, kappa)
        sx = Affine(xA.a0 - UxA.a0, xA.ac - UxA.ac, xA.as_ - UxA.as_)
        sy = Affine(yA.a0 - UzA.a0, yA.ac - UzA.ac, yA.as_ - UzA.as_)
        if prescribed:
            th1, W1, alpha1, it = theta0 + W0 * t, W0, 0.0, 0
        else:
            try:
                th1, W1, alpha1, it = solve_spin(
                    rotor, h, th, W, alpha, sx, sy, M0s[n], slopes[n], kload, step=step, old_torque=tau + Tc
                )
            except ArithmeticError:
                status = f"Newton on the spin equation failed at t = {t:g} s"
                break
        newton += it
        newton_max = max(newton_max, it)
        c, s = math.cos(th1), math.sin(th1)
        u1.axpy(gamma * c, gN)
        u1.axpy(gamma * s, gZ)
        Ux1, Uz1, x1, y1 = UxA.at(c, s), UzA.at(c, s), xA.at(c, s), yA.at(c, s)
        Uy1 = float(plate.get(u1)[1])
        Theta1 = float(roll.get(u1)[0])
        if not all(map(math.isfinite, (Ux1, x1, y1, th1, Uy1))):
            status = f"solution diverged (not finite) at t = {t:g} s"
            break
        # the new products: one product, the other from the step's own equation, Keff u1 = R +
        # the unbalance = wf K u1 + cm M u1 + the plate's rows + cc C_modal u1 (module text)
        rMu0 = [rd.dot(Mu) for rd in r_dirs]
        Wu1 = dots(u1.getArray(readonly=True))
        R.copy(tmp)
        plate.add(tmp, (gamma * c - d_x * Ux1, -d_y * Uy1, gamma * s - d_z * Uz1))
        if len(d_modal):
            tmp.getArray()[:] -= W_modal @ (cc * d_modal * Wu1)
        if M_nz is not None:
            M_nz.mult(u1, Mu)
            tmp.axpy(-cm, Mu)
            tmp.scale(1.0 / wf)
            tmp.copy(Ku)  # K u1
        else:
            K.mult(u1, Ku)
            tmp.axpy(-wf, Ku)
            tmp.scale(1.0 / cm)
            tmp.copy(Mu)  # M u1
        v.axpy(ba, a)  # v~
        a.waxpy(-1.0, pred, u1)
        a.scale(1.0 / (step.beta * h * h))  # a1 = (u1 - u~) / (beta h**2)
        v.axpy(step.gamma * h, a)
        Mv.axpy(ba, Ma)
        Ma.waxpy(-1.0, w, Mu)
        Ma.scale(1.0 / (step.beta * h * h))
        Mv.axpy(step.gamma * h, Ma)
        rotor_moves = (x1 - x, 0.0, y1 - y)
        dbase = -sum(
            0.5 * (ag[d, n - 1] + ag[d, n]) * (r_dirs[d].dot(Mu) - rMu0[d] + mC * rotor_moves[d]) for d in range(3)
        )
        u1.copy(u)
        P1 = np.zeros((3, 3))
        for i, U1 in enumerate((Ux1, Uy1, Uz1)):
            P1[i, 0] = U1
            P1[i, 1], P1[i, 2] = step.update(U1, *step.predict(P[i, 0], P[i, 1], P[i, 2]))
        vx1, ax1 = step.update(x1, *step.predict(x, vx, ax))
        vy1, ay1 = step.update(y1, *step.predict(y, vy, ay))
        Wv1 = dots(v.getArray(readonly=True))
        tau1 = drive_torque(M0s[n], slopes[n], kload, W1)
        Tc1 = coupling_torque(rotor, x1 - Ux1, y1 - Uz1, th1)
        # work increments by the trapezoidal rule (Newmark's energy identity for its linear part)
        work[0] += 0.5 * (tau + tau1) * (th1 - th)
        Md1 = motor(n, W1)
        work[0] += 0.5 * (Md + Md1) * (Theta1 - Theta)  # the motor's reaction on the plate
        work[1] -= 0.5 * (Tc + Tc1) * (th1 - th)
        work[2] += sum(b1 * (P1[i, 0] - P[i, 0]) * 0.5 * (P[i, 1] + P1[i, 1]) for i in (0, 1))
        if relative:
            work[2] += b2 * ((x1 - Ux1) - (x - P[0, 0])) * 0.5 * ((vx - P[0, 1]) + (vx1 - P1[0, 1]))
            work[2] += b2 * ((y1 - Uz1) - (y - P[2, 0])) * 0.5 * ((vy - P[2, 1]) + (vy1 - P1[2, 1]))
        else:
            work[2] += b2 * (x1 - x) * 0.5 * (vx + vx1) + b2 * (y1 - y) * 0.5 * (vy + vy1)
        if len(d_modal):
            work[2] += float(np.sum((Wu1 - Wu) * d_modal * 0.5 * (Wv + Wv1)))
        work[3] += dbase
        Wu, Wv = Wu1, Wv1
        P, x, y, vx, vy, ax, ay = P1, x1, y1, vx1, vy1, ax1, ay1
        th, W, alpha, tau, Tc, Md, Theta = th1, W1, alpha1, tau1, Tc1, Md1, Theta1
        for k, val in (
            ("tip_x", P[0, 0]),
            ("tip_x_absolute", P[0, 0] + ug[n]),
            ("tip_y", P[1, 0]),
            ("rotor_x", x),
            ("rotor_y", y),
            ("plate_z", P[2, 0]),
            ("shaft_deflection_x", x - P[0, 0] - e * c),
            ("shaft_deflection_y", y - P[2, 0] - e * s),
        ):
            peaks[k] = max(peaks[k], abs(val))
        if n % stride == 0 or n == steps:
            record(j, t)
            j += 1
        if progress and n % max(1, steps // 10) == 0:
            progress(f"3D transient: step {n} of {steps} (t = {t:.3g} s)")
    t_int = time.perf_counter() - t_int
    for obj in vecs + [ksp, Keff] + ([M_nz] if M_nz is not None else []):
        obj.destroy()
    out = {k: val[:j] for k, val in out.items()}
    out["max_abs"] = {k: float(val) for k, val in peaks.items()}
    stats = {
        "status": status,
        "steps": int(n if status == "ok" else n - 1),
        "factorisations": 1,
        "solves": int(n + 2 + len(d_modal)),
        "newton_iterations": int(newton),
        "newton_max": int(newton_max),
        "factorisation_seconds": setup,
        "integration_seconds": t_int,
        "seconds_per_step": t_int / max(n, 1),
        "output_stride": stride,
    }
    return out, stats


def _static_deflection(K, roll: Plate, moment: float, u, rhs, comm) -> None:
    """u = K^-1 (``moment`` on the plate's Theta_y): the tube's static state under the motor's
    reaction (one Cholesky factorisation of K, MUMPS; ``rhs`` is scratch)."""
    from petsc4py import PETSc

    ksp = PETSc.KSP().create(comm)
    try:
        ksp.setOperators(K)
        ksp.setType("preonly")
        ksp.getPC().setType("cholesky")
        ksp.getPC().setFactorSolverType("mumps")
        rhs.set(0.0)
        roll.add(rhs, (moment,))
        ksp.solve(rhs, u)
    finally:
        ksp.destroy()
        rhs.set(0.0)
