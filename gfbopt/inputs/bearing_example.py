"""The complete example of the bearing file (``docs/formats/bearing_file.md``,
:data:`gfbopt.inputs.file_schema.BEARING_FILE`): the Ruscitto bearing with its ``[model]``."""

BEARING_EXAMPLE = '''\
source = "Ruscitto, D., McCormick, J. & Gray, S. (1978), NASA CR-135368"

[bearing]
name = "Ruscitto et al. (1978)"
radius = 19.05e-3              # R [m]
length = 38.1e-3               # L [m]
radial_clearance = 20e-6       # c [m]
top_foil_thickness = 101.6e-6  # t_t [m]
bump_thickness = 101.6e-6      # t_b [m]
bump_pitch = 4.572e-3          # s [m]
bump_half_length = 1.778e-3    # l0 [m]
bump_youngs_modulus = 214e9    # E_b [Pa]
top_foil_youngs_modulus = 214e9  # E_t [Pa]
poisson_ratio = 0.29           # nu [-]
ambient_pressure = 1.0e5       # p_a [Pa]
viscosity = 2.98e-5            # mu [Pa s]

[model]
film = "seam"
seam_angle_deg = 180.0
foil = "simple"
deflection_law = "mean"
loss_factor = 0.0
'''
