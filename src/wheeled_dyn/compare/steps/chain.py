r"""Where an error enters: the steps of a derivation, their consistency, and the causes they
explain downstream.

:func:`with_steps` (called by :meth:`ComparisonEngine.compare`) adds to a derivation's result

1. the records of its own ``[[step]]`` tables and of the ``*_steps.toml`` files in its folder
   that name it under ``feeds`` (:mod:`.step_records`);
2. internal consistency, without the truth: the derivation's :math:`A` against the Hessian
   :math:`\partial^2T/\partial\nu\,\partial\nu` of the document's own kinetic energy, its
   :math:`Q` against :math:`\partial U/\partial q` of its own potential energy (records with
   ``key = "consistency"``);
3. an ``upstream_step`` :class:`~.result.Cause` for each differing term of the equations of
   motion (:math:`h_i`'s product :math:`\nu_j\nu_k`, :math:`A_{ij}`'s acceleration
   :math:`\dot\nu_j`) whose term differs in an earlier step too: the first such step of the
   chain (kinematics before energies before generalized forces, then the document's order).

A file of steps only (no ``[matrices]``) gives a result of its steps alone.
"""

from __future__ import annotations

from collections import Counter
from collections.abc import Callable, Sequence
from dataclasses import replace
from pathlib import Path

import numpy as np
import sympy as sp

from ...derivations.builtin import STEPS_SUFFIX
from ...paths import file_stamp
from ...derivations.schema import Derivation
from ...derivations.steps import STEP_KINDS
from ..grid.assumptions import declared
from ..causes.root import claim_causes
from ...compiled import numpy_function
from ..judge.diagnose import agrees, max_error, value_diagnoses
from ..sides.document import document_symbol_values
from ..records import (Cause, CauseKind, Diagnosis, DiagnosisKind as K, DerivationResult,
                       ElementRecord, Verdict, diagnosis)
from ..readings.row_combinations import as_compared
from ..grid.samples import parameter_sets
from ..runtime.workers import Workers, can_fork

def energy_consistency(steps_d: Derivation, eom: Derivation, seed: int = 2026
                       ) -> list[ElementRecord]:
    r"""The fed derivation's A against the Hessian of the document's own total kinetic energy,
    and its Q against the gradient of its own total potential energy (names matched)."""
    out: list[ElementRecord] = []
    names = [str(v) for v in eom.velocities]
    if [str(v) for v in steps_d.velocities] != names or \
            [str(p) for p in steps_d.positions] != [str(p) for p in eom.positions]:
        return out
    terms = eom.read_off(assume=True, unscale=True)
    point = dict(declared(eom).linearised_about)
    rng = np.random.default_rng([seed, 13])
    sets = parameter_sets(eom.model, 2, rng)
    for s in steps_d.steps:
        if s.bodies or s.given or s.kind not in ("kinetic energy", "potential energy"):
            continue
        expr = s.components[0].xreplace(dict(zip(steps_d.positions, eom.positions)))
        expr = expr.xreplace(dict(zip(steps_d.velocities, eom.velocities)))
        if s.kind == "kinetic energy" and terms.A is not None:
            own = sp.hessian(expr, eom.velocities)
            pairs = [(f"A[{i + 1},{j + 1}]", terms.A[i, j], own[i, j], f"∂²T/∂{names[i]}∂{names[j]}")
                     for i in range(eom.n) for j in range(eom.n)]
        elif s.kind == "potential energy" and terms.Q is not None:
            pairs = [(f"Q[{i + 1}]", terms.Q[i], expr.diff(p), f"∂U/∂{p}")
                     for i, p in enumerate(eom.positions)]
        else:
            continue
        states = rng.uniform(-np.pi, np.pi, (20, eom.n))
        for k, p in enumerate(eom.positions):          # a linearised A: at its point
            if str(p) in point:
                states[:, k] = point[str(p)]
        per_set = [(_values(eom, sets, k), _values(steps_d, sets, k)) for k in range(len(sets))]
        for label, a, b, what in pairs:
            if a.has(sp.nan):
                continue
            parts_a, parts_b = [], []
            for va, vb in per_set:
                fa = numpy_function(eom.positions, a.xreplace(va))
                fb = numpy_function(eom.positions, b.xreplace(vb))
                parts_a.append(np.broadcast_to(fa(*states.T), (len(states),)))
                parts_b.append(np.broadcast_to(fb(*states.T), (len(states),)))
            Da, Db = np.concatenate(parts_a).astype(float), np.concatenate(parts_b).astype(float)
            scale = max(float(np.abs(Da).max()), float(np.abs(Db).max()), 1e-300)
            ok = agrees(Da, Db, scale)
            diags = () if ok else (diagnosis(
                K.NOTE, f"{label} of {eom.path.stem} is not {what} of the document's own "
                f"energy {s.name}", prefix=""), *(replace(
                    x, text=x.text.replace("the truth", "the energy's"),
                    detail=x.detail.replace("the truth", "the energy's"))
                    for x in value_diagnoses(Da, Db, scale)))
            out.append(ElementRecord(
                element=f"{label} vs {what} of {s.name}", key="consistency", index=(),
                verdict=Verdict.AGREES if ok else Verdict.DIFFERS, diagnoses=diags,
                document=sp.sstr(a),
                document_model=sp.sstr(b), truth=None, residual=None,
                max_error=max_error(Da, Db), scale=scale, step=s.kind, equation=s.equation))
    return out


def _values(d: Derivation, sets, k: int) -> dict:
    rng = np.random.default_rng(k)
    return {s: sp.Float(v) for s, v in document_symbol_values(d, sets[k], rng).items()}


def _mono(r: ElementRecord, eom: Derivation) -> Counter | None:
    if r.key == "h":
        return Counter(r.element.split(":", 1)[1].split("*"))
    if r.key == "A":
        return Counter([str(eom.accelerations[r.index[1]])])
    return None


def _difference(diagnoses: Sequence[Diagnosis]) -> str:
    r"""``extra`` (the truth is 0), ``missing`` (the document has 0) or ``other``."""
    for x in diagnoses:
        if x.kind in (K.EXTRA, K.MISSING):
            return x.kind.value
    return "other"


def _explains(step: str, eom: str) -> bool:
    r"""A step's term difference can explain the equations' one: the same kind, or a term
    missing upstream where the equations' term is otherwise wrong."""
    return step == eom or (eom == "other" and step == "missing")


def upstream_causes(steps: Sequence[ElementRecord], eom_records: Sequence[ElementRecord],
                    eom: Derivation) -> list[Cause]:
    r"""For each differing term of the equations of motion, the first step (of the chain,
    :data:`STEP_KINDS` order, then the document's) whose same term differs."""
    level = {k: i for i, k in enumerate(STEP_KINDS)}
    chain = sorted((r for r in steps if r.verdict == "differs" and r.key == "step"),
                   key=lambda r: level.get(r.step, len(level)))
    found: dict[tuple[str, Diagnosis], list[str]] = {}
    for r in eom_records:
        mono = _mono(r, eom) if r.verdict == "differs" else None
        if not mono:
            continue
        kind = _difference(r.diagnoses)
        for s in chain:
            hit = next((x for x in s.diagnoses if x.product
                        and Counter(x.product.split("*")) == mono
                        and _explains(_difference([x]), kind)), None)
            if hit:
                found.setdefault((s.element, hit), []).append(r.element)
                break
    out = []
    for (element, finding), labels in found.items():
        s = next(x for x in chain if x.element == element)
        term = finding.product
        rows = sorted({lab.split("[")[1].split("]")[0].split(",")[0] for lab in labels})
        out.append(Cause(kind=CauseKind.UPSTREAM_STEP, elements=tuple(labels),
                         explanation=f"{element} differs (its {finding.text[5:]}); the {term} "
                         "term of "
                         f"equation{'s' if len(rows) > 1 else ''} {', '.join(rows)} "
                         f"({', '.join(labels)}) follows from it",
                         step=s.step, equation=s.equation))
    return out


_STEP_CACHE: dict[tuple, list[ElementRecord]] = {}


_LOADED: dict[tuple[str, tuple | None], Derivation] = {}


def _load(path: Path) -> Derivation:
    r"""A step file, parsed once per content."""
    from ...derivations.parse import load_derivation
    key = (str(path), file_stamp(path))
    if key not in _LOADED:
        _LOADED[key] = load_derivation(path)
    return _LOADED[key]


def _step_key(path: Path, seed: int) -> tuple:
    from ...models.registry import model_version
    return str(path), file_stamp(path), seed, model_version(_load(path).model)


def _step_records(d: Derivation, seed: int) -> list[ElementRecord]:
    r"""The records of the steps of ``d`` (:mod:`.step_records`, imported on first use: a
    derivation without steps of its own, whose step files a worker compares, needs none of
    it in the parent)."""
    from .records import compare_steps
    return compare_steps(d, seed)


def _step_file(path: Path, seed: int) -> tuple[Derivation, list[ElementRecord]]:
    r"""A step file and its records, compared once per content (of it and of its model)."""
    key = _step_key(path, seed)
    if key not in _STEP_CACHE:
        _STEP_CACHE[key] = _step_records(_load(path), seed)
    return _load(path), _STEP_CACHE[key]


def _neighbours(path: Path) -> list[Path]:
    r"""The ``*_steps.toml`` files in the folder of ``path``, other than it (sorted)."""
    folder = path.parent
    if not path.is_file() or not folder.is_dir():      # a derivation built in Python
        return []
    return [p for p in sorted(folder.glob("*" + STEPS_SUFFIX)) if p != path]


def steps_state(path: Path) -> tuple[tuple[str, tuple | None], ...]:
    r"""The step files beside the derivation file ``path`` with their times of change (what a
    comparison of it reads besides it: a result remembered is stale when one changes;
    :func:`~wheeled_dyn.paths.file_stamp`)."""
    return tuple((p.name, file_stamp(p)) for p in _neighbours(path))


def feeding_files(d: Derivation) -> list[Path]:
    r"""The ``*_steps.toml`` files beside ``d`` whose ``feeds`` name it (sorted)."""
    return _feeding(d.path)


def _feeding(path: Path) -> list[Path]:
    return [p for p in _neighbours(path) if path.stem in _feeds(p)]


def _feeds(path: Path) -> tuple[str, ...]:
    r"""The derivations a step file names in ``feeds``, read from its TOML alone (the
    whole file is read as a derivation only where it feeds the one compared: three of seed
    001's four step files feed other derivations). Malformed TOML is the loader's error; a
    ``feeds`` that is not a list of names is read by the loader, so its error is the loader's
    too."""
    from ...derivations.source import read_toml
    feeds = read_toml(path)[0].get("feeds", [])
    if not isinstance(feeds, list) or not all(isinstance(x, str) for x in feeds):
        return _load(path).feeds
    return tuple(feeds)


def _fed_records(path: Path, seed: int) -> list[tuple[Path, list[ElementRecord]]]:
    r"""The step files feeding the derivation file ``path`` and their records (in a worker:
    see :func:`_beside`)."""
    return [(p, _step_file(p, seed)[1]) for p in _feeding(path)]


def _beside(d: Derivation, seed: int, compare: Callable[[Derivation], DerivationResult]
            ) -> tuple[DerivationResult, list[Path]]:
    r"""``compare(d)`` and the step files feeding ``d``, found and compared meanwhile by a
    forked worker (:mod:`.workers`; one after the other where it cannot fork)."""
    neighbours = _neighbours(d.path)
    if not neighbours or not can_fork():
        return compare(d), feeding_files(d)
    with Workers(1) as worker:          # it inherits what is cached here: unchanged files
        worker.submit(_fed_records, (d.path, seed), [p.name for p in neighbours])
        base = compare(d)
        (fed,) = worker.wait()
    for p, records in fed:
        _STEP_CACHE[_step_key(p, seed)] = records
    return base, [p for p, _ in fed]


def has_equations(d: Derivation) -> bool:
    return d.equations is not None or any(getattr(d, k) is not None for k in "ACQBG")


def with_steps(d: Derivation, compare: Callable[[Derivation], DerivationResult],
               seed: int = 2026, parallel: bool = False,
               on_stage: Callable[[str], None] | None = None) -> DerivationResult:
    r"""``compare(d)`` (the equations of motion, when the file has them) with the records of
    its steps and of the step files that feed it, the consistency of its A and Q with the
    document's own energies, and the ``upstream_step`` causes. ``parallel``: the step files
    are compared in a forked worker meanwhile. ``on_stage("steps")`` where steps are compared."""
    if d.steps and on_stage is not None:
        on_stage("steps")
    own = _step_records(d, seed) if d.steps else []
    if not has_equations(d):
        from .records import STEP_SETS, STEP_STATES
        return DerivationResult(
            path=d.path, title=d.title, model=d.model, source=dict(d.source),
            coordinates=d.coordinates.use or "inline",
            velocities=tuple(str(v) for v in d.velocities), form="steps", records=tuple(own),
            row_factors=(), energy=None, asymmetric=(), constraints=(),
            reconstructed=dict(d.reconstructed), samples=STEP_STATES, parameter_sets=STEP_SETS,
            assumes=declared(d).describe())
    base, paths = _beside(d, seed, compare) if parallel else (compare(d), feeding_files(d))
    if paths and on_stage is not None:
        on_stage("steps")
    fed = [_step_file(p, seed) for p in paths]
    if not own and not fed:
        return base
    steps = own + [r for _, recs in fed for r in recs]
    eom = as_compared(d, base)              # rows divided or combined as found
    consistency = energy_consistency(d, eom, seed) + [r for sd, _ in fed
                                                     for r in energy_consistency(sd, eom, seed)]
    causes = claim_causes(steps) + upstream_causes(steps, base.records, d)
    return replace(base, records=tuple(base.records) + tuple(steps) + tuple(consistency),
                   causes=tuple(base.causes) + tuple(causes))


__all__ = ["energy_consistency", "feeding_files", "upstream_causes", "with_steps"]
