"""Inputs: the bearing in SI, the non-dimensional model and formulation, the grid, and every
SI ↔ non-dimensional conversion (:mod:`.conversions`, the only place they meet)."""
from .bearing import BearingGeometry
from .bearing_file import bearing_from_dict, load_bearing, load_bearing_file, read_toml
from .grid import DEFAULT_GRID, Grid
from .model import (DEFLECTION_LAWS, FILM_MODELS, FOIL_MODELS, SUBAMBIENT_TREATMENTS,
                    BearingModel)
from .options import MAX_FILM, ModelOptions, merge_options, resolve_model_options
from .rotor import OperatingPoint, Rotor

__all__ = ["BearingGeometry", "BearingModel", "DEFAULT_GRID", "DEFLECTION_LAWS", "FILM_MODELS",
           "FOIL_MODELS", "Grid", "MAX_FILM", "ModelOptions", "OperatingPoint", "Rotor",
           "SUBAMBIENT_TREATMENTS", "bearing_from_dict", "load_bearing", "load_bearing_file",
           "merge_options", "read_toml", "resolve_model_options"]
