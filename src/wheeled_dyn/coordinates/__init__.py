r"""Coordinate sets: document coordinates and velocities in terms of the model's."""

from .builtin import (builtin_coordinate_set, builtin_specs, coordinate_set_names,
                      default_coordinate_set)
from .spec import CoordinateSet, CoordinateSpecError, model_symbols, parse_coordinate_set, parse_expression

__all__ = ["CoordinateSet", "CoordinateSpecError", "builtin_coordinate_set", "builtin_specs",
           "coordinate_set_names", "default_coordinate_set", "model_symbols",
           "parse_coordinate_set", "parse_expression"]
