"""Tapered and stepped towers, and a cantilever on springs, against independent references.

Sources and tolerances:

- The tapered or stepped Euler-Bernoulli cantilever's frequencies by
  shooting: (EI w'')'' = m omega**2 w integrated along the height with
  scipy's DOP853 (rtol 1e-12) from the base's conditions, the root of the
  top's 2 x 2 boundary determinant by Brent's method (bracketed within 1 %
  of the beam's value: no sign change there fails the test): another
  formulation than the finite elements, converged to ~1e-10.  The Hermite
  beam (64 elements, error ~ h**4 ~ 1e-8 here) meets it within 1e-6;
  Rayleigh-Ritz bounds it from above (its theorem: the inequality must hold
  to round-off) and with 10 shapes lies within 1e-4 of it on the cone
  (measured 6e-5), 2.5e-3 on the stepped tower (see the test).
- The uniform cantilever on a translational, a rotational and a coupling
  spring: its closed-form frequency equation, the 4 x 4 determinant of the
  general solution A cosh + B sinh + C cos + D sin under the energy's
  boundary conditions (EI w''' + k_t w + k_c w' = 0 and -EI w'' + k_c w +
  k_r w' = 0 at the base, w'' = w''' = 0 at the top).  Checked against its
  own limits (stiff springs: Blevins' 1.87510407; no rocking spring and a
  stiff translation: the pinned-free beam's rigid rotation) and the Hermite
  beam on the same springs within 1e-6 (64 elements).
- The section data: the frustum's exact volume pi h/3 (R**2 + R r + r**2)
  for the outer and inner surfaces (the tower's mass to 1e-12, Gauss
  quadrature of a quadratic), and a node of the beam on every joint.
- Gazetas (1991) Table 1's formulas for a foundation of any shape, applied
  to the circle (A_b = pi R**2, L = B = R: chi = pi/4), give K_V and K_H
  within 1 % of the rigid disk's exact values this module uses (0.7 % and
  0.9 % by hand: 2 (0.73 + 1.54 chi**0.75) = 4.03 against 4; 2 (2 + 2.5
  chi**0.85) = 8.07 against 8); the embedded springs against numbers worked
  by hand from Gazetas' Table 2 below (1e-3: the hand's four digits); the
  transfer to the ground is the rigid footing's T^T K T (1e-12).
"""

from __future__ import annotations

import math

import numpy as np
import pytest
from scipy.integrate import solve_ivp, trapezoid
from scipy.optimize import brentq

from rotorpillar.reduced.beam_fe import BaseSprings, BeamProperties, beam_modes
from rotorpillar.reduced.foundation import embedment_factors, footing_stiffness, surface_circle
from rotorpillar.reduced.pillar import cantilever_root, tube_section
from rotorpillar.reduced.pillar_modes import beam_line
from rotorpillar.reduced.tower import element_nodes, rayleigh_ritz, sections_along, tower_mass
from rotorpillar.scene import SceneError, load_scene, scene_from_dict
from rotorpillar.scene.files import read_scene_toml

E, NU, RHO = 2.1e11, 0.3, 7850.0


def tower(cans, foundation=None):
    """The paper's scene with its tube replaced by ``cans`` (and a foundation)."""
    data, _ = read_scene_toml("paper")
    data["pillar"] = {
        k: v for k, v in data["pillar"].items() if k not in ("height", "outer_diameter", "inner_diameter")
    }
    data["pillar"]["cans"] = cans
    if foundation is not None:
        data["foundation"] = foundation
    return scene_from_dict(data, "tower")


CONE = [
    dict(height=40.0, outer_diameter_bottom=4.0, outer_diameter_top=2.4, wall_thickness=0.03, wall_thickness_top=0.02)
]
STEPPED = [
    dict(height=15.0, outer_diameter_bottom=4.0, outer_diameter_top=3.4, wall_thickness=0.035),
    dict(height=15.0, outer_diameter_bottom=3.4, outer_diameter_top=3.4, wall_thickness=0.025),
    dict(height=10.0, outer_diameter_bottom=3.4, outer_diameter_top=2.6, wall_thickness=0.018),
]


def shooting_frequencies(pillar, near, springs: BaseSprings | None = None) -> list[float]:
    """The Euler-Bernoulli beam's omegas (rad/s) by shooting (see the module text), one root
    of the boundary determinant within 1 % of each of ``near``: the bracket must hold a
    sign change, or the test fails."""
    E_ = pillar.youngs_modulus
    segs = pillar.segments()

    def top_state(omega, y0):
        y = np.asarray(y0, dtype=float)
        for s in segs:

            def rhs(z, y, s=s):
                sec = sections_along(pillar, [z], "above" if z < s.top else "below")
                return [y[1], y[2] / (E_ * sec.second_moment[0]), y[3], omega**2 * sec.mass_per_length[0] * y[0]]

            sol = solve_ivp(rhs, (s.bottom, s.top), y, method="DOP853", rtol=1e-12, atol=1e-14)
            y = sol.y[:, -1]
        return y

    def det(omega):
        if springs is None:
            starts = ([0, 0, 1, 0], [0, 0, 0, 1])
        else:
            k, r, c = springs.horizontal, springs.rocking, springs.coupling
            starts = ([1, 0, c, -k], [0, 1, r, -c])
        a, b = (top_state(omega, s) for s in starts)
        # scale the columns: the states grow like exp(beta z)
        a, b = a / np.linalg.norm(a), b / np.linalg.norm(b)
        return a[2] * b[3] - a[3] * b[2]

    return [brentq(det, 0.99 * w, 1.01 * w, xtol=1e-13) for w in near]


# Ritz's tolerance: 1e-4 on the smooth cone (measured 6e-5 with 10 shapes); on the stepped
# tower the smooth shapes meet a curvature that jumps at each step and the error falls only
# as ~1/shapes (measured 7.7e-4, 9.6e-4, 1.9e-3 for the first three with 10): 2.5e-3
@pytest.mark.parametrize("cans, ritz_tol", [(CONE, 1e-4), (STEPPED, 2.5e-3)], ids=["cone", "stepped"])
def test_tapered_and_stepped_beams_meet_the_shooting_solution(cans, ritz_tol):
    p = tower(cans).pillar
    fe = beam_modes(beam_line(p, 64), 64, "euler", 3).omega
    exact = shooting_frequencies(p, fe)
    assert np.allclose(fe, exact, rtol=1e-6, atol=0)
    ritz = rayleigh_ritz(p, terms=10).omega[:3]
    assert np.all(ritz >= np.asarray(exact) * (1 - 1e-12))  # an upper bound (Rayleigh-Ritz's theorem)
    assert np.allclose(ritz, exact, rtol=ritz_tol, atol=0)


def test_a_ritz_bound_falls_with_more_shapes():
    p = tower(CONE).pillar
    w = [rayleigh_ritz(p, terms=n).omega[0] for n in (1, 2, 4, 8)]
    assert all(a >= b - 1e-12 * a for a, b in zip(w, w[1:]))  # adding shapes never raises a Ritz value


def spring_determinant(beta_L: float, EI: float, L: float, kt: float, kr: float, kc: float) -> float:
    """The closed-form frequency equation of the uniform cantilever on base springs (see the module text)."""
    b = beta_L / L
    ch, sh, c, s = math.cosh(beta_L), math.sinh(beta_L), math.cos(beta_L), math.sin(beta_L)
    M = np.array(
        [
            [kt, EI * b**3 + kc * b, kt, -EI * b**3 + kc * b],
            [-EI * b**2 + kc, kr * b, EI * b**2 + kc, kr * b],
            [1.0, sh / ch, -c / ch, -s / ch],
            [sh / ch, 1.0, s / ch, -c / ch],
        ]
    )
    M[0] /= np.abs(M[0]).max()
    M[1] /= np.abs(M[1]).max()
    return float(np.linalg.det(M))


def spring_roots(EI, m, L, kt, kr, kc, count=3):
    grid = np.linspace(0.05, 12.0, 4000)
    vals = [spring_determinant(x, EI, L, kt, kr, kc) for x in grid]
    roots = []
    for i in range(len(grid) - 1):
        if np.sign(vals[i]) != np.sign(vals[i + 1]):
            x = brentq(lambda x: spring_determinant(x, EI, L, kt, kr, kc), grid[i], grid[i + 1], xtol=1e-14)
            if abs(spring_determinant(x, EI, L, kt, kr, kc)) < 1e-6:  # a root, not a pole of the scaling
                roots.append((x / L) ** 2 * math.sqrt(EI / m))
            if len(roots) == count:
                break
    return roots


SEC = tube_section(2.0, 1.96, RHO)
L_BEAM = 20.0
EI, M_RHO = E * SEC.second_moment, SEC.mass_per_length


def test_the_closed_form_spring_equation_has_the_clamped_and_pinned_limits():
    stiff = 1e9 * EI / L_BEAM**3  # springs 1e9 times the beam's own stiffness: their softness is 1e-9
    w = spring_roots(EI, M_RHO, L_BEAM, stiff, stiff * L_BEAM**2, 0.0, 1)[0]
    assert w == pytest.approx(cantilever_root(1) ** 2 * math.sqrt(EI / (M_RHO * L_BEAM**4)), rel=1e-5)
    # no rocking spring, the base held in translation: the pinned-free beam's first
    # elastic root 3.9266 (its rigid rotation at omega = 0 drops out of the grid)
    w = spring_roots(EI, M_RHO, L_BEAM, stiff, 1e-9, 0.0, 1)[0]
    assert w == pytest.approx(3.92660231**2 * math.sqrt(EI / (M_RHO * L_BEAM**4)), rel=1e-5)


@pytest.mark.parametrize(
    "kt, kr, kc",
    [
        (2e8, 5e9, 0.0),  # a soft translational and rotational spring
        (2e8, 5e9, -2.0e8),  # with coupling, either sign
        (2e8, 5e9, 3.0e8),
    ],
)
def test_cantilever_on_springs_meets_its_frequency_equation(kt, kr, kc):
    exact = spring_roots(EI, M_RHO, L_BEAM, kt, kr, kc, 3)
    bp = BeamProperties(E, NU, 0.53, RHO, SEC.area, SEC.second_moment, L_BEAM)
    base = BaseSprings(kt, kr, kc)
    fe = beam_modes(bp, 64, "euler", 3, base=base).omega
    assert np.allclose(fe, exact, rtol=1e-6, atol=0)
    clamped = beam_modes(bp, 64, "euler", 1).omega[0]
    assert exact[0] < clamped  # springs only soften
    # the same springs on a tower: shooting against the beam and the Ritz bound
    p = tower(CONE).pillar
    fe = beam_modes(beam_line(p, 64), 64, "euler", 2, base=base).omega
    shot = shooting_frequencies(p, fe, base)
    assert np.allclose(fe, shot, rtol=1e-6, atol=0)
    ritz = rayleigh_ritz(p, terms=10, base=base).omega[:2]
    assert np.all(ritz >= np.asarray(shot) * (1 - 1e-12)) and np.allclose(ritz, shot, rtol=1e-4, atol=0)


def test_section_data_of_a_cone_and_of_steps():
    p = tower(CONE).pillar
    # the frustum: outer radii 2.0 -> 1.2, inner 1.97 -> 1.18 (m), 40 m
    frustum = lambda R, r: math.pi * 40.0 / 3 * (R**2 + R * r + r**2)
    assert tower_mass(p) == pytest.approx(p.density * (frustum(2.0, 1.2) - frustum(1.97, 1.18)), rel=1e-12)
    s = sections_along(p, [0.0, 40.0])
    assert s.outer_diameter.tolist() == [4.0, 2.4] and np.allclose(s.wall_thickness, [0.03, 0.02], rtol=1e-12)
    q = tower(STEPPED).pillar
    nodes = element_nodes(q, 20)
    assert {15.0, 30.0} <= set(np.round(nodes, 12)) and len(nodes) == 21
    # a joint's two sides: the wall steps from 35 to 25 mm at 15 m
    below, above = sections_along(q, [15.0], "below"), sections_along(q, [15.0], "above")
    assert below.wall_thickness[0] == pytest.approx(0.035) and above.wall_thickness[0] == pytest.approx(0.025)


def test_gazetas_general_shape_formulas_reproduce_the_rigid_disk():
    G, nu, R = 50e6, 0.3, 10.0
    kv, kh, kr, kt = surface_circle(G, nu, R)
    chi = math.pi / 4  # A_b / (4 L**2) for the circle's circumscribed square
    assert 2 * G * R / (1 - nu) * (0.73 + 1.54 * chi**0.75) == pytest.approx(kv, rel=0.01)
    assert 2 * G * R / (2 - nu) * (2 + 2.5 * chi**0.85) == pytest.approx(kh, rel=0.01)


def test_gazetas_embedded_footing_by_hand():
    # G = 50 MPa, nu = 0.3, R = 10 m, D = d = 2 m: by hand from Table 2 (B = L = R = 10,
    # A_b = 314.16 m**2, A_w = 2 pi R d = 125.66 m**2, chi = pi/4, h = D - d/2 = 1 m)
    fv, fh, fr, ft = embedment_factors(10.0, 2.0)
    assert fv == pytest.approx((1 + 2 / 210 * (1 + 1.3 * 0.7854)) * (1 + 0.2 * 0.4 ** (2 / 3)), rel=1e-3)
    assert fv == pytest.approx(1.0197 * 1.1086, rel=1e-3)
    assert fh == pytest.approx((1 + 0.15 * 0.4472) * (1 + 0.52 * (1 * 125.66 / 1000) ** 0.4), rel=1e-3)
    assert fh == pytest.approx(1.0671 * 1.2261, rel=1e-3)
    assert fr == pytest.approx(1 + 1.26 * 0.2 * 1.2, rel=1e-3)  # (d/D)**-0.2 = 1, (B/L)**0.5 = 1
    assert ft == pytest.approx(1 + 1.4 * 2 * 0.2**0.9, rel=1e-3)
    assert ft == pytest.approx(1.6578, rel=1e-3)  # 0.2**0.9 = 0.2349
    s = footing_stiffness(50e6, 0.3, 10.0, 2.0)
    kv, kh, kr, kt = surface_circle(50e6, 0.3, 10.0)
    assert s.horizontal == pytest.approx(2.3529e9 * 1.0671 * 1.2261, rel=1e-3)
    assert s.vertical == pytest.approx(2.8571e9 * 1.0197 * 1.1086, rel=1e-3)
    # at the base's centre K_HR = d K_H / 3; the rigid footing carries it up D = 2 m
    K0 = np.array([[s.horizontal, 2.0 * s.horizontal / 3], [2.0 * s.horizontal / 3, kr * fr]])
    T = np.array([[1.0, -2.0], [0.0, 1.0]])  # u_base = u_top - D theta
    Kt = T.T @ K0 @ T
    assert np.allclose([s.horizontal, s.coupling, s.rocking], [Kt[0, 0], Kt[0, 1], Kt[1, 1]], rtol=1e-12)
    flat = footing_stiffness(50e6, 0.3, 10.0, 0.0)
    assert (flat.horizontal, flat.rocking, flat.coupling) == (kh, kr, 0.0)


BAD = [
    ({"pillar.cans": [dict(CONE[0], wall_thickness=2.5)]}, "pillar.cans[0].wall_thickness", "< the can's outer radius"),
    ({"pillar.cans": [dict(CONE[0], wall_thickness_top=1.3)]}, "pillar.cans[0].wall_thickness_top", "outer radius"),
    ({"pillar.cans": [dict(CONE[0], height=-1.0)]}, "pillar.cans[0].height", "> 0"),
    ({"pillar.cans": [{"height": 10.0}]}, "pillar.cans[0].outer_diameter_bottom", "missing"),
    ({"pillar.cans": [dict(CONE[0], colour=1)]}, "pillar.cans[0].colour", "unknown key"),
    ({"pillar.cans": CONE, "pillar.height": 41.0}, "pillar.height", "sum of the cans"),
    ({"pillar.cans": CONE, "pillar.outer_diameter": 4.0}, "pillar.outer_diameter", "not both"),
    (
        {"foundation.kind": "springs", "foundation.horizontal_stiffness": -1e9},
        "foundation.horizontal_stiffness",
        ">= 1",
    ),
    (
        {"foundation.kind": "springs", "foundation.horizontal_stiffness": 1e9},
        "foundation.rocking_stiffness",
        "required",
    ),
    (
        {
            "foundation.kind": "springs",
            "foundation.horizontal_stiffness": 1e9,
            "foundation.rocking_stiffness": 1e11,
            "foundation.coupling_stiffness": 1e11,
        },
        "foundation.coupling_stiffness",
        "sqrt(K_H K_R)",
    ),
    (
        {"foundation.kind": "footing", "foundation.soil_shear_modulus": 8e7, "foundation.soil_poisson_ratio": 0.3},
        "foundation.radius",
        "required",
    ),
    ({"foundation.kind": "footing", "foundation.radius": 0.0}, "foundation.radius", ">= 0.01"),
    ({"foundation.radius": 10.0}, "foundation.radius", "only with foundation.kind = 'footing'"),
    ({"foundation.kind": "rock"}, "foundation.kind", "one of 'clamped', 'springs', 'footing'"),
]


@pytest.mark.parametrize("sets, key, rng", BAD, ids=[b[1] + ":" + b[2] for b in BAD])
def test_bad_tower_and_foundation_input_is_one_line_naming_the_key(sets, key, rng):
    data, _ = read_scene_toml("paper")
    for k, v in sets.items():
        sec, name = k.split(".")
        if sec == "pillar" and name == "cans":
            for old in ("height", "outer_diameter", "inner_diameter"):
                data["pillar"].pop(old, None)
        data.setdefault(sec, {})[name] = v
    with pytest.raises(SceneError) as err:
        scene_from_dict(data, "bad")
    msg = str(err.value)
    assert "\n" not in msg and key in msg and rng in msg


def test_bad_can_on_the_command_line_exits_2_and_writes_nothing(tmp_path, here):
    # in this process (``here``): a refusal before any work needs no Python start-up
    out = tmp_path / "out"
    can = "pillar.cans=[{height=87.6, outer_diameter_bottom=6.0, outer_diameter_top=3.87, wall_thickness=3.5}]"
    proc = here("analyze", "nrel5mw", "--out", out, "--set", can)
    assert proc.returncode == 2
    assert "pillar.cans[0].wall_thickness" in proc.stderr and len(proc.stderr.strip().splitlines()) == 1
    assert not out.exists() or not any(out.rglob("*"))


def test_the_uniform_scenes_have_no_cans_and_stand_on_a_clamp():
    for name in ("paper", "paper-stiff", "sommerfeld"):
        s = load_scene(name)
        assert s.pillar.is_uniform and s.pillar.cans == () and s.foundation.kind == "clamped"


# The paper's uniform tube must give today's numbers whichever way a scene states it and
# whichever of the tower's general paths computes it.  References and tolerances:
# - the tube as one cylindrical can: the same segment (D1 = D0 - 2 t to round-off), so every
#   number of the closed forms and of the beam agrees to 1e-12;
# - the beam of per-element sections (tower_line: each element's section sampled at its Gauss
#   points) against the uniform beam (uniform_line: one section): the same matrices up to
#   round-off (a constant section integrates exactly), 1e-10 on the frequencies (eigh's
#   round-off on K's condition number ~ n**4 ~ 1e6 times 1e-16);
# - Rayleigh-Ritz on the uniform tube: its shapes are the uniform cantilever's exact modes, so
#   it returns Eq. 1's frequencies (the first three, from Blevins' roots) and Eq. 2's continuous
#   tip mass m_col / 4 up to its 40-point quadrature's round-off (1e-9);
# - the tower's route of the closed forms forced on the uniform tube: its Timoshenko value is the
#   200-element beam's, against the Timoshenko frequency equation's root within 1e-5: the
#   Timoshenko element converges as (H / n)**2 (measured 1.2e-5, 3.0e-6, 7.5e-7 at 100, 200,
#   400 elements: a factor 4 per halving), so 3e-6 at 200.
def test_the_uniform_tube_as_one_can_gives_todays_numbers():
    from rotorpillar.reduced.pillar_modes import beam_pillar_modes
    from rotorpillar.reduced.reduction import pillar_closed_forms

    today = load_scene("paper")
    p = today.pillar
    wall = (p.outer_diameter - p.inner_diameter) / 2
    one_can = tower(
        [
            dict(
                height=p.height,
                outer_diameter_bottom=p.outer_diameter,
                outer_diameter_top=p.outer_diameter,
                wall_thickness=wall,
            )
        ]
    )
    q = one_can.pillar
    assert q.is_uniform and q.cans and q.height == p.height
    a, b = pillar_closed_forms(p), pillar_closed_forms(q)
    assert b.statement == a.statement and b.rayleigh_ritz is None
    for name in ("area", "second_moment", "mass", "omega_col1", "omega_col1_timoshenko", "tip_mass_limit"):
        assert getattr(b, name) == pytest.approx(getattr(a, name), rel=1e-12), name
    assert np.allclose(b.omega_euler_bernoulli, a.omega_euler_bernoulli, rtol=1e-12, atol=0)
    top = today.gondola.mass
    for theory in ("euler", "timoshenko"):
        wa = beam_pillar_modes(p, top, 3, theory, 40).omega
        wb = beam_pillar_modes(q, top, 3, theory, 40).omega
        assert np.allclose(wb, wa, rtol=1e-12, atol=0), theory


def test_the_towers_general_paths_reproduce_the_uniform_tubes_closed_forms():
    from rotorpillar.reduced.beam_fe import uniform_line
    from rotorpillar.reduced.pillar import omega_euler_bernoulli, section_of, tip_mass_continuous
    from rotorpillar.reduced.pillar_modes import beam_properties
    from rotorpillar.reduced.reduction import _tower_closed_forms, pillar_closed_forms
    from rotorpillar.reduced.tower import tower_line

    scene = load_scene("paper")
    p, top = scene.pillar, scene.gondola.mass
    for theory in ("euler", "timoshenko"):
        uniform = beam_modes(uniform_line(beam_properties(p), 40), 40, theory, 4, tip_mass=top).omega
        general = beam_modes(tower_line(p, 40), 40, theory, 4, tip_mass=top).omega
        assert np.allclose(general, uniform, rtol=1e-10, atol=0), theory
    sec = section_of(p)
    eq1 = [
        omega_euler_bernoulli(p.youngs_modulus, sec.second_moment, sec.mass_per_length, p.height, k) for k in (1, 2, 3)
    ]
    ritz = rayleigh_ritz(p, terms=10)
    assert np.allclose(ritz.omega[:3], eq1, rtol=1e-9, atol=0)
    assert ritz.tip_mass == pytest.approx(tip_mass_continuous(sec.mass_per_length * p.height), rel=1e-9)
    today, forced = pillar_closed_forms(p), _tower_closed_forms(p, None)
    assert forced.omega_col1 == pytest.approx(today.omega_col1, rel=1e-9)
    assert forced.tip_mass_limit == pytest.approx(today.tip_mass_limit, rel=1e-9)
    assert forced.omega_col1_timoshenko == pytest.approx(today.omega_col1_timoshenko, rel=1e-5)


def test_the_blade_passing_order_is_drawn_at_k_times_the_speed():
    """Issue 27.3: a rotor of k blades excites its tower at k x its speed; the Campbell charts draw
    that order as the line omega = k Omega (1x is each chart's own line, so only 3x here)."""
    from matplotlib.figure import Figure

    from rotorpillar.postprocess.engineering_charts import order_lines

    ax = Figure().add_subplot()
    order_lines(ax, (1, 3), 12.0)
    (line,) = ax.lines
    x, y = (np.asarray(v, dtype=float) for v in line.get_data())
    assert x[0] == y[0] == 0.0 and y[-1] == 12.0 and y[-1] / x[-1] == pytest.approx(3.0, rel=1e-15)
    assert line.get_label().startswith("3x")


def test_the_overturning_stiffness_against_the_closed_form_and_a_quadrature():
    """sum(m g z): a uniform tube's m_t g H / 2 plus the tops' m g (H + h) (closed form), and a
    cone's against the trapezoidal rule on 20001 points (another method; its error ~ (H/n)**2
    relative, 1e-8 here, so 1e-6 holds)."""
    from rotorpillar.reduced.excitation import STANDARD_GRAVITY as g
    from rotorpillar.reduced.tower import overturning_stiffness

    s = load_scene("paper")
    p, H = s.pillar, s.pillar.height
    m_tube = p.density * math.pi / 4 * (p.outer_diameter**2 - p.inner_diameter**2) * H
    expected = g * (m_tube * H / 2 + (s.gondola.mass + s.rotor.mass) * H)  # paper: both tops at the top
    assert overturning_stiffness(s) == pytest.approx(expected, rel=1e-12)
    cone = tower(CONE)
    z = np.linspace(0.0, cone.pillar.height, 20001)
    sec = sections_along(cone.pillar, z, "above")
    tube = trapezoid(sec.mass_per_length * z, z)
    tops = (cone.gondola.mass + cone.rotor.mass) * cone.pillar.height
    assert overturning_stiffness(cone) == pytest.approx(g * (tube + tops), rel=1e-6)


@pytest.mark.parametrize(
    "sets, words",
    [
        # a rocking spring below sum(m g z) = 2.74e6 N m/rad on paper: the machine topples
        (
            ["foundation.kind=springs", "foundation.horizontal_stiffness=1e9", "foundation.rocking_stiffness=1e6"],
            "foundation.rocking_stiffness = 1e+06 is out of range: must be > the machine's overturning stiffness",
        ),
        # a 1 cm footing on paper's soil: K_R = 8 G R**3 / (3 (1 - nu)) = 190 N m/rad
        (
            ["foundation.kind=footing", "foundation.soil_shear_modulus=5e7", "foundation.soil_poisson_ratio=0.3"]
            + ["foundation.radius=0.01"],
            "foundation.radius = 0.01 with foundation.soil_shear_modulus = 5e+07",
        ),
        # deeper than wide: a caisson (and Gazetas' coupling would make the springs give energy)
        (
            ["foundation.kind=footing", "foundation.soil_shear_modulus=5e7", "foundation.soil_poisson_ratio=0.3"]
            + ["foundation.radius=3", "foundation.embedment=100"],
            "foundation.embedment = 100 is out of range: must be >= 0 and <= the footing's width",
        ),
    ],
    ids=["rocking", "small-footing", "deep-footing"],
)
def test_a_foundation_that_cannot_hold_the_machine_is_refused(tmp_path, capsys, sets, words):
    """Each case once crashed or ran on: a rocking spring of 1 N m/rad made the 3D modal solve
    fail (exit 1), an embedment of 1000 m an internal error (exit 70), a 1 cm footing ran."""
    from rotorpillar.cli import main

    out = tmp_path / "out"
    code = main(["analyze", "paper", *[a for s in sets for a in ("--set", s)], "--out", str(out)])
    err = capsys.readouterr().err.strip().splitlines()
    assert code == 2 and len(err) == 1 and words in err[0], err
    assert not out.exists() or not any(out.iterdir())
