"""The lumped thermal network of one bearing (a lumped model: one temperature per node).

Nodes: the film (mean film temperature T_f), the journal T_j, the foil (top foil and bumps)
T_b and the sleeve (bearing housing bore) T_s; the ambient T_a and the cooling inlet T_in are
given.  Heat generated in the film is the film's drag power P (all of the shear work becomes
heat in the gas).  Paths (conductances in W/K):

    film → journal           g_fj   (default: gas conduction across half the film, k A/(c/2))
    journal → shaft/ambient  g_ja   (stated)
    film → foil              g_fb   (default: gas conduction across half the film, k A/(c/2))
    foil → sleeve (bumps)    g_bs   (stated)
    sleeve → ambient         g_sa   (stated)
    foil → cooling flow      g_c = ṁ c_p ε,  ε = 1 − exp(−hA/(ṁ c_p))
    film → side leakage      g_l = ṁ_l c_p

The cooling flow: the mass flow ṁ enters the bump channels at T_in and flows along them past a
foil at the uniform temperature T_b (plug flow, a channel at constant wall temperature: the
NTU–effectiveness relation with NTU = hA/(ṁ c_p); hA not stated: ε = 1, the flow leaves fully
mixed at T_b, an upper bound of the cooling).  Heat taken: ṁ c_p (T_out − T_in),
T_out = T_in + ε (T_b − T_in).

The side leakage: the gas that leaves the film at its two ends (axial outflow ṁ_l) carries
c_p (T_f − T_a) per kg; the same mass enters from the ambient at T_a (sub-ambient zones and
the seam).  ṁ_l comes from the film's pressure (:func:`gfbopt.thermal.bearing.side_leakage`).

Heat balances, one per node (the 4 × 4 linear system of :func:`solve_network`):

    P = g_fj (T_f − T_j) + g_fb (T_f − T_b) + g_l (T_f − T_a)
    g_fj (T_f − T_j) = g_ja (T_j − T_a)
    g_fb (T_f − T_b) = g_bs (T_b − T_s) + g_c (T_b − T_in)
    g_bs (T_b − T_s) = g_sa (T_s − T_a)

What the lumped model leaves out: the temperature varying round the film and across it (a
thermohydrodynamic film), the temperature varying through the journal and the sleeve (each is
one uniform temperature), radiation, and heat carried along the shaft to the other bearing.
"""
from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Optional

import numpy as np

from ..errors import ParameterError

#: thermal conductivity of air at 300 K [W/(m K)] (Incropera & DeWitt, *Fundamentals of Heat
#: and Mass Transfer*, 6th ed., 2007, Table A.4)
AIR_CONDUCTIVITY = 0.0263
#: specific heat of air at constant pressure at 300 K [J/(kg K)] (same table)
AIR_SPECIFIC_HEAT = 1007.0
#: specific gas constant of dry air [J/(kg K)] (R/M, M = 28.965 g/mol)
AIR_GAS_CONSTANT = 287.05
#: 20 °C [K]
DEFAULT_AMBIENT_K = 293.15
#: the highest film temperature analysed [K] by default: the top of the range over which
#: Sutherland's law gives the viscosity of air within ±2 % (170–1900 K; White, F. M.,
#: *Viscous Fluid Flow*, 3rd ed., 2006, Table 1-2).  A film hotter than the limit has no
#: valid state in this model: the heat balance reports thermal runaway instead.  The foil's
#: own material limit (its coating, the top and bump foil alloy) is lower in practice and is
#: stated with ``max_film_temperature``.
SUTHERLAND_AIR_MAX_K = 1900.0
#: the lumped network's nodes, in the order of :func:`solve_network`
NODES = ("film", "journal", "foil", "sleeve")
SIDE_LEAKAGE_MODELS = ("film", "none")


@dataclass(frozen=True)
class JournalMaterial:
    """The journal's material and bore (the ``[journal]`` table), SI.

    density ρ [kg/m³], youngs_modulus E [Pa], poisson_ratio ν [-], expansion_coefficient α
    [1/K] (needed by the heat balance only; None: not stated), inner_radius a [m] (0: solid).
    """

    density: float
    youngs_modulus: float
    poisson_ratio: float
    expansion_coefficient: Optional[float] = None
    inner_radius: float = 0.0

    def check(self, radius: float, where: str = "journal") -> None:
        """The rules with the bearing's radius R [m]: 0 <= a < R."""
        for name in ("density", "youngs_modulus"):
            value = getattr(self, name)
            if not (isinstance(value, (int, float)) and value > 0 and math.isfinite(value)):
                raise ParameterError(f"{where}.{name}", value, "must be a finite number > 0 "
                                     "(the centrifugal growth needs it)")
        if not -1.0 < self.poisson_ratio < 0.5:
            raise ParameterError(f"{where}.poisson_ratio", self.poisson_ratio,
                                 "must lie in (-1, 0.5) (an isotropic solid)")
        if not 0.0 <= self.inner_radius < radius:
            raise ParameterError(f"{where}.inner_radius", self.inner_radius,
                                 f"must satisfy 0 <= inner_radius < the journal radius "
                                 f"{radius!r} m (0: a solid journal)")
        if self.expansion_coefficient is not None and not self.expansion_coefficient >= 0:
            raise ParameterError(f"{where}.expansion_coefficient", self.expansion_coefficient,
                                 "must be >= 0 [1/K]")


@dataclass(frozen=True)
class ThermalNetwork:
    """The ``[thermal]`` table: temperatures [K], conductances [W/K], flows [kg/s], gas
    properties.  None: the default named in the field's docs (module docstring)."""

    journal_to_ambient: float
    foil_to_sleeve: float
    sleeve_to_ambient: float
    sleeve_expansion_coefficient: float
    ambient_temperature: float = DEFAULT_AMBIENT_K
    reference_temperature: Optional[float] = None   # the cold clearance's; default T_a
    viscosity_temperature: Optional[float] = None   # where [bearing].viscosity holds; T_a
    film_to_journal: Optional[float] = None          # default k A/(c/2)
    film_to_foil: Optional[float] = None             # default k A/(c/2)
    cooling_mass_flow: float = 0.0
    cooling_inlet_temperature: Optional[float] = None   # default T_a
    cooling_conductance: Optional[float] = None      # hA; None: fully mixed (ε = 1)
    gas_conductivity: float = AIR_CONDUCTIVITY
    gas_specific_heat: float = AIR_SPECIFIC_HEAT
    gas_constant: float = AIR_GAS_CONSTANT
    sutherland_constant: float = 110.4
    side_leakage: str = "film"
    max_film_temperature: Optional[float] = None     # [K]; default SUTHERLAND_AIR_MAX_K

    def check(self, where: str = "thermal") -> None:
        """Temperatures > 0 K, conductances and flows >= 0, a path from the film to ambient."""
        for name in ("ambient_temperature", "reference_temperature", "viscosity_temperature",
                     "cooling_inlet_temperature"):
            value = getattr(self, name)
            if value is not None and not value > 0:
                raise ParameterError(f"{where}.{name}", value, "must be > 0 K (an absolute "
                                     "temperature: below 0 K is not a temperature)")
        for name in ("journal_to_ambient", "foil_to_sleeve", "sleeve_to_ambient",
                     "film_to_journal", "film_to_foil", "cooling_mass_flow",
                     "cooling_conductance"):
            value = getattr(self, name)
            if value is not None and not value >= 0:
                raise ParameterError(f"{where}.{name}", value, "must be >= 0 (a negative "
                                     "conductance or flow would carry heat against the "
                                     "temperature difference)")
        for name in ("sleeve_expansion_coefficient", "sutherland_constant"):
            if not getattr(self, name) >= 0:
                raise ParameterError(f"{where}.{name}", getattr(self, name), "must be >= 0")
        for name in ("gas_conductivity", "gas_specific_heat", "gas_constant"):
            if not getattr(self, name) > 0:
                raise ParameterError(f"{where}.{name}", getattr(self, name), "must be > 0")
        limit = self.max_film_temperature
        if limit is not None and not (math.isfinite(limit) and limit > self.ambient_temperature
                                      and limit > self.inlet_k):
            raise ParameterError(f"{where}.max_film_temperature", limit, "must be a finite "
                                 "temperature [K] above the ambient and cooling inlet "
                                 "temperatures")
        if self.side_leakage not in SIDE_LEAKAGE_MODELS:
            raise ParameterError(f"{where}.side_leakage", self.side_leakage,
                                 f"must be one of {', '.join(SIDE_LEAKAGE_MODELS)}")

    @property
    def film_limit_k(self) -> float:
        """The highest film temperature with a valid state [K] (``max_film_temperature``,
        default :data:`SUTHERLAND_AIR_MAX_K`)."""
        return SUTHERLAND_AIR_MAX_K if self.max_film_temperature is None \
            else self.max_film_temperature

    @property
    def film_limit_source(self) -> str:
        """Where :attr:`film_limit_k` comes from, in words."""
        return ("the top of Sutherland's law's range for air, White 2006 Table 1-2"
                if self.max_film_temperature is None else
                "[thermal].max_film_temperature")

    @property
    def reference_k(self) -> float:
        return self.ambient_temperature if self.reference_temperature is None \
            else self.reference_temperature

    @property
    def viscosity_k(self) -> float:
        return self.ambient_temperature if self.viscosity_temperature is None \
            else self.viscosity_temperature

    @property
    def inlet_k(self) -> float:
        return self.ambient_temperature if self.cooling_inlet_temperature is None \
            else self.cooling_inlet_temperature

    def conductances(self, radius: float, length: float, clearance: float,
                     leakage_flow: float = 0.0) -> "Conductances":
        """The resolved conductances [W/K] for a bearing of radius R, length L and (cold)
        clearance c [m], with a side-leakage mass flow ṁ_l [kg/s]."""
        wall = self.gas_conductivity * 2.0 * math.pi * radius * length / (0.5 * clearance)
        flow = self.cooling_mass_flow * self.gas_specific_heat
        if flow > 0 and self.cooling_conductance is not None:
            flow *= -math.expm1(-self.cooling_conductance / flow)   # ε = 1 − e^(−NTU)
        leak = leakage_flow * self.gas_specific_heat if self.side_leakage == "film" else 0.0
        return Conductances(
            film_to_journal=wall if self.film_to_journal is None else self.film_to_journal,
            journal_to_ambient=self.journal_to_ambient,
            film_to_foil=wall if self.film_to_foil is None else self.film_to_foil,
            foil_to_sleeve=self.foil_to_sleeve, sleeve_to_ambient=self.sleeve_to_ambient,
            cooling=flow, side_leakage=leak)


@dataclass(frozen=True)
class Conductances:
    """The network's conductances [W/K] (module docstring), resolved."""

    film_to_journal: float
    journal_to_ambient: float
    film_to_foil: float
    foil_to_sleeve: float
    sleeve_to_ambient: float
    cooling: float = 0.0
    side_leakage: float = 0.0

    def matrix(self) -> np.ndarray:
        """The 4 × 4 conductance matrix of the node balances (order :data:`NODES`)."""
        fj, ja, fb = self.film_to_journal, self.journal_to_ambient, self.film_to_foil
        bs, sa, gc, gl = self.foil_to_sleeve, self.sleeve_to_ambient, self.cooling, \
            self.side_leakage
        return np.array([[fj + fb + gl, -fj, -fb, 0.0],
                         [-fj, fj + ja, 0.0, 0.0],
                         [-fb, 0.0, fb + bs + gc, -bs],
                         [0.0, 0.0, -bs, bs + sa]])

    def check_connected(self, where: str = "thermal") -> None:
        """Every node reaches the ambient (else its temperature is undefined or the heat has
        nowhere to go): ParameterError naming the isolated node."""
        edges = {("film", "journal"): self.film_to_journal, ("film", "foil"): self.film_to_foil,
                 ("foil", "sleeve"): self.foil_to_sleeve}
        ground = {"journal": self.journal_to_ambient, "sleeve": self.sleeve_to_ambient,
                  "foil": self.cooling, "film": self.side_leakage}
        reached = {n for n, g in ground.items() if g > 0}
        grew = True
        while grew:
            grew = False
            for (a, b), g in edges.items():
                if g > 0 and (a in reached) != (b in reached):
                    reached |= {a, b}
                    grew = True
        for node in NODES:
            if node not in reached:
                raise ParameterError(f"{where}", node, "node of the thermal network has no "
                                     "path to the ambient (a conductance of 0 cuts it off): "
                                     "state a conductance > 0 on its path")


@dataclass(frozen=True)
class NetworkState:
    """The network solved for a heat input: temperatures [K] and heat flows [W]."""

    power_w: float
    film_k: float
    journal_k: float
    foil_k: float
    sleeve_k: float
    to_shaft_w: float
    to_housing_w: float
    to_cooling_w: float
    to_side_leakage_w: float
    cooling_outlet_k: float

    @property
    def heat_out_w(self) -> float:
        """Heat leaving to the ambient and the flows [W] (= power_w at a solved state)."""
        return self.to_shaft_w + self.to_housing_w + self.to_cooling_w + self.to_side_leakage_w


def solve_network(power_w: float, g: Conductances, ambient_k: float,
                  inlet_k: Optional[float] = None, cooling_flow_capacity: float = 0.0
                  ) -> NetworkState:
    """Temperatures of the nodes for a heat input P [W] in the film (module docstring).

    cooling_flow_capacity ṁ c_p [W/K] gives the cooling outlet T_out = T_in + (g_c/ṁc_p)
    (T_b − T_in); 0: no cooling flow (T_out = T_in)."""
    inlet = ambient_k if inlet_k is None else inlet_k
    # solved for the rises over the ambient (exactly 0 with no heat and an ambient inlet)
    rhs = np.array([power_w, 0.0, g.cooling * (inlet - ambient_k), 0.0])
    tf, tj, tb, ts = ambient_k + np.linalg.solve(g.matrix(), rhs)
    outlet = inlet if cooling_flow_capacity <= 0 else \
        inlet + g.cooling / cooling_flow_capacity * (tb - inlet)
    return NetworkState(power_w=float(power_w), film_k=float(tf), journal_k=float(tj),
                        foil_k=float(tb), sleeve_k=float(ts),
                        to_shaft_w=float(g.journal_to_ambient * (tj - ambient_k)),
                        to_housing_w=float(g.sleeve_to_ambient * (ts - ambient_k)),
                        to_cooling_w=float(g.cooling * (tb - inlet)),
                        to_side_leakage_w=float(g.side_leakage * (tf - ambient_k)),
                        cooling_outlet_k=float(outlet))
