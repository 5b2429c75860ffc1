"""The flexible shaft's Timoshenko elements against closed forms (gfbopt.rotor.shaft).

Steel (E = 211 GPa, ρ = 7810 kg/m³, ν = 0.3); "massless" shafts have ρ = 1e-6 kg/m³
(their mass, ~1e-10 kg, is 1e-11 of the disk's: below every tolerance here)."""
import math

import numpy as np
import pytest
from scipy.linalg import eig, eigh

from gfbopt.errors import ParameterError
from gfbopt.inputs.shaft_file import Disk, ShaftElement, ShaftModel
from gfbopt.rotor.beam_element import section, shear_coefficient
from gfbopt.rotor.shaft import build_shaft
from gfbopt.rotor.structure import Structure

E, RHO, NU = 211e9, 7810.0, 0.3
G_MOD = E / (2 * (1 + NU))


def _shaft(n, length, d, di=0.0, rho=RHO, disks=(), positions=(), shear=True):
    el = ShaftElement(length / n, d, rho, E, di, NU)
    return build_shaft(ShaftModel((el,) * n, tuple(disks)), positions, shear=shear)


def _keep(s, fixed):
    """The degrees of freedom left after fixing ``fixed`` (global indices)."""
    return [i for i in range(s.size) if i not in set(fixed)]


def _pinned_frequencies(s, count):
    n = len(s.nodes) - 1
    keep = _keep(s, (0, 1, 4 * n, 4 * n + 1))
    k, m = s.stiffness()[np.ix_(keep, keep)], s.mass()[np.ix_(keep, keep)]
    w = np.sqrt(eigh(k, m, eigvals_only=True))
    return w[::2][:count]                       # x and y planes give each frequency twice


def test_structure_contract():
    s = _shaft(4, 0.4, 0.02)
    assert isinstance(s, Structure) and s.kind == "shaft" and s.size == 20
    assert s.dof_names[:4] == ("x_0", "y_0", "psi_x_0", "psi_y_0")
    g = s.gyroscopic()
    assert np.allclose(g, -g.T) and np.allclose(s.mass(), s.mass().T)
    assert np.allclose(s.stiffness(), s.stiffness().T)


def test_pinned_pinned_euler_bernoulli_beam_to_0p1_percent():
    """(nπ/L)² √(EI/ρA), 20 Euler–Bernoulli elements; L/d = 100, so the rotary inertia in
    the element (not in the closed form) lowers mode 3 by (3π r/L)²/2 = 1.4e-4 only."""
    length, d = 1.0, 0.01
    area, inertia = section(d, 0.0)
    w = _pinned_frequencies(_shaft(20, length, d, shear=False), 3)
    exact = [(n * math.pi / length) ** 2 * math.sqrt(E * inertia / (RHO * area))
             for n in (1, 2, 3)]
    assert np.allclose(w, exact, rtol=1e-3, atol=0)
    assert abs(w[2] / exact[2] - 1) > 1e-5       # the check sees the discretisation


def _timoshenko_pinned(n, length, d):
    """Lower root of (κGA k² − ρAω²)(EI k² + κGA − ρIω²) = (κGA k)², k = nπ/L (simply
    supported Timoshenko beam)."""
    area, inertia = section(d, 0.0)
    kga = shear_coefficient(0.0, d, NU) * G_MOD * area
    k = n * math.pi / length
    a = RHO * area * RHO * inertia
    b = -(RHO * area * (E * inertia * k**2 + kga) + RHO * inertia * kga * k**2)
    c = kga * k**2 * (E * inertia * k**2 + kga) - (kga * k) ** 2
    return math.sqrt((-b - math.sqrt(b * b - 4 * a * c)) / (2 * a))


def test_timoshenko_shear_correction_against_closed_form():
    """L/d = 5: shear and rotary inertia lower mode 3 by 17 % from Euler–Bernoulli.  The
    elements converge to the exact frequency equation as h² (Φ ∝ 1/h² makes a short
    element's interpolation linear; the same standard element as ROSS's): measured 1.7e-5,
    2.1e-4, 8.0e-4 above it for modes 1–3 with 40 elements, 4.2e-6, 5.2e-5, 2.0e-4 with 80;
    the check asks 80 elements for 3e-4 and the error's ratio 4 ± 2 % between the two."""
    length, d = 0.5, 0.1
    exact = np.array([_timoshenko_pinned(n, length, d) for n in (1, 2, 3)])
    err40 = _pinned_frequencies(_shaft(40, length, d), 3) / exact - 1
    err80 = _pinned_frequencies(_shaft(80, length, d), 3) / exact - 1
    assert np.all((err80 > 0) & (err80 < 3e-4))
    assert np.allclose(err40 / err80, 4.0, rtol=0.02)
    eb = _pinned_frequencies(_shaft(40, length, d, shear=False), 3)
    assert np.all(eb / exact - 1 > 0.03)


def _condensed(s, fixed, keep):
    """K condensed onto ``keep`` (massless shaft: Guyan reduction is exact)."""
    free = _keep(s, fixed)
    inner = [i for i in free if i not in keep]
    k = s.stiffness()
    kdd, kdi, kii = k[np.ix_(keep, keep)], k[np.ix_(keep, inner)], k[np.ix_(inner, inner)]
    return kdd - kdi @ np.linalg.solve(kii, kdi.T)


def test_jeffcott_central_disk_on_pinned_shaft():
    """k = 1/(L³/48EI + L/4κGA) (the Timoshenko element is exact for the static beam),
    ω = √(k/m) to 1e-8; with shear off k = 48 EI/L³."""
    length, d, mass = 0.5, 0.02, 10.0
    area, inertia = section(d, 0.0)
    kga = shear_coefficient(0.0, d, NU) * G_MOD * area
    for shear, k_exact in ((False, 48 * E * inertia / length**3),
                           (True, 1 / (length**3 / (48 * E * inertia) + length / (4 * kga)))):
        s = _shaft(10, length, d, rho=1e-6, disks=(Disk(0.25, mass, 0.01, 0.02),),
                   shear=shear)
        c = s.node_index(0.25)
        n = len(s.nodes) - 1
        keep = [4 * c, 4 * c + 1, 4 * c + 2, 4 * c + 3]
        k = _condensed(s, (0, 1, 4 * n, 4 * n + 1), keep)
        m = s.mass()[np.ix_(keep, keep)]
        w = np.sort(np.sqrt(eigh(k, m, eigvals_only=True)))
        assert w[0] == pytest.approx(math.sqrt(k_exact / mass), rel=1e-8)
        assert k[0, 0] == pytest.approx(k_exact, rel=1e-9)


def test_overhung_disk_forward_and_backward_whirl():
    """A disk at the end of a massless cantilever, spinning at ω: the closed-form 2 × 2
    flexibility problem det[[k11 − mΩ², k12], [k12, k22 − I_t Ω² + I_p ω Ω]] = 0 (x + iy ∝
    e^{iΩt}: Ω > 0 forward, < 0 backward), F = [[L³/3EI + L/κGA, L²/2EI], [L²/2EI, L/EI]]."""
    length, d = 0.3, 0.025
    m, it, ip, omega = 5.0, 0.02, 0.035, 2000.0
    area, inertia = section(d, 0.0)
    kga = shear_coefficient(0.0, d, NU) * G_MOD * area
    ei = E * inertia
    flex = np.array([[length**3 / (3 * ei) + length / kga, length**2 / (2 * ei)],
                     [length**2 / (2 * ei), length / ei]])
    (k11, k12), (_, k22) = np.linalg.inv(flex)
    # (k11 − mΩ²)(k22 − I_t Ω² + I_p ω Ω) − k12² = 0, a quartic in Ω
    poly = np.polymul([-m, 0.0, k11], [-it, ip * omega, k22]) - np.array([0, 0, 0, 0, k12**2])
    roots = np.sort(np.roots(poly).real)
    s = _shaft(6, length, d, rho=1e-6, disks=(Disk(length, m, it, ip),))
    tip = len(s.nodes) - 1
    keep = [4 * tip + j for j in range(4)]
    k = _condensed(s, (0, 1, 2, 3), keep)
    mm, g = s.mass()[np.ix_(keep, keep)], s.gyroscopic()[np.ix_(keep, keep)]
    z = np.zeros((4, 4))
    a = np.block([[z, np.eye(4)], [-np.linalg.solve(mm, k), -np.linalg.solve(mm, omega * g)]])
    lam, vec = eig(a)
    fe = []
    for val, v in zip(lam, vec.T):
        if val.imag > 0:
            x, y = v[0], v[1]                  # forward: ŷ = −i x̂, |x̂ + iŷ| > |x̂ − iŷ|
            sign = 1.0 if abs(x + 1j * y) > abs(x - 1j * y) else -1.0
            fe.append(sign * val.imag)
    assert np.allclose(np.sort(fe), roots, rtol=1e-8, atol=0)
    assert roots[0] < 0 < roots[-1] and abs(roots[-1]) > abs(roots[0])   # gyroscopic split


def test_free_free_has_four_rigid_body_modes_and_the_rigid_inertia():
    """Free–free: four zero frequencies (two translations, two tilts), the fifth a bending
    mode; the rigid-body motions carry exactly the model's mass and inertia about the CG."""
    el = [ShaftElement(0.1, 0.03, RHO, E, 0.01, NU), ShaftElement(0.2, 0.02, RHO, E)]
    model = ShaftModel(tuple(el), (Disk(0.05, 2.0, 0.004, 0.007),
                                   Disk(0.27, 1.0, 0.001, 0.002)))
    s = build_shaft(model)
    w2 = eigh(s.stiffness(), s.mass(), eigvals_only=True)
    assert np.all(np.abs(w2[:4]) < 1e-9 * w2[4]) and w2[4] > 1e4
    zg = s.centre_of_gravity
    trans = np.zeros(s.size)
    trans[0::4] = 1.0
    tilt = np.zeros(s.size)
    tilt[0::4] = np.array(s.nodes) - zg
    tilt[2::4] = 1.0
    m = s.mass()
    assert trans @ m @ trans == pytest.approx(model.total_mass, rel=1e-12)
    assert tilt @ m @ tilt == pytest.approx(model.transverse_inertia, rel=1e-12)
    assert trans @ m @ tilt == pytest.approx(0.0, abs=1e-12 * model.total_mass)
    tilt_y = np.roll(tilt, 1)                   # the same rigid tilt in the y–z plane
    assert tilt @ s.gyroscopic() @ tilt_y == pytest.approx(model.polar_inertia, rel=1e-12)


def test_station_between_nodes_is_the_static_beam():
    """A cantilever under a tip load: w(z) = P z²(3L − z)/6EI + P z/κGA, reproduced between
    nodes by the element's interpolation (exact for the static Timoshenko beam)."""
    length, d, p = 0.4, 0.02, 100.0
    area, inertia = section(d, 0.0)
    kga = shear_coefficient(0.0, d, NU) * G_MOD * area
    s = _shaft(4, length, d)
    free = _keep(s, (0, 1, 2, 3))
    f = s.station(length).T @ np.array([p, 0.0])
    q = np.zeros(s.size)
    q[free] = np.linalg.solve(s.stiffness()[np.ix_(free, free)], f[free])
    for z in (0.03, 0.1, 0.27, 0.4):
        exact = p * z**2 * (3 * length - z) / (6 * E * inertia) + p * z / kga
        assert (s.station(z) @ q)[0] == pytest.approx(exact, rel=1e-10)
        assert (s.station(z) @ q)[1] == 0.0


def test_positions_insert_nodes_and_off_shaft_is_refused():
    s = _shaft(4, 0.4, 0.02, positions=(0.13, 0.2 + 1e-12))
    assert 0.13 in s.nodes and len(s.nodes) == 6     # 0.2 + 1e-12 is the node at 0.2
    assert s.node_index(0.13) == 2
    assert sum(e.length for e in s.elements) == pytest.approx(0.4, rel=1e-15)
    with pytest.raises(ParameterError, match="must lie on the shaft"):
        _shaft(4, 0.4, 0.02, positions=(0.41,))
    with pytest.raises(ParameterError, match="must lie on the shaft"):
        s.station(-0.01)
