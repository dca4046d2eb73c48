r"""Which of the model's special parameter families a document can assume: none that makes a
symbol it writes vanish.

A family (:class:`~..grid.samples.SpecialCase`: products of inertia zero, the centre of mass
on the axle, no armature ...) sets parameters to zero. A document that writes a term in
:math:`MX_1` does not take :math:`MX_1 = 0`: under the family the term vanishes whatever its
sign or factor, so the family explains nothing about it.

- **Undeclared families** that make a written symbol vanish are not tried as explanations
  (:func:`consistent_cases`): a sign error in a term in :math:`MX_1` was "agrees only if the
  centre of mass is on the axle", where the document keeps :math:`MX_1` everywhere.
- **Declared families** that do are the file contradicting itself
  (:func:`contradicted_families`): its terms in those symbols are never compared (they vanish
  in every parameter set drawn), which a cause says first; the verdicts under the
  declaration stand.
- **Declared families** that make two written symbols proportional (:func:`related_families`:
  :math:`I_x = I_y` under ``I1_eq_I2``, :math:`J = 2K` under ``disc_wheels``) leave a term in
  their difference uncompared, whatever its sign or factor: said first the same way.
- **Declared units** that contradict the link or joint parameters a symbol's value names (a
  moment of inertia in kg·m) are the file contradicting itself too (:func:`contradiction_causes`,
  :func:`~.units.contradicted_units`).

A symbol vanishes under a family where its value is at most :data:`ZERO` of its largest on
parameter sets drawn without the family, in every set drawn with it — and, for a model of a
URDF, at most that of its value in the URDF itself: the sets drawn without a family have
inertias of no particular size (a proof mass of 1 µg, its moment 3e-18 kg m², is drawn there
as a body of grams), so a family that keeps the URDF's own small moment does not make it
vanish.
"""

from __future__ import annotations

from collections.abc import Sequence

import numpy as np
import sympy as sp

from ...derivations.schema import Derivation
from ...expression_size import free_symbols_of
from ..grid.assumptions import Assumptions
from ..grid.samples import (ROUND_WHEELS, URDF_PROPORTIONS, URDF_STRUCTURE, SpecialCase,
                            parameter_sets)
from ..records import Cause, CauseKind
from ..sides.document import DocumentFunctions, document_symbol_values
from .units import contradicted_units, format_dim

#: A symbol's value at most this fraction of its largest without the family is zero.
ZERO = 1e-12
#: Parameter sets drawn with and without a family to see what it makes vanish.
SETS = 2


def written_symbols(funcs: DocumentFunctions) -> set[sp.Symbol]:
    r"""The document's symbols (not inputs) its matrices or equations write."""
    found: set[sp.Basic] = set()
    for expr in funcs.exprs.values():
        if expr is not None:
            found |= free_symbols_of(expr)
    return found & set(funcs.params)


#: Parameter sets drawn per (model, its version, families, seed): shared by the documents
#: of one model (each family's sets drawn once per process).
_DRAWN: dict[tuple, list] = {}


def _values(d: Derivation, special: Sequence[SpecialCase], seed: int
            ) -> list[dict[sp.Symbol, float]]:
    from ...models.registry import model_version
    key = (d.model, model_version(d.model), tuple(c.name for c in special), seed)
    if key not in _DRAWN:
        rng = np.random.default_rng([seed, 11, len(special)])
        _DRAWN[key] = parameter_sets(d.model, SETS, rng, tuple(special))
    rng = np.random.default_rng(seed)
    return [document_symbol_values(d, ps, rng) for ps in _DRAWN[key]]


def _gone(d: Derivation, written: set[sp.Symbol], free: list[dict], held: list[dict],
          seed: int) -> list[sp.Symbol]:
    r"""The ``written`` symbols nonzero in some set of ``free`` and zero in every one of
    ``held``, beside their largest in ``free`` and, for a model of a URDF, beside their value
    in the URDF (module text), in the file's order."""
    if not free or not held:
        return []
    out = []
    own: list[dict | None] = []
    for s in (spec.symbol for spec in d.symbols.values() if spec.symbol in written):
        size = max(abs(v[s]) for v in free)
        if not (size > 0 and all(abs(v[s]) <= ZERO * size for v in held)):
            continue
        if not own:
            own.append(_own(d, seed))
        if own[0] is None or all(abs(v[s]) <= ZERO * abs(own[0][s]) for v in held):
            out.append(s)
    return out


def _own(d: Derivation, seed: int) -> dict[sp.Symbol, float] | None:
    r"""The document's symbols at the model's own parameters (its URDF's numbers); None for
    a model of a physical record (its parameters are drawn in their own ranges)."""
    from ...models.registry import load_model, model_entry
    from ..grid.samples import ParameterSet, namespace_values
    if model_entry(d.model).parameters is not None:
        return None
    wm = load_model(d.model)
    return document_symbol_values(d, ParameterSet(wm, namespace_values(wm, None)),
                                  np.random.default_rng(seed))


def vanishing(d: Derivation, written: set[sp.Symbol], without: Sequence[SpecialCase],
              case: SpecialCase, seed: int) -> list[sp.Symbol]:
    r"""The ``written`` symbols that ``case`` makes vanish, beside the families ``without``
    (module text), in the file's order."""
    if not written:
        return []
    return _gone(d, written, _values(d, without, seed), _values(d, (*without, case), seed),
                 seed)


def consistent_cases(d: Derivation, funcs: DocumentFunctions, cases: Sequence[SpecialCase],
                     assumed: Assumptions, seed: int) -> tuple[SpecialCase, ...]:
    r"""The undeclared ``cases`` that make no symbol the document writes vanish."""
    written = written_symbols(funcs)
    if not written or not cases:
        return tuple(cases)
    free = _values(d, assumed.families, seed)
    return tuple(c for c in cases if not _gone(
        d, written, free, _values(d, (*assumed.families, c), seed), seed))


#: The families whose relations between symbols are the robot's own or said elsewhere.
OWN_RELATIONS = frozenset(c.name for c in (URDF_STRUCTURE, URDF_PROPORTIONS, ROUND_WHEELS))
#: Relative spread within which a ratio of two symbols is one number in every set.
RATIO_TOL = 1e-9
#: Largest denominator of a ratio a family holds between two written symbols (J = 2K).
RATIO_DENOMINATOR = 12


def _ratio(a: sp.Symbol, b: sp.Symbol, sets: list[dict]) -> float | None:
    r""":math:`a/b`, the same in every one of ``sets`` (within :data:`RATIO_TOL`), or None."""
    ratios = [v[a] / v[b] for v in sets if v[b] != 0 and v[a] != 0]
    if len(ratios) < len(sets) or not ratios or not np.all(np.isfinite(ratios)):
        return None
    r = float(ratios[0])
    return r if all(abs(x - r) <= RATIO_TOL * abs(r) for x in ratios) else None


def related(d: Derivation, written: set[sp.Symbol], without: Sequence[SpecialCase],
            case: SpecialCase, seed: int) -> list[tuple[sp.Symbol, sp.Symbol, sp.Expr]]:
    r"""The pairs of ``written`` symbols that ``case`` makes proportional by a simple fraction
    (:math:`I_x = I_y` under ``I1_eq_I2``, :math:`J = 2K` under ``disc_wheels``) and that are
    not so beside the families ``without``: ``(a, b, c)`` with :math:`a = c\,b`. A term in
    :math:`a - c\,b` vanishes in every set drawn, whatever its sign or factor."""
    if len(written) < 2:
        return []
    free, held = _values(d, without, seed), _values(d, (*without, case), seed)
    symbols = [spec.symbol for spec in d.symbols.values() if spec.symbol in written]
    out = []
    for i, a in enumerate(symbols):
        for b in symbols[i + 1:]:
            r = _ratio(a, b, held)
            if r is None or _ratio(a, b, free) is not None:
                continue
            c = sp.nsimplify(r, rational=True, tolerance=RATIO_TOL * abs(r))
            if c.q <= RATIO_DENOMINATOR and abs(float(c) - r) <= RATIO_TOL * abs(r):
                out.append((a, b, c))
    return out


def contradicted_families(d: Derivation, funcs: DocumentFunctions, assumed: Assumptions,
                          seed: int) -> list[tuple[str, list[sp.Symbol]]]:
    r"""The declared families that make a symbol the document writes vanish, with those
    symbols."""
    written = written_symbols(funcs)
    out = []
    for case in assumed.families:
        others = [c for c in assumed.families if c is not case]
        gone = vanishing(d, written, others, case, seed)
        if gone:
            out.append((case.name, gone))
    return out


def related_families(d: Derivation, funcs: DocumentFunctions, assumed: Assumptions,
                     seed: int) -> list[tuple[str, list[tuple[sp.Symbol, sp.Symbol, sp.Expr]]]]:
    r"""The declared families that make two symbols the document writes proportional
    (:func:`related`), with those pairs; none for the families that keep the URDF's own
    structure or proportions (their relations are the robot's), nor for ``round_wheels``
    (a wheel's symbols of its asymmetry are said by
    :func:`~..grid.round_wheels.round_contradiction`)."""
    written = written_symbols(funcs)
    out = []
    for case in assumed.families:
        if case.name in OWN_RELATIONS:
            continue
        others = [c for c in assumed.families if c is not case]
        pairs = related(d, written, others, case, seed)
        if pairs:
            out.append((case.name, pairs))
    return out


def contradiction_causes(d: Derivation, funcs: DocumentFunctions, assumed: Assumptions,
                         seed: int) -> tuple[Cause, ...]:
    r"""A ``file_error`` cause per declared family that makes a written symbol vanish, and
    per symbol whose declared units contradict its value."""
    out = []
    for name, gone in contradicted_families(d, funcs, assumed, seed):
        them = ", ".join(map(str, gone))
        out.append(Cause(CauseKind.FILE_ERROR, (), (
            f"the file declares {name}, under which {them} "
            f"{'is' if len(gone) == 1 else 'are'} 0, but the document writes "
            f"{'it' if len(gone) == 1 else 'them'}: its terms in {them} vanish in every "
            "parameter set and are not compared (declare the family only where the "
            "document's equations assume it)")))
    for name, pairs in related_families(d, funcs, assumed, seed):
        said = ", ".join(f"{a} = {sp.sstr(c * b)}" for a, b, c in pairs)
        terms = ", ".join(sp.sstr(a - c * b) for a, b, c in pairs)
        out.append(Cause(CauseKind.FILE_ERROR, (), (
            f"the file declares {name}, under which {said}, but the document writes "
            f"{'both' if len(pairs) == 1 else 'each'}: a term in {terms} vanishes in every "
            "parameter set and is not compared, whatever its sign or factor (declare the "
            "family only where the document's equations assume it)")))
    for name, value, declared, given in contradicted_units(d):
        out.append(Cause(CauseKind.FILE_ERROR, (), (
            f"the file declares {name} in {format_dim(declared)}, but its value {value} is "
            f"{format_dim(given)}: the declared units are wrong (the comparison uses the "
            "value; the units only check the document's terms)")))
    return tuple(out)


__all__ = ["RATIO_DENOMINATOR", "RATIO_TOL", "ZERO", "consistent_cases",
           "contradicted_families", "contradiction_causes", "related", "related_families",
           "vanishing", "written_symbols"]
