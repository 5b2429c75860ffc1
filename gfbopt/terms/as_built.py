"""Drag torque and the bearing as built (gfbopt.inputs.bore, gfbopt.physics.torque,
gfbopt.rotor.capacity, gfbopt.studies.bearing_as_built)."""

TERMS = {
    "torque_ratio": ("-", "drag torque on the journal over Petroff's, T / (2π μ ω R³ L / c) "
                     "(1 for a concentric journal in a round bore)"),
    "couette_torque_ratio": ("-", "the Couette (journal-motion shear) part of torque_ratio"),
    "drag_torque_nm": ("N m", "drag torque on the journal: the torque the drive supplies per "
                       "bearing"),
    "power_loss_w": ("W", "power lost in the film per bearing, drag torque × ω"),
    "petroff_power_w": ("W", "Petroff's power loss of the concentric journal, "
                        "2π μ ω² R³ L / c"),
    "preload_depth_um": ("µm", "mechanical preload depth (shim thickness or lobe depth)"),
    "preload_ratio": ("-", "preload depth over the radial clearance"),
    "bore": ("text", "bore profile: round, shims, lobes or table"),
    "n_pads": ("-", "number of top-foil pads"),
    "n_shims": ("-", "number of shims (or lobes) of the bore"),
    "min_film_limit_um": ("µm", "smallest minimum film allowed"),
    "load_capacity_newton": ("N", "largest static load carried with h_min ≥ the limit"),
    "lift_off_speed_rpm": ("rpm", "lowest speed at which the load is carried with h_min ≥ "
                           "the limit"),
}
