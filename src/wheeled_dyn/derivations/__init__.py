r"""Derivation files: a document's equations of motion as plain TOML data.

A derivation file records what a document says (its coordinates, symbols, matrices or
equations, transcribed as printed, typos included, with every place restored from garbled text
marked) and how it relates to a model of the toolkit. The comparison engine checks it against
Pinocchio. Format: ``docs/derivation-format.md``.

>>> from wheeled_dyn.derivations import builtin_derivations, load_derivation
>>> d = load_derivation(builtin_derivations("seed001")[0])   # doctest: +SKIP
>>> d.A, d.C, d.Q                                              # doctest: +SKIP
"""

from .._lazy import attach

__getattr__, __dir__, __all__ = attach(__name__, {
    "declared_sets": ".coordinates",
    "BuiltinSet": ".coordinates",
    "DerivationNameError": ".errors",
    "KHALIL_FUNCTIONS": ".expressions",
    "KHALIL_NAMES": ".expressions",
    "LINK_FUNCTIONS": ".expressions",
    "PHYSICAL_NAMES": ".expressions",
    "physical_in_standard": ".expressions",
    "STANDARD_FUNCTIONS": ".expressions",
    "parse_expression": ".expressions",
    "parse_model_expression": ".expressions",
    "parse_units": ".expressions",
    "real_symbol": ".expressions",
    "builtin_derivations": ".builtin",
    "builtin_groups": ".builtin",
    "builtin_tables": ".builtin",
    "derivation_files": ".builtin",
    "MISSING_ELEMENT": ".matrices",
    "load_derivation": ".parse",
    "load_derivations": ".parse",
    "EquationTerms": ".readoff",
    "split_equation_terms": ".readoff",
    "CoordinateSpec": ".schema",
    "Derivation": ".schema",
    "SymbolSpec": ".schema",
    "ComparisonTable": ".table",
    "TableEntry": ".table",
    "load_comparison_table": ".table",
})
