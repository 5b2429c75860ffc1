"""The ``[journal]`` and ``[thermal]`` tables of the bearing file (the clearance at speed,
:mod:`gfbopt.thermal`), defined with :mod:`gfbopt.inputs.file_schema`'s Field and Table.

``[journal]`` alone switches on the journal's centrifugal growth; ``[thermal]`` (which needs
``[journal]``) switches on the heat balance.  A file with neither keeps the isothermal,
cold-clearance answers.  :func:`gfbopt.thermal.files.running_spec` builds the
:class:`~gfbopt.thermal.running.RunningSpec` of a bearing from the checked tables (this module
imports only the schema: the inputs floor stays below gfbopt.thermal).
"""
from __future__ import annotations

from .file_schema import Field, Table

#: lowest temperature [K] a [thermal] key accepts: the bottom of the range over which
#: Sutherland's law gives the viscosity of air within ±2 % (170–1900 K; White, F. M.,
#: *Viscous Fluid Flow*, 3rd ed., 2006, Table 1-2; gfbopt.thermal.network's top,
#: SUTHERLAND_AIR_MAX_K).  A value below it is almost surely degrees Celsius typed as kelvin.
SUTHERLAND_AIR_MIN_K = 170.0
_WHY_T = ("the unit is kelvin: 20 °C is 293.15 K; Sutherland's law for air holds from 170 K, "
          "White 2006 Table 1-2")
_WHY_G = "a conductance: a negative one would carry heat against the temperature difference"

#: the ``[journal]`` table: the journal's material and bore
JOURNAL = Table("journal", "the journal's material and bore: stating it switches on the "
                "journal's centrifugal growth (Lamé, plane stress) in the running clearance",
                fields=(
    Field("density", "number", "kg/m³", "journal density ρ", positive=True,
          why="the centrifugal growth needs it"),
    Field("youngs_modulus", "number", "Pa", "journal Young's modulus E", low=1e6, high=1e13,
          why="a solid: 1 MPa to 10 TPa"),
    Field("poisson_ratio", "number", "-", "journal Poisson's ratio ν", low=-0.999,
          high=0.499, why="an isotropic solid has -1 < ν < 0.5"),
    Field("expansion_coefficient", "number", "1/K", "journal thermal expansion coefficient "
          "α_j (required with [thermal])", default=None, low=0.0, high=1e-3,
          why="solids: 0 to 1e-3 1/K"),
    Field("inner_radius", "number", "m", "journal bore radius a (0: a solid journal)",
          default=0.0, low=0.0, why="a radius"),
), rules=("inner_radius < [bearing] radius (a hollow journal has a wall)",))

#: the ``[thermal]`` table: the lumped thermal network of the bearing
THERMAL = Table("thermal", "the lumped thermal network of the bearing (film, journal, foil "
                "and sleeve temperatures; heat generated = the film's drag power): stating it "
                "switches on the heat balance, solved with the growths and Sutherland's "
                "viscosity to a fixed point at each speed", fields=(
    Field("journal_to_ambient", "number", "W/K", "conductance journal → shaft and ambient "
          "g_ja", low=0.0, why=_WHY_G),
    Field("foil_to_sleeve", "number", "W/K", "conductance top foil and bumps → sleeve "
          "g_bs", low=0.0, why=_WHY_G),
    Field("sleeve_to_ambient", "number", "W/K", "conductance sleeve (housing) → ambient "
          "g_sa", low=0.0, why=_WHY_G),
    Field("sleeve_expansion_coefficient", "number", "1/K", "expansion coefficient of the "
          "sleeve (bearing housing bore) α_s", low=0.0, high=1e-3,
          why="solids: 0 to 1e-3 1/K"),
    Field("ambient_temperature", "number", "K", "ambient temperature T_a",
          default=293.15, low=SUTHERLAND_AIR_MIN_K, why=_WHY_T),
    Field("reference_temperature", "number", "K", "temperature at which radial_clearance is "
          "stated (default: ambient_temperature)", default=None, low=SUTHERLAND_AIR_MIN_K,
          why=_WHY_T),
    Field("viscosity_temperature", "number", "K", "temperature at which [bearing] viscosity "
          "holds (default: ambient_temperature)", default=None, low=SUTHERLAND_AIR_MIN_K,
          why=_WHY_T),
    Field("film_to_journal", "number", "W/K", "conductance film → journal g_fj (default: "
          "gas conduction across half the film, k 2πRL/(c/2))", default=None, low=0.0,
          why=_WHY_G),
    Field("film_to_foil", "number", "W/K", "conductance film → top foil g_fb (default: gas "
          "conduction across half the film, k 2πRL/(c/2))", default=None, low=0.0,
          why=_WHY_G),
    Field("cooling_mass_flow", "number", "kg/s", "cooling flow ṁ through the bump channels",
          default=0.0, low=0.0, why="a mass flow"),
    Field("cooling_inlet_temperature", "number", "K", "cooling flow inlet temperature T_in "
          "(default: ambient_temperature)", default=None, low=SUTHERLAND_AIR_MIN_K,
          why=_WHY_T),
    Field("cooling_conductance", "number", "W/K", "hA of the bump channels: effectiveness "
          "1 − exp(−hA/(ṁ c_p)) (default: the flow leaves fully mixed at the foil "
          "temperature)", default=None, low=0.0, why=_WHY_G),
    Field("gas_conductivity", "number", "W/(m K)", "gas thermal conductivity k (air at "
          "300 K, Incropera & DeWitt Table A.4)", default=0.0263, positive=True),
    Field("gas_specific_heat", "number", "J/(kg K)", "gas specific heat c_p (air at 300 K, "
          "Incropera & DeWitt Table A.4)", default=1007.0, positive=True),
    Field("gas_constant", "number", "J/(kg K)", "specific gas constant R_g (dry air)",
          default=287.05, positive=True),
    Field("sutherland_constant", "number", "K", "Sutherland's constant S (air: U.S. "
          "Standard Atmosphere 1976)", default=110.4, low=0.0),
    Field("side_leakage", "choice", "text", "film: the gas leaving the film's ends carries "
          "c_p (T_f − T_a) per kg (flow from the film's pressure); none: left out",
          default="film", choices=("film", "none")),
    Field("max_film_temperature", "number", "K", "highest film temperature with a valid "
          "state, e.g. the foil's material limit (not stated: 1900 K, the top of Sutherland's "
          "range for air, White 2006 Table 1-2); above it the answer is thermal runaway",
          default=None, low=SUTHERLAND_AIR_MIN_K, why=_WHY_T),
), rules=("needs a [journal] table with expansion_coefficient",
          "every node (film, journal, foil, sleeve) has a path of conductances > 0 to the "
          "ambient"))

#: the tables the clearance at speed adds to the bearing file
RUNNING_TABLES = (JOURNAL, THERMAL)


#: the example's tail: a steel journal and a heat balance (appended to the bearing file's)
RUNNING_EXAMPLE = '''
[journal]                      # optional: centrifugal growth of the journal
density = 7850.0               # rho [kg/m3]
youngs_modulus = 200e9         # E [Pa]
poisson_ratio = 0.3            # nu [-]
expansion_coefficient = 12e-6  # alpha_j [1/K]
inner_radius = 0.0             # a [m], 0: solid

[thermal]                      # optional: the heat balance (needs [journal])
ambient_temperature = 293.15   # T_a [K]
journal_to_ambient = 0.5       # g_ja [W/K]
foil_to_sleeve = 2.0           # g_bs [W/K]
sleeve_to_ambient = 3.0        # g_sa [W/K]
sleeve_expansion_coefficient = 12e-6  # alpha_s [1/K]
cooling_mass_flow = 0.0        # [kg/s] through the bump channels
'''
