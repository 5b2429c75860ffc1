"""Glossary entries of the bumps' Coulomb friction and hardening:
:mod:`gfbopt.linear.friction_onset` and :mod:`gfbopt.physics.friction`."""

TERMS = {
    "orbit_amplitude": ("-", "semi-major axis of the journal's whirl orbit at which the bumps' "
                        "friction is evaluated (describing function), in radial clearances"),
    "stuck_fraction": ("-", "share of the loaded foil units (θ rows or nodes) whose friction "
                       "slider stays stuck at that orbit amplitude"),
    "converged": ("-", "True when the mode shape and the friction's describing function "
                  "reached a fixed point"),
    "friction_coefficient": ("-", "Coulomb friction coefficient μ_f of the slider beside each "
                             "bump (slip force per unit area μ_f times the local gauge "
                             "pressure)"),
    "friction_stiffness_ratio": ("-", "stiffness of the friction element's spring over the "
                                 "bump's, κ = k_f/k_b (stuck foundation k_b (1 + κ))"),
    "hardening_exponent": ("-", "exponent n of the hardening bump k0/(1 − δ/δ_lim)^n (0: off)"),
    "hardening_limit": ("m", "deflection δ_lim at which the hardening bump is flat (<= the "
                        "bump height)"),
    "hardening_limit_ratio": ("-", "the hardening limit in radial clearances, W_lim = δ_lim/c "
                              "(the non-dimensional model's; hardening_limit is δ_lim in m)"),
    "bump_height": ("m", "bump height h_b, the hard limit of the hardening bump"),
}
