"""Journal-centre orbits of a batch of rigid rotors: one driver, several integration methods.

=========  ===================================================================================
method     what it is
=========  ===================================================================================
rk4        classic explicit Runge–Kutta, batched over rotors (:mod:`.rk4`): the reference
rkc        damped second-order Runge–Kutta–Chebyshev, batched (:mod:`.rkc`): stages from the
           stiffness bound, step from accuracy; ≈ 15× fewer evaluations than RK4 at 144 × 36
bdf        scipy's implicit BDF with a sparse Jacobian, rotor by rotor (:mod:`.bdf`)
=========  ===================================================================================

Each method is one module with one ``integrate_*`` function of the same signature, listed in
:data:`METHODS` with the options it takes and, for the explicit methods, its step of a packed
system (``step(f, z, Δτ, stages)``).  :func:`check_method` validates a method and its options
once for every driver: :func:`integrate_orbits` (one bearing, a batch of rotors) dispatches to
the method's integrator; :func:`gfbopt.transient.rotor_run.integrate_rotor` (the whole rotor
on its bearings) advances with the method's step (explicit methods only: bdf is refused there).
"""
from __future__ import annotations

from dataclasses import dataclass
from typing import Callable, Optional

from ..errors import ParameterError
from ..threads import single_threaded
from .bdf import integrate_bdf
from .result import OrbitBatch, check_masses, check_positive
from .rk4 import integrate_rk4, rk4_array_step
from .rkc import integrate_rkc, rkc_step
from .system import State, TransientModel

@dataclass(frozen=True)
class Method:
    """One integration method: ``integrate`` the one-bearing batch integrator, ``options``
    the keyword options it accepts beyond the common ones, ``step`` one explicit step
    ``step(f, z, dt, stages) -> z`` of a packed system dz/dτ = f(z) (None: implicit).
    It unpacks as the pair ``(integrate, options)``, as the table's entries always did."""

    integrate: Callable
    options: tuple
    step: Optional[Callable] = None

    def __iter__(self):
        return iter((self.integrate, self.options))

    def __getitem__(self, k):
        return (self.integrate, self.options)[k]


#: method name → :class:`Method` (integrator, options, packed step)
METHODS: dict[str, Method] = {
    "rk4": Method(integrate_rk4, ("time_step", "check_every"), rk4_array_step),
    "rkc": Method(integrate_rkc, ("time_step", "stages", "check_every"), rkc_step),
    "bdf": Method(integrate_bdf, ("rtol", "atol")),
}


def check_method(method: str, options: dict, *, explicit: bool = False) -> Method:
    """The :class:`Method` named ``method``, after checking it and its ``options`` (a
    given option the method does not use is refused, not ignored; ``explicit``: a driver
    that needs the method's packed step refuses an implicit method)."""
    if method not in METHODS:
        raise ParameterError("method", method, f"must be one of {', '.join(METHODS)}")
    spec = METHODS[method]
    if explicit and spec.step is None:
        usable = ", ".join(m for m, s in METHODS.items() if s.step is not None)
        raise ParameterError("method", method, f"has no explicit step for this driver; "
                             f"one of {usable}")
    for key, value in options.items():
        if key not in spec.options and value is not None:
            users = [m for m, s in METHODS.items() if key in s.options]
            raise ParameterError(key, value, f"applies to method={'/'.join(users) or '?'} "
                                 f"only, not to method='{method}'")
    return spec


@single_threaded
def integrate_orbits(tm: TransientModel, mass, revolutions: float = 10.0, *,
                     kick: float = 1e-3, initial: Optional[State] = None,
                     sample_every: float = 0.2, contact_film: float = 0.02,
                     settle: float = 2.0, progress=None, method: str = "rk4",
                     **method_options) -> OrbitBatch:
    """Advance a batch of rotors (one per entry of ``mass``, M̄ = M c ω²/W0).

    Parameters
    ----------
    tm : the transient model (:func:`gfbopt.transient.system.transient_model`); with
        structural damping (η > 0) its foil is a Kelvin–Voigt state (:mod:`.foil_state`),
        supported by rk4 and rkc for both deflection laws and by bdf for the axial-mean law
    mass : M̄ of each rotor [-], > 0
    revolutions : length of the run in shaft revolutions [-]
    kick : initial journal velocity dX/dτ = dY/dτ = kick/√2 from the equilibrium [-]
    initial : a batch state to start from instead of the kicked equilibrium (with the foil
        state W of a damped model)
    sample_every : Δτ between stored samples [rad]
    contact_film : minimum film H at which a rotor is in contact; its run stops there [-]
    settle : revolutions skipped before fitting the growth rate [-]
    progress : optional callable(fraction in [0, 1]) for progress display
    method : a key of :data:`METHODS` ('rk4', 'rkc' or 'bdf').  The default stays 'rk4',
        the reference whose numbers the regression tier pins; the searches and the CLI
        default to 'rkc' (:data:`gfbopt.transient.critical_mass.DEFAULT_METHOD`: ≈ 13×
        faster at equal accuracy at 144 × 36, see that module).
    method_options : options of that method only — rk4: ``time_step`` Δτ [rad] (default
        from the stability bound; a step above the RK4 stability limit is refused),
        ``check_every`` (steps between re-checks of the bound); rkc: ``time_step`` (default
        chosen for accuracy), ``stages`` (default from the stiffness bound; a step or stage
        count outside the stability region is refused), ``check_every``; bdf: ``rtol``,
        ``atol``.  An option the chosen method does not use is refused, not ignored.

    Returns
    -------
    OrbitBatch, with ``success`` False and a message when the integration failed at run time.
    """
    if getattr(tm, "friction", None) is not None:       # bumps that rub: sliders beside the state
        from .friction_orbit import integrate_friction_orbits

        if method_options.get("stages") is not None:
            raise ParameterError("stages", method_options["stages"], "is not an option of the "
                                 "transient with bump friction (RKC's stages follow its bound)")
        method_options.pop("stages", None)
        return integrate_friction_orbits(
            tm, mass, revolutions, kick=kick, initial=initial, sample_every=sample_every,
            contact_film=contact_film, settle=settle, method=method,
            **{k: v for k, v in method_options.items() if v is not None}).orbit
    integrate = check_method(method, method_options).integrate
    options = {k: v for k, v in method_options.items() if v is not None}
    tm.law.check_engine(method, damped=tm.foil_state is not None)
    mass = check_masses(mass)
    revolutions = check_positive("revolutions", revolutions)
    return integrate(tm, mass, revolutions, kick=kick, initial=initial,
                     sample_every=sample_every, contact_film=contact_film, settle=settle,
                     progress=progress, **options)
