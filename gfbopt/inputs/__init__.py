"""Inputs: the bearing in SI, the non-dimensional model and formulation, the grid, and every
SI ↔ non-dimensional conversion (:mod:`.conversions`, the only place they meet)."""
from .bearing import BearingGeometry
from .bearing_file import bearing_from_dict, load_bearing, read_toml
from .grid import DEFAULT_GRID, Grid
from .model import (DEFLECTION_LAWS, FILM_MODELS, FOIL_MODELS, SUBAMBIENT_TREATMENTS,
                    BearingModel)

__all__ = ["BearingGeometry", "BearingModel", "DEFAULT_GRID", "DEFLECTION_LAWS", "FILM_MODELS",
           "FOIL_MODELS", "Grid", "SUBAMBIENT_TREATMENTS", "bearing_from_dict", "load_bearing",
           "read_toml"]
