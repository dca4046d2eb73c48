r"""Derivation files: a document's equations of motion as plain TOML data.

A derivation file records what a document says (its coordinates, symbols, matrices or
equations, transcribed as printed, typos included, with every place restored from garbled text
marked) and how it relates to a model of the toolkit. The comparison engine checks it against
Pinocchio. Format: ``docs/derivation-format.md``.

>>> from wheeled_dyn.derivations import builtin_derivations, load_derivation
>>> d = load_derivation(builtin_derivations("seed001")[0])   # doctest: +SKIP
>>> d.A, d.C, d.Q                                              # doctest: +SKIP
"""

from .coordinates import BUILTIN_COORDINATE_SETS, BuiltinSet
from .errors import DerivationNameError
from .expressions import (KHALIL_FUNCTIONS, KHALIL_NAMES, STANDARD_FUNCTIONS,
                          parse_expression, parse_model_expression, parse_units, real_symbol)
from .builtin import builtin_derivations, builtin_groups, builtin_tables, derivation_files
from .matrices import MISSING_ELEMENT
from .parse import load_derivation, load_derivations
from .readoff import EquationTerms, split_equation_terms
from .schema import CoordinateSpec, Derivation, SymbolSpec
from .table import ComparisonTable, TableEntry, load_comparison_table

__all__ = [
    "BUILTIN_COORDINATE_SETS", "BuiltinSet", "ComparisonTable", "CoordinateSpec", "Derivation",
    "DerivationNameError", "EquationTerms", "KHALIL_FUNCTIONS", "KHALIL_NAMES",
    "MISSING_ELEMENT", "STANDARD_FUNCTIONS", "SymbolSpec", "TableEntry", "builtin_derivations",
    "builtin_groups", "builtin_tables", "derivation_files", "load_comparison_table",
    "load_derivation", "load_derivations", "parse_expression", "parse_model_expression", "parse_units",
    "real_symbol", "split_equation_terms",
]
