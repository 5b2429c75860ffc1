"""Pointwise physics, written once, evaluating on numpy arrays and CasADi symbols alike.

=======================  ===============================================================
module                   what it holds
=======================  ===============================================================
:mod:`.film`             film thickness, the pressure that loads the journal (full/Gümbel)
:mod:`.foil_laws`        the registry of foil laws (rigid, simple axial-mean, local, beam)
:mod:`.beam`             Hermite finite elements of the top foil on the bump foundation
:mod:`.bump`             bump-foil geometry → compliance, stresses, sag (Heshmat)
:mod:`.closed_forms`     Ausman's small-eccentricity solution and the concentric impedance
=======================  ===============================================================
"""
