r"""The comparison engine: a document's derivation against the truth.

For a :class:`~wheeled_dyn.derivations.schema.Derivation`, one call per stage:

1. **grid** — K random physically consistent parameter sets of its model, N states each
   (:mod:`.grid`), the truth there in the document's coordinates, and the document's numbers
   (:mod:`.sides`);
2. **judge: equivalence** — whether each equation is right, whatever its form: a combination
   of the true equations with :math:`W = A_{doc}A^{-1}` invertible (:mod:`.judge.equivalence`).
   This alone decides the equations' verdicts;
3. **readings: frames** — which combination of the true equations each document equation is
   meant to be (the true one, :math:`-1` × it, divided by its inertia, solved for the
   accelerations ...), chosen so the fewest elements differ (:mod:`.readings.frames`);
4. **judge: elements** — every element of A, C, Q, B and every velocity product of h against
   the truth in its row's frame, with typed diagnoses (:mod:`.judge.element`), "agrees only if"
   from the special parameter families the document did not declare
   (:mod:`.judge.families`), C judged by the products of h it takes part in
   (:mod:`.judge.factorization`), differing terms named (:mod:`.judge.named`);
5. **causes** — the few reasons (:mod:`.causes`), a better reading of the file's sign
   conventions as a cause only (:mod:`.causes.readings`; applied only where the file declares
   its convention unknown);
6. **steps** — earlier steps of the derivation (:mod:`.steps`).

The element pipeline lives in :mod:`.judgement`; this module wires the stages.
"""

from __future__ import annotations

import hashlib
from collections.abc import Callable
from dataclasses import replace
from os import PathLike

import numpy as np

from ...derivations.schema import Derivation
from ...errors import ArgumentError
from ...paths import file_stamp
from ...models.registry import model_version
from .conventions import convention_finding, unknown_convention
from .kept_products import kept_products
from .linear_point import point_finding
from .sliding import sliding_wheels
from .symbol_maps import symbol_map_finding
from ..causes.root import root_causes
from ..grid.inputs import check_model_names, grid_size
from ..grid.grid import Grids
from .judgement import Judgement, judge_derivation
from ..records import Cause, Convention, ConventionSummary, DerivationResult
from ..sides.truth import truth_for

#: Called with a derivation's file name and the name of the stage that starts.
StageCallback = Callable[[str, str], None]
#: The stages of one comparison as ``on_stage`` names them, in the order they start ("steps"
#: comes first for the file's own ``[[step]]`` tables, last for the step files that feed it;
#: "readings" only where the equations are not right as declared).
STAGES: tuple[str, ...] = ("grid", "truth", "document", "equivalence", "frames", "judging",
                           "readings", "causes", "steps")


class ComparisonEngine:
    r"""Compares derivations; the truth is computed once per (model, coordinates, parameter
    families, grid size), so derivations sharing coordinates share it. ``parallel_steps``:
    the step files feeding a derivation are compared in a forked process meanwhile (the
    command line's ``compare``; :func:`~.steps.chain.with_steps`). ``on_stage``: told when
    each stage of a derivation starts (a progress display)."""

    def __init__(self, samples: int = 1000, param_sets: int = 5, seed: int = 2026,
                 parallel_steps: bool = False, on_stage: StageCallback | None = None) -> None:
        self.samples, self.param_sets, self.seed = grid_size(samples, param_sets, seed)
        if not isinstance(parallel_steps, bool):
            raise ArgumentError("ComparisonEngine", "parallel_steps", parallel_steps,
                                "True or False")
        if on_stage is not None and not callable(on_stage):
            raise ArgumentError("ComparisonEngine", "on_stage", on_stage,
                                "a function (file name, stage name) or None")
        self.parallel_steps = parallel_steps
        self.on_stage = on_stage
        self.grids = Grids(seed, truth_for)
        self._results: dict[tuple, DerivationResult] = {}

    def stage(self, d: Derivation, name: str) -> None:
        if self.on_stage is not None:
            self.on_stage(d.path.name, name)

    def compare(self, d: Derivation | str | PathLike) -> DerivationResult:
        r"""The comparison of one derivation (memoised per file and content); a path is loaded
        (:func:`~wheeled_dyn.derivations.load_derivation`), and its names are checked against
        its model first, as the command line does (an unknown one is an error naming the file,
        the line and the item)."""
        if isinstance(d, (str, PathLike)):
            from ...derivations import load_derivation
            derivation = load_derivation(d)
        elif isinstance(d, Derivation):
            derivation = d
        else:
            raise ArgumentError("ComparisonEngine.compare", "d", d, "a Derivation "
                                "(wheeled_dyn.derivations.load_derivation) or the path of a "
                                "derivation file")
        check_model_names(derivation)
        from ..steps.chain import steps_state, with_steps    # earlier steps, upstream causes
        # per content: of the derivation (one built in Python has no file, and two of the same
        # title had shared a result), of the step files beside it and of the model's files
        key = (hashlib.sha256(repr(derivation).encode()).hexdigest(),
               file_stamp(derivation.path),
               steps_state(derivation.path), model_version(derivation.model))
        if key not in self._results:
            try:
                self._results[key] = with_steps(derivation, self._compare, self.seed,
                                                self.parallel_steps,
                                                lambda stage: self.stage(derivation, stage))
            except RecursionError:       # SymPy's and Python's compilers recurse per level
                from ...errors import DerivationError
                raise DerivationError(derivation.path, "matrices", "an expression nested too "
                                      "deeply to compile (its definitions substituted): "
                                      "write it flatter") from None
        return self._results[key]

    def judge(self, d: Derivation, announce: bool = False) -> Judgement:
        r"""The equations and elements of ``d`` judged as the file declares them (values that
        overflow or leave the reals are inf or NaN there, silently: they never decide);
        ``announce``: its stages are told to ``on_stage`` (not those of re-readings)."""
        with np.errstate(all="ignore"):
            return judge_derivation(self, d, announce)

    def _compare(self, d: Derivation) -> DerivationResult:
        first: list[Cause] = []
        applied = unknown_convention(self, d)
        if applied is not None:                   # the file says its convention is unknown
            d, cause = applied
            first.append(cause)
        j = self.judge(d, announce=True)
        result = j.result
        sliding = sliding_wheels(j.sides.grid.cs, j.sides.grid.sets[0].model)
        first += [sliding] if sliding is not None else []      # the map, before any reading
        self.stage(d, "readings")
        kept = kept_products(self, d, j)
        if kept is not None:                      # velocity products a linearisation hides
            result = kept[0]
            first.append(kept[1])
        point = point_finding(self, d, j) if not j.result.equivalent else None
        first += [point] if point is not None else []
        if applied is None and point is None and not j.result.equivalent and result.equations:
            finding = convention_finding(self, d, j)
            if finding is not None:
                first.append(finding[0])
                result = replace(result, conventions=finding[1])
            else:
                mapped = symbol_map_finding(d, j)      # a symbol mapped to another axis
                first += [mapped] if mapped is not None else []
        if result.conventions is None:
            result = replace(result, conventions=ConventionSummary(
                declared=Convention("as declared", result.counts())))
        self.stage(d, "causes")
        found = root_causes(j.evaluation, d, result.records, result.energy, result.asymmetric,
                            [*first, *j.causes])
        return replace(result, causes=found)


__all__ = ["ComparisonEngine", "STAGES", "StageCallback"]
