"""The lumped heat balance and its fixed point against hand solutions: a linear
network with a drag power law P = a ω²/c (solved by hand, a quadratic), its runaway speed,
the heat balance closing, and the limits (zero speed, very large conductances)."""
import math

import pytest

from gfbopt.errors import ParameterError
from gfbopt.thermal.growth import centrifugal_growth
from gfbopt.thermal.network import JournalMaterial, ThermalNetwork, solve_network
from gfbopt.thermal.running import (CENTRIFUGAL, HEAT_BALANCE, ISOTHERMAL, DragSample,
                                    RunningSpec, running_point, speed_line)

R, L, C0, MU, PA = 19.05e-3, 38.1e-3, 20e-6, 1.85e-5, 1.0e5
STEEL = JournalMaterial(density=7850.0, youngs_modulus=200e9, poisson_ratio=0.3,
                        expansion_coefficient=12e-6)
NET = ThermalNetwork(journal_to_ambient=0.8, foil_to_sleeve=2.0, sleeve_to_ambient=3.0,
                     sleeve_expansion_coefficient=6e-6, film_to_journal=10.0,
                     film_to_foil=8.0, cooling_mass_flow=2e-4, side_leakage="none",
                     ambient_temperature=300.0)
A = 4.5e-11            # P = a ω²/c: 50 W at 45,000 rpm and 20 µm [W m s²]


def omega(rpm):
    return rpm * math.pi / 30


def power_law(a=A):
    calls = []

    def drag(speed, c, mu, film_k):
        calls.append(speed)
        p = a * omega(speed) ** 2 / c
        petroff = 2 * math.pi * mu * omega(speed) ** 2 * R**3 * L / c
        return DragSample(p, p / petroff, 0.0, c, mu, film_k)
    drag.calls = calls
    return drag


def spec(network=NET, journal=STEEL):
    return RunningSpec(R, L, C0, MU, PA, journal, network)


def hand_rates(net=NET):
    """dT_j/dP, dT_s/dP [K/W] of the network by series/parallel resistances."""
    gc = net.cooling_mass_flow * net.gas_specific_heat          # fully mixed: ε = 1
    r_j = 1 / net.film_to_journal + 1 / net.journal_to_ambient
    r_sleeve = 1 / net.foil_to_sleeve + 1 / net.sleeve_to_ambient
    r_b = 1 / net.film_to_foil + 1 / (gc + 1 / r_sleeve)
    film = 1 / (1 / r_j + 1 / r_b)                                # T_f − T_a per watt
    journal = film / r_j / net.journal_to_ambient
    foil = film - film / r_b / net.film_to_foil
    sleeve = foil / r_sleeve / net.sleeve_to_ambient
    return film, journal, sleeve


def hand_fixed_point(rpm, a=A, net=NET):
    _, rj, rs = hand_rates(net)
    beta = STEEL.expansion_coefficient * R * rj - net.sleeve_expansion_coefficient * (R + C0) * rs
    c0 = C0 - centrifugal_growth(omega(rpm), R, 0.0, 7850.0, 200e9, 0.3)
    disc = c0**2 - 4 * beta * a * omega(rpm) ** 2
    return (c0 - math.sqrt(disc)) / (2 * beta), beta


def test_network_closes_and_matches_resistances():
    g = NET.conductances(R, L, C0)
    state = solve_network(37.0, g, 300.0, 300.0, NET.cooling_mass_flow * 1007.0)
    assert state.heat_out_w == pytest.approx(37.0, rel=1e-12)
    film, journal, sleeve = hand_rates()
    assert state.film_k - 300 == pytest.approx(37 * film, rel=1e-12)
    assert state.journal_k - 300 == pytest.approx(37 * journal, rel=1e-12)
    assert state.sleeve_k - 300 == pytest.approx(37 * sleeve, rel=1e-12)
    assert state.cooling_outlet_k == pytest.approx(state.foil_k, rel=1e-14)   # fully mixed
    # a finite channel: effectiveness 1 − e^(−NTU), heat = ṁ c_p (T_out − T_in)
    net = ThermalNetwork(**{**NET.__dict__, "cooling_conductance": 0.1})
    st = solve_network(37.0, net.conductances(R, L, C0), 300.0, 290.0, 2e-4 * 1007.0)
    assert st.to_cooling_w == pytest.approx(2e-4 * 1007.0 * (st.cooling_outlet_k - 290.0),
                                            rel=1e-12)
    assert st.heat_out_w == pytest.approx(37.0, rel=1e-12)


@pytest.mark.parametrize("rpm", [15_000.0, 30_000.0, 45_000.0])
def test_fixed_point_reproduces_hand_solution(rpm):
    drag = power_law()
    point = running_point(spec(), rpm, drag, tolerance_k=1e-9)
    p_hand, _ = hand_fixed_point(rpm)
    assert point.converged
    assert point.network.power_w == pytest.approx(p_hand, rel=1e-8)
    assert point.network.heat_out_w == pytest.approx(point.network.power_w, rel=1e-9)
    assert point.model == HEAT_BALANCE
    assert point.static_solves <= 6


def test_monotone_in_speed_and_balance_at_every_point():
    line = speed_line(spec(), [5e3, 15e3, 25e3, 35e3, 45e3], power_law())
    power = [p.network.power_w for p in line.points]
    film = [p.network.film_k for p in line.points]
    growth = [p.centrifugal_growth + p.thermal_growth for p in line.points]
    for series in (power, film, growth):
        assert all(b > a for a, b in zip(series, series[1:]))
    for p in line.points:
        assert p.network.heat_out_w == pytest.approx(p.network.power_w, rel=1e-9)
    # this law ignores μ while the predictor scales with it (the adversarial case): ≤ 3
    # solves per point at the default 0.01 K (measured 2, 2, 2, 3, 3)
    assert max(p.static_solves for p in line.points) <= 3


def test_runaway_speed_bracketed():
    """c0 − k ω² − β P = c, P = aω²/c has a root iff (c0 − kω²)² ≥ 4 β a ω²: runaway from
    ω* with k ω*² + 2 √(β a) ω* − c0 = 0."""
    a = 6 * A
    _, beta = hand_fixed_point(1000.0, a)
    k = centrifugal_growth(1.0, R, 0.0, 7850.0, 200e9, 0.3)
    w = (-math.sqrt(beta * a) + math.sqrt(beta * a + k * C0)) / k
    exact = w * 30 / math.pi
    line = speed_line(spec(), [0.5 * exact, 0.8 * exact, 1.2 * exact], power_law(a),
                      bracket=0.005)
    assert line.limit_kind == "runaway"
    assert line.limit_low_rpm <= exact <= line.limit_rpm
    assert line.limit_rpm / line.limit_low_rpm - 1 <= 0.01
    assert line.message.startswith("thermal runaway from")
    assert not line.points[-1].converged and "thermal runaway" in line.points[-1].message


def test_zero_speed_and_huge_conductances_are_ambient():
    still = running_point(spec(), 0.0, power_law())
    assert still.network.film_k == 300.0 and still.running_clearance == C0
    assert still.viscosity == MU
    big = ThermalNetwork(journal_to_ambient=1e15, foil_to_sleeve=1e15, sleeve_to_ambient=1e15,
                         film_to_journal=1e15, film_to_foil=1e15,
                         sleeve_expansion_coefficient=6e-6, ambient_temperature=300.0)
    hot = running_point(RunningSpec(R, L, C0, MU, PA, STEEL, big), 45e3, power_law())
    cold = running_point(RunningSpec(R, L, C0, MU, PA, STEEL), 45e3, power_law())
    assert hot.converged and abs(hot.network.film_k - 300.0) < 1e-10
    assert hot.running_clearance == pytest.approx(cold.running_clearance, rel=1e-10)
    assert hot.viscosity == pytest.approx(MU, rel=1e-10)


def test_models_named_and_centrifugal_closure():
    assert RunningSpec(R, L, C0, MU, PA).model_name == ISOTHERMAL
    assert RunningSpec(R, L, C0, MU, PA, STEEL).model_name == CENTRIFUGAL
    iso = running_point(RunningSpec(R, L, C0, MU, PA), 45e3, power_law())
    assert iso.running_clearance == C0 and iso.static_solves == 0
    soft = JournalMaterial(density=7850.0, youngs_modulus=2e9, poisson_ratio=0.3)
    line = speed_line(RunningSpec(R, L, C0, MU, PA, soft), [1e4, 3e4, 6e4], power_law())
    assert line.limit_kind == "closure"
    # u = ρω²b³(1 − ν)/(4E) = c0 − 1 µm (the floor)
    k = centrifugal_growth(1.0, R, 0.0, 7850.0, 2e9, 0.3)
    exact = math.sqrt((C0 - 1e-6) / k) * 30 / math.pi
    assert line.limit_low_rpm <= exact <= line.limit_rpm
    assert "journal reaches the foil" in line.message


@pytest.mark.parametrize("change, key", [
    (dict(journal_to_ambient=-1.0), "journal_to_ambient"),
    (dict(cooling_mass_flow=-1e-3), "cooling_mass_flow"),
    (dict(ambient_temperature=-5.0), "ambient_temperature"),
    (dict(journal_to_ambient=0.0, sleeve_to_ambient=0.0, cooling_mass_flow=0.0), "thermal")])
def test_bad_network_refused(change, key):
    with pytest.raises(ParameterError) as err:
        spec(ThermalNetwork(**{**NET.__dict__, **change}))
    assert key in str(err.value)


def test_bad_journal_refused():
    with pytest.raises(ParameterError, match="inner_radius"):
        spec(journal=JournalMaterial(7850.0, 200e9, 0.3, 12e-6, inner_radius=R))
    with pytest.raises(ParameterError, match="expansion_coefficient"):
        spec(journal=JournalMaterial(7850.0, 200e9, 0.3))
