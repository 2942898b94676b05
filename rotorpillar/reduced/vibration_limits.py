"""The unbalance and the steady vibration at the running speed against the standards' limits.

Balance quality (ISO 21940-11:2016, *Rotor balancing - Procedures and
tolerances for rotors with rigid behaviour*, 4.4 and Table 1):

- the grade of a rotor with mass eccentricity e at its service speed Omega:
  G = e Omega, in mm/s (e in mm, Omega in rad/s);
- the permissible eccentricity of a required grade: e_per = G / Omega;
- the standard grades step by a factor of about 2.5: G 0.4, 1, 2.5, 6.3, 16,
  40, 100, 250, 630, 1600, 4000; Table 1 asks G 2.5 of gas and steam
  turbines, turbo-generators and compressors, G 6.3 of pumps, fans and
  general machinery.

Shaft vibration (API Standard 617, *Axial and centrifugal compressors and
expander-compressors*, 7th ed. 2.6.8.8, the limit of the shop test, which
the unbalance response analysis of 2.6.2 is verified against): the unfiltered
peak-to-peak shaft displacement relative to each radial bearing at the
maximum continuous speed N (rpm) is limited to

    A_vl = 25.4 sqrt(12000 / N) um, or 25.4 um, whichever is less

(1 mil = 25.4 um at and below 12000 rpm: the cap governs every machine
slower than that).

Housing vibration (ISO 20816-3:2022, *Industrial machinery with a power
rating above 15 kW and operating speeds between 120 r/min and 30000 r/min*,
Annex A, Table A.1, the values of ISO 10816-3:2009 Table A.1 carried over):
the broadband r.m.s. velocity on the bearing housing against the zone
boundaries, by machine group and support:

    group 1 (rated power above 300 kW)   rigid     A/B 2.3  B/C 4.5  C/D 7.1 mm/s
                                         flexible  A/B 3.5  B/C 7.1  C/D 11.0 mm/s
    group 2 (15 kW to 300 kW)            rigid     A/B 1.4  B/C 2.8  C/D 4.5 mm/s
                                         flexible  A/B 2.3  B/C 4.5  C/D 7.1 mm/s

Zone A: newly commissioned machines; B: unrestricted long-term operation;
C: not for long-term continuous operation; D: damage.  A support is rigid in
a direction when the lowest natural frequency of machine and support in it
is at least 25 % above the main excitation (the rotational frequency),
flexible otherwise (ISO 20816-3, 3.4).  The check here takes the B/C
boundary, the limit of unrestricted long-term operation.

A steady harmonic motion x = Re(X e^{i Omega t}) has the peak-to-peak 2 |X|
and the r.m.s. velocity Omega |X| / sqrt(2).

>>> round(balance_grade(0.002, 89.7), 1)
179.4
>>> grade_class(179.4)
'G 250'
>>> round(api617_shaft_limit(15000.0) * 1e6, 2), round(api617_shaft_limit(3000.0) * 1e6, 2)
(22.72, 25.4)
>>> iso20816_zone(5.0, ISO20816_3_BOUNDARIES[(1, "flexible")])
'B'
"""

from __future__ import annotations

import math

import numpy as np

from ..provenance import Record

#: ISO 21940-11 Table 1's balance quality grades (mm/s)
ISO_GRADES = (0.4, 1.0, 2.5, 6.3, 16.0, 40.0, 100.0, 250.0, 630.0, 1600.0, 4000.0)
#: ISO 21940-11 Table 1: gas and steam turbines, turbo-generators, compressors (mm/s)
GRADE_TURBO_GENERATOR = 2.5
#: API 617's reference speed (rpm) and its 1 mil cap (m)
API617_REFERENCE_RPM, API617_CAP = 12000.0, 25.4e-6
#: ISO 20816-3 Table A.1: (group, support) -> (A/B, B/C, C/D) r.m.s. velocity (mm/s)
ISO20816_3_BOUNDARIES: dict[tuple[int, str], tuple[float, float, float]] = {
    (1, "rigid"): (2.3, 4.5, 7.1),
    (1, "flexible"): (3.5, 7.1, 11.0),
    (2, "rigid"): (1.4, 2.8, 4.5),
    (2, "flexible"): (2.3, 4.5, 7.1),
}
#: ISO 20816-3's scope: rated power (W) and speeds (rpm)
ISO20816_3_POWER_MIN, ISO20816_3_GROUP1_POWER = 15e3, 300e3
ISO20816_3_SPEEDS = (120.0, 30000.0)
#: ISO 20816-3: a support is rigid when its lowest frequency is this far above the excitation
RIGID_SUPPORT_RATIO = 1.25


def rpm(omega: float) -> float:
    """Omega (rad/s) in revolutions per minute."""
    return omega * 30.0 / math.pi


# --------------------------------------------------------------------------
# Balance quality (ISO 21940-11)


def balance_grade(eccentricity: float, omega: float) -> float:
    """ISO 21940-11: G = e Omega (mm/s), e the mass centre's eccentricity (m), Omega (rad/s)."""
    return 1e3 * eccentricity * omega


def permissible_eccentricity(grade: float, omega: float) -> float:
    """ISO 21940-11: e_per = G / Omega (m), G (mm/s), Omega (rad/s)."""
    return 1e-3 * grade / omega


def grade_class(grade: float) -> str | None:
    """The finest standard grade the rotor meets: the smallest G of Table 1 not below
    ``grade`` (mm/s), e.g. "G 250"; None beyond G 4000."""
    for g in ISO_GRADES:
        if grade <= g * (1 + 1e-12):
            return f"G {g:g}"
    return None


class BalanceQuality(Record):
    """The rotor's unbalance as a balance quality grade (ISO 21940-11)."""

    eccentricity: float
    """e, the mass centre's distance from the axis (m)"""
    running_speed: float
    """Omega, the service speed the grade is taken at (rad/s)"""
    grade: float
    """G = e Omega (mm/s)"""
    grade_class: str | None
    """the finest standard grade it meets, e.g. "G 250" (None: coarser than G 4000)"""
    required: float
    """the grade required of the machine type (rotor.balance_grade) (mm/s)"""
    permissible_eccentricity: float
    """e_per = G_required / Omega (m)"""
    clause: str
    """where the rule is"""


def balance_quality(eccentricity: float, omega: float, required: float) -> BalanceQuality:
    """The grade of ``eccentricity`` (m) at ``omega`` (rad/s) beside the ``required`` (mm/s)."""
    g = balance_grade(eccentricity, omega)
    return BalanceQuality(
        float(eccentricity),
        float(omega),
        float(g),
        grade_class(g),
        float(required),
        permissible_eccentricity(required, omega),
        "ISO 21940-11:2016, 4.4 (G = e Omega) and Table 1",
    )


# --------------------------------------------------------------------------
# Shaft vibration (API 617)


def api617_shaft_limit(speed_rpm: float) -> float:
    """API 617: A_vl = 25.4 sqrt(12000 / N) um or 25.4 um, whichever is less (m), N (rpm)."""
    return API617_CAP * min(math.sqrt(API617_REFERENCE_RPM / speed_rpm), 1.0)


def orbit_peak_to_peak(x: complex, y: complex) -> float:
    """Peak-to-peak of the orbit x = Re(X e^{i theta}), y = Re(Y e^{i theta}) along its
    major axis (m): twice the larger singular value of [[Re X, Im X], [Re Y, Im Y]],
    the most any probe direction reads."""
    r = np.array([[x.real, x.imag], [y.real, y.imag]])
    return 2.0 * float(np.linalg.svd(r, compute_uv=False)[0])


class ShaftVibration(Record):
    """The steady shaft displacement relative to its bearing at the running speed (API 617)."""

    running_speed: float
    """Omega (rad/s)"""
    speed_rpm: float
    """N (rpm)"""
    peak_to_peak_x: float
    """2 |d_x|, in the rotor's plane (m)"""
    peak_to_peak_y: float
    """2 |d_y|, normal to it (m)"""
    peak_to_peak: float
    """along the orbit's major axis, the largest a probe reads (m)"""
    limit: float
    """A_vl (m)"""
    clause: str
    """where the limit is"""


def shaft_vibration(omega: float, shaft_x: complex, shaft_y: complex) -> ShaftVibration:
    """The shaft's steady orbit (complex amplitudes, m) at ``omega`` (rad/s) against API 617."""
    n = rpm(omega)
    return ShaftVibration(
        float(omega),
        n,
        2.0 * abs(shaft_x),
        2.0 * abs(shaft_y),
        orbit_peak_to_peak(shaft_x, shaft_y),
        api617_shaft_limit(n),
        "API 617 7th ed. 2.6.8.8: 25.4 sqrt(12000/N) um or 25.4 um, whichever is less",
    )


# --------------------------------------------------------------------------
# Housing vibration (ISO 20816-3)


def rms_velocity(amplitude: float, omega: float) -> float:
    """Omega |X| / sqrt(2): the r.m.s. velocity of a harmonic motion of amplitude |X| (m/s)."""
    return omega * amplitude / math.sqrt(2.0)


def machine_group(power: float) -> int | None:
    """ISO 20816-3's group of a machine of rated ``power`` (W): 1 above 300 kW, 2 from
    15 kW; None below (outside its scope)."""
    if power > ISO20816_3_GROUP1_POWER:
        return 1
    return 2 if power >= ISO20816_3_POWER_MIN else None


def support_class(first_frequency: float, excitation: float) -> str:
    """ "rigid" when the lowest natural frequency of machine and support is at least 25 %
    above the excitation (both rad/s, or both Hz), else "flexible" (ISO 20816-3)."""
    return "rigid" if first_frequency >= RIGID_SUPPORT_RATIO * excitation else "flexible"


def iso20816_zone(velocity: float, boundaries: tuple[float, float, float]) -> str:
    """The zone "A" ... "D" of an r.m.s. velocity against (A/B, B/C, C/D), same units."""
    for zone, top in zip("ABC", boundaries):
        if velocity <= top:
            return zone
    return "D"


class HousingVibration(Record):
    """The bearing housing's (the pillar top's) steady r.m.s. velocity against ISO 20816-3."""

    running_speed: float
    """Omega (rad/s)"""
    velocity_rms: float
    """Omega |tip X| / sqrt(2), in the rotor's plane (mm/s)"""
    power: float
    """the rated power the group is taken from: the drive's torque times Omega (W)"""
    group: int | None
    """ISO 20816-3's machine group (1: above 300 kW; 2: 15-300 kW; None: outside its scope)"""
    first_frequency: float
    """the lowest natural frequency of machine and support in the rotor's plane (rad/s)"""
    support: str
    """"rigid" or "flexible" (ISO 20816-3: rigid when first_frequency >= 1.25 Omega)"""
    boundaries: tuple[float, float, float] | None
    """zone boundaries A/B, B/C, C/D of Table A.1 (mm/s); None outside its scope"""
    zone: str | None
    """"A" ... "D" (None outside its scope)"""
    limit: float | None
    """the B/C boundary: the limit of unrestricted long-term operation (mm/s)"""
    clause: str
    """where the limits are, and what is outside the standard's scope"""


def housing_vibration(omega: float, tip_amplitude: float, power: float, first_frequency: float) -> HousingVibration:
    """The top's steady amplitude (m) at ``omega`` (rad/s) against ISO 20816-3's zones."""
    v = 1e3 * rms_velocity(tip_amplitude, omega)
    group = machine_group(power)
    support = support_class(first_frequency, omega)
    n = rpm(omega)
    lo, hi = ISO20816_3_SPEEDS
    clause = f"ISO 20816-3:2022 Annex A, Table A.1, group {group}, {support} support"
    if group is None:
        clause = f"outside ISO 20816-3: rated power {power / 1e3:.3g} kW below 15 kW"
    elif not lo <= n <= hi:
        clause += f" (the speed, {n:.4g} rpm, is outside its {lo:g}-{hi:g} rpm)"
    bounds = None if group is None else ISO20816_3_BOUNDARIES[(group, support)]
    return HousingVibration(
        float(omega),
        float(v),
        float(power),
        group,
        float(first_frequency),
        support,
        bounds,
        None if bounds is None else iso20816_zone(v, bounds),
        None if bounds is None else bounds[1],
        clause,
    )
