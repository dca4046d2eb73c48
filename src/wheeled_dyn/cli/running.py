r"""How the commands run comparisons: one after the other with a progress bar
(:func:`run_comparison`), or the default report's on forked workers that take its groups of
derivations, costliest first, each the next as it is free (:func:`compare_report`); each result reused from the results cache when nothing it depends on
changed."""

from __future__ import annotations

from collections.abc import Callable, Sequence
from pathlib import Path
from typing import TYPE_CHECKING

from ..errors import DerivationError
from .inputs import check_model_names
from .report_output import reused_tables

if TYPE_CHECKING:       # the heavy modules load in the functions (a quick --help and list)
    from ..compare.engine import ComparisonEngine
    from ..compare.records import DerivationResult
    from ..derivations.schema import Derivation


class _Silent:
    r"""The progress bar where stderr is not a terminal: it shows nothing (and ``tqdm``, with
    the package metadata it reads, is not loaded for it)."""

    disable = True

    def __enter__(self) -> _Silent:
        return self

    def __exit__(self, *exc: object) -> None:
        return None

    def update(self, n: int = 1) -> None:
        return None

    def set_postfix_str(self, text: str) -> None:
        return None


def progress(total: int, what: str):
    r"""A progress bar on stderr (``tqdm``) when stderr is a terminal; silent otherwise."""
    import sys

    if not sys.stderr.isatty():
        return _Silent()
    from tqdm import tqdm
    return tqdm(total=total, desc=what, unit="file", file=sys.stderr, leave=False)


def stage_display(bar) -> Callable[[str, str], None]:
    r"""A :class:`~wheeled_dyn.compare.engine.ComparisonEngine` ``on_stage`` callback: the progress ``bar`` shows
    the derivation being compared and its current stage (``eq25_lagrange.toml: judging``)."""
    def show(name: str, stage: str) -> None:
        bar.set_postfix_str(f"{name}: {stage}")
    return show


def _known_model(d) -> None:
    r"""``d``'s model is one the registry knows; else one error naming the derivation file and
    the line of its ``model =`` (it named neither)."""
    from ..errors import InputFileError, UnknownNameError
    from ..models.registry import model_entry
    from ..derivations.source import key_line
    try:
        model_entry(d.model)
    except UnknownNameError as exc:
        raise DerivationError(d.path, "model", str(exc), key_line(d.path, None, "model")
                              ) from None
    except InputFileError as exc:           # the model file it names: the file says why
        raise DerivationError(d.path, "model", f"the model file it names cannot be read: "
                              f"{exc}", key_line(d.path, None, "model")) from None


def run_comparison(files: Sequence[Path], samples: int, param_sets: int, seed: int = 2026,
                   model: str | None = None, engine: ComparisonEngine | None = None
                   ) -> list[DerivationResult]:
    r"""Compare each derivation file; all files are parsed (and checked against ``model``)
    before any comparison starts."""
    from ..derivations.linear_document import load_linear_document
    from ..derivations import load_derivations
    from ..models.registry import model_key
    from ..compare.engine import ComparisonEngine
    from ..compare.other_documents.linear import compare_linear, is_linear_document
    from ..compare.runtime.result_cache import note_parsed
    from ..report.symbols import remember_notation
    linear = [Path(p) for p in files if is_linear_document(p)]
    note_parsed(p for p in files if Path(p) not in linear)
    derivations = load_derivations([p for p in files if Path(p) not in linear])
    for item in [*derivations, *(load_linear_document(p) for p in linear)]:
        _known_model(item)
        if model is not None and model_key(item.model) != model_key(model):
            if model.endswith(".toml") and Path(model).exists():
                from ..models.registry import load_model
                load_model(model)           # a model file that cannot be read says why first
            missing = model.endswith((".toml", ".urdf")) and not Path(model).exists()
            urdf = model.endswith(".urdf") and not missing
            raise DerivationError(item.path, "model", f"the file describes model "
                                  f"{item.model!r}, not {model!r}" + (
                                      f" ({model} does not exist: a model file's path is "
                                      f"taken from {Path.cwd()})" if missing else "") + (
                                      " (a URDF is no model file: 'wheeled-dyn model "
                                      f"{model} --out MODEL.toml' writes one)" if urdf else ""))
        if item.path not in linear:
            check_model_names(item)
    for d in derivations:
        remember_notation(d)          # the report renders them without reading them again
    engine = engine or ComparisonEngine(samples=samples, param_sets=param_sets, seed=seed)
    by_path = {}
    with progress(len(files), "comparing") as bar:
        before = engine.on_stage
        if before is None and not bar.disable:
            engine.on_stage = stage_display(bar)
        try:
            for d in derivations:
                by_path[d.path] = _compared(engine, d)
                bar.update()
        finally:
            engine.on_stage = before
        for p in linear:                        # published linearised equations
            by_path[p] = compare_linear(p)
            bar.update()
    return [by_path[d.path] for d in derivations] + [by_path[p] for p in linear]


#: Relative cost of a derivation with n coordinates (measured: n**3), and of reproducing a
#: hand-made table (in the same units; it compares two documents again under its assumptions,
#: reusing their truth: measured, seed 001's takes 0.22 s against 0.56 s for eq. 25).
TABLE_COST = 12


def _groups(derivations, heavy: frozenset[str] = frozenset()) -> list[list[int]]:
    r"""Indices of the derivations in groups that share a model and coordinate set (they share
    the truth), the costliest first: the workers take them in this order, each the next as
    it finishes one (the longest first: the last to finish is a short one). A group holding
    a file named in ``heavy`` carries the cost of the table that compares it."""
    groups: dict[tuple, list[int]] = {}
    for i, d in enumerate(derivations):
        groups.setdefault((d.model, d.coordinates.use, repr(d.coordinates.raw)), []).append(i)

    def cost(members):
        extra = TABLE_COST if any(derivations[i].path.name in heavy for i in members) else 0
        return sum(derivations[i].n ** 3 for i in members) + extra

    return sorted(groups.values(), key=lambda m: -cost(m))


def _compared(engine: ComparisonEngine, d) -> DerivationResult:
    r"""``engine.compare(d)``, reused from the results cache when nothing it depends on
    changed (:mod:`~wheeled_dyn.compare.runtime.result_cache`)."""
    from ..compare.records import DerivationResult
    from ..compare.runtime.result_cache import result_key, reused
    grid = (engine.samples, engine.param_sets, engine.seed)
    return reused(lambda: result_key(d.path, d.model, grid), DerivationResult,
                  lambda: engine.compare(d), lambda r: Path(r.path) == Path(d.path),
                  parsed=d.path)


#: The derivations :func:`compare_report` parsed, by file: its forked workers inherit them.
_PARSED: dict[Path, Derivation] = {}


def _work(args, tick: Callable[[], object] | None = None,
          on_stage: Callable[[str, str], None] | None = None):
    r"""Compare the derivations ``files[i]`` for ``i`` in ``indices`` (and reproduce the
    tables of ``table_group``); ``tick()`` after each and ``on_stage(file, stage)`` at each
    stage of a comparison (default: in a worker, tell the parent). Returns the results, the
    tables' sections and the results' HTML sections (made here, in parallel, rather than one
    after the other in the parent)."""
    from ..report.html import derivation_html
    from ..disk_cache import save_memos
    from ..compare.engine import ComparisonEngine
    from ..compare.runtime.workers import stage as worker_stage
    from ..compare.runtime.workers import tick as worker_tick
    tick = tick or worker_tick
    files, indices, samples, param_sets, table_group = args
    engine = ComparisonEngine(samples=samples, param_sets=param_sets,
                              on_stage=on_stage or worker_stage)
    results = []
    for i in indices:
        results.append((i, _compared(engine, _PARSED[files[i]])))
        tick()
    sections = reused_tables(engine, table_group) if table_group else None
    html = {files[i]: derivation_html(r) for i, r in results}
    save_memos()               # the LaTeX and display forms this process made, for the next run
    return results, sections, html


def compare_report(files: Sequence[Path], samples: int, param_sets: int,
                   table_group: str | None = None, workers: int | None = None
                   ) -> tuple[list[DerivationResult], tuple[list[str], list[str], dict],
                              dict[Path, str]]:
    r"""Compare ``files`` (and reproduce the shipped comparison tables of ``table_group``) on
    up to ``workers`` processes (default: the machine's cores, at most 2 per derivation group);
    results in the order of ``files``, the tables' sections, and each result's HTML section
    by file (for :func:`~wheeled_dyn.report.render`). Processes are forked, so nothing is
    imported twice and the derivations are parsed once (the tables' files are read again where
    they are reproduced)."""
    import os

    from ..derivations import load_derivations
    from ..report.symbols import remember_notation
    from ..compare.runtime.result_cache import note_parsed
    from ..compare.runtime.workers import Workers, can_fork
    note_parsed(files)
    derivations = load_derivations(files)
    for d in derivations:
        _known_model(d)
        check_model_names(d)
        remember_notation(d)             # the workers and the parent render without re-reading
    paths = [d.path for d in derivations]
    _PARSED.update(zip(paths, derivations))
    workers = max(1, min(workers or os.cpu_count() or 1, len(derivations)))
    table_docs: set[str] = set()
    if table_group:
        from ..derivations import builtin_tables, load_comparison_table
        for t in builtin_tables(table_group):
            table_docs |= set(load_comparison_table(t).documents)
    groups = _groups(derivations, frozenset(table_docs))
    from ..compare.runtime.result_cache import package_digest, results_reused
    if results_reused():
        package_digest()                 # once, in the parent: the forked workers inherit it
    owner = next((k for k, g in enumerate(groups) if any(paths[i].name in table_docs
                                                        for i in g)), 0)
    jobs = [(paths, g, samples, param_sets, table_group if k == owner else None)
            for k, g in enumerate(groups)]
    workers = min(workers, len(jobs))
    try:
        with progress(len(paths), "comparing") as bar:
            show = stage_display(bar)
            if workers == 1 or not can_fork():
                outputs = [_work(job, bar.update, show) for job in jobs]
            else:
                with Workers(workers) as pool:
                    for job in jobs:
                        pool.submit(_work, (job,), [paths[i].name for i in job[1]])
                    outputs = pool.wait(bar.update, None if bar.disable else show)
    finally:
        _PARSED.clear()
    results: dict[int, DerivationResult] = {}
    sections: tuple[list[str], list[str], dict] = ([], [], {})
    html: dict[Path, str] = {}
    for found, sec, parts in outputs:
        for i, r in found:
            results[i] = r
        if sec is not None:
            sections = sec
        html.update(parts)
    return [results[i] for i in range(len(paths))], sections, html
