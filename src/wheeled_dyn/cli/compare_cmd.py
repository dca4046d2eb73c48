r"""CLI: ``wheeled-dyn report`` (the default job) and ``wheeled-dyn compare MODEL FILE...``."""

from __future__ import annotations

import argparse
import time
from collections.abc import Callable, Sequence
from pathlib import Path

from typing import TYPE_CHECKING

from ..errors import DerivationError, WheeledDynError

if TYPE_CHECKING:       # the heavy modules load in the handlers (a quick --help and list)
    from ..derivations.schema import Derivation
    from ..compare.engine import ComparisonEngine
    from ..compare.records import DerivationResult

#: Defaults of the default report: states per parameter set, parameter sets.
DEFAULT_SAMPLES, DEFAULT_PARAM_SETS = 1000, 5
#: Ranges of --samples and --param-sets, and of their product (the states of one comparison):
#: memory and time grow with it (at 10**9 states the comparison asked for 112 GiB).
MAX_SAMPLES, MAX_PARAM_SETS, MAX_STATES = 100_000, 1000, 1_000_000


def check_grid(samples: int, param_sets: int) -> None:
    r"""Raise :class:`~wheeled_dyn.errors.LimitError` unless ``1 <= samples <= MAX_SAMPLES``,
    ``1 <= param_sets <= MAX_PARAM_SETS`` and their product is at most ``MAX_STATES``."""
    from ..errors import LimitError
    if not 1 <= samples <= MAX_SAMPLES:
        raise LimitError("--samples", samples, f"an integer from 1 to {MAX_SAMPLES}")
    if not 1 <= param_sets <= MAX_PARAM_SETS:
        raise LimitError("--param-sets", param_sets, f"an integer from 1 to {MAX_PARAM_SETS}")
    if samples * param_sets > MAX_STATES:
        raise LimitError("--samples × --param-sets", samples * param_sets,
                         f"at most {MAX_STATES:,} states", "memory and time grow with them")


def input_files(entries: Sequence[str | Path]) -> list[Path]:
    r"""The derivation files named on the command line (a folder stands for its ``*.toml``
    files); a folder without any raises :class:`~wheeled_dyn.errors.InputFileError`."""
    from ..derivations.builtin import derivation_files
    from ..errors import InputFileError
    files: list[Path] = []
    for entry in entries:
        found = derivation_files([entry])
        if not found:
            raise InputFileError(entry, "folder without derivation files (*.toml)")
        files.extend(found)
    return files


def check_model_names(d) -> None:
    r"""The names derivation ``d`` uses of its model, checked before comparing: every key of
    ``[inputs]`` is a model input, every value of ``[symbols]`` uses the model's parameters
    and links. Raises :class:`~wheeled_dyn.derivations.errors.DerivationNameError` naming the
    file, the line, the item and the valid names."""
    from sympy.core.function import AppliedUndef

    from ..derivations.errors import DerivationNameError
    from ..derivations.expressions import GEOMETRY_NAMES
    from ..derivations.source import SourceText, read_small_text
    from ..models.registry import load_model, model_entry
    from ..compare.grid.samples import namespace_values
    wm = load_model(d.model)
    entry = model_entry(d.model)
    values = namespace_values(wm, entry.parameters() if entry.parameters else None)
    src = SourceText(d.path, read_small_text(d.path) if d.path.is_file() else "")  # or Python
    for key in d.inputs:
        if key not in wm.input_names:
            raise DerivationNameError(d.path, f"inputs.{key}", "model input", key,
                                      wm.input_names, src.line_of("inputs", key))
    links = sorted({k[k.index("(") + 1:-1] for k in values if "(" in k})
    for name, spec in d.symbols.items():
        if spec.value is None:
            continue
        item, line = f"symbols.{name}.value", src.line_of("symbols", name)
        args = set()
        for call in spec.value.atoms(AppliedUndef):
            link = str(call.args[0])
            args |= call.args[0].free_symbols
            key = f"{call.func.__name__}({link})"
            geometric = call.func.__name__ in GEOMETRY_NAMES
            if (link not in links or key not in values) and not geometric:
                from ..models.link_parameters import merged_links
                body = merged_links(wm).get(link)
                if body is not None:        # a link fixed to another: no parameters of its own
                    raise DerivationNameError(
                        d.path, item, f"link of its own (it is fixed to the rigid body named "
                        f"{body.carrier}: {', '.join(body.members)}; name that body)", link,
                        links, line)
            if link not in links:
                kind = GEOMETRY_NAMES.get(call.func.__name__, "link")   # origin_x(joint)
                raise DerivationNameError(d.path, item, kind, link, links, line)
            if key not in values:
                raise DerivationNameError(d.path, item, "model parameter", key,
                                          [k for k in values if k.endswith(f"({link})")], line)
        for symbol in spec.value.free_symbols - args:
            if symbol.name not in values:
                raise DerivationNameError(d.path, item, "model parameter", symbol.name,
                                          [k for k in values if "(" not in k], line)


def progress(total: int, what: str):
    r"""A progress bar on stderr (``tqdm``) when stderr is a terminal; silent otherwise."""
    import sys

    from tqdm import tqdm
    return tqdm(total=total, desc=what, unit="file", file=sys.stderr, leave=False,
                disable=not sys.stderr.isatty())


def stage_display(bar) -> Callable[[str, str], None]:
    r"""A :class:`~wheeled_dyn.compare.engine.ComparisonEngine` ``on_stage`` callback: the progress ``bar`` shows
    the derivation being compared and its current stage (``eq25_lagrange.toml: judging``)."""
    def show(name: str, stage: str) -> None:
        bar.set_postfix_str(f"{name}: {stage}")
    return show


def run_comparison(files: Sequence[Path], samples: int, param_sets: int, seed: int = 2026,
                   model: str | None = None, engine: ComparisonEngine | None = None
                   ) -> list[DerivationResult]:
    r"""Compare each derivation file; all files are parsed (and checked against ``model``)
    before any comparison starts."""
    from ..derivations.linear_document import load_linear_document
    from ..derivations import load_derivations
    from ..models.registry import model_entry, model_key
    from ..compare.engine import ComparisonEngine
    from ..compare.other_documents.linear import compare_linear, is_linear_document
    from ..compare.runtime.result_cache import note_parsed
    linear = [Path(p) for p in files if is_linear_document(p)]
    note_parsed(p for p in files if Path(p) not in linear)
    derivations = load_derivations([p for p in files if Path(p) not in linear])
    for item in [*derivations, *(load_linear_document(p) for p in linear)]:
        model_entry(item.model)
        if model is not None and model_key(item.model) != model_key(model):
            raise DerivationError(item.path, "model", f"the file describes model "
                                  f"{item.model!r}, not {model!r}")
        if item.path not in linear:
            check_model_names(item)
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
#: hand-made table (in the same units; it compares two documents again under its assumptions;
#: measured: seed 001's takes twice the time of one of its derivations, 0.97 s against 0.5 s).
TABLE_COST = 50


def _bins(derivations, workers: int, heavy: frozenset[str] = frozenset()) -> list[list[int]]:
    r"""Indices of the derivations split into ``workers`` bins of about equal cost; derivations
    sharing a model and coordinate set stay together (they share the truth). A group holding a
    file named in ``heavy`` carries the cost of the table that compares it."""
    groups: dict[tuple, list[int]] = {}
    for i, d in enumerate(derivations):
        groups.setdefault((d.model, d.coordinates.use, repr(d.coordinates.raw)), []).append(i)

    def cost(members):
        extra = TABLE_COST if any(derivations[i].path.name in heavy for i in members) else 0
        return sum(derivations[i].n ** 3 for i in members) + extra

    bins: list[list[int]] = [[] for _ in range(workers)]
    load = [0.0] * workers
    for members in sorted(groups.values(), key=lambda m: -cost(m)):
        k = load.index(min(load))
        bins[k] += members
        load[k] += cost(members)
    return [b for b in bins if b]


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
    sections = _reused_tables(engine, table_group) if table_group else None
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
    from ..models.registry import model_entry
    from ..report.symbols import remember_notation
    from ..compare.runtime.result_cache import note_parsed
    from ..compare.runtime.workers import Workers, can_fork
    note_parsed(files)
    derivations = load_derivations(files)
    for d in derivations:
        model_entry(d.model)
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
    bins = _bins(derivations, workers, frozenset(table_docs))
    from ..compare.runtime.result_cache import package_digest
    package_digest()                     # once, in the parent: the forked workers inherit it
    owner = next((k for k, b in enumerate(bins) if any(paths[i].name in table_docs for i in b)), 0)
    jobs = [(paths, b, samples, param_sets, table_group if k == owner else None)
            for k, b in enumerate(bins)]
    try:
        with progress(len(paths), "comparing") as bar:
            show = stage_display(bar)
            if len(jobs) == 1 or not can_fork():
                outputs = [_work(job, bar.update, show) for job in jobs]
            else:
                with Workers(len(jobs)) as workers:
                    for job in jobs:
                        workers.submit(_work, (job,), [paths[i].name for i in job[1]])
                    outputs = workers.wait(bar.update, None if bar.disable else show)
    finally:
        _PARSED.clear()
    results: list[DerivationResult | None] = [None] * len(paths)
    sections: tuple[list[str], list[str], dict] = ([], [], {})
    html: dict[Path, str] = {}
    for found, sec, parts in outputs:
        for i, r in found:
            results[i] = r
        if sec is not None:
            sections = sec
        html.update(parts)
    return results, sections, html


def summary_heading(r: DerivationResult) -> str:
    r"""``file — document eqs (1)-(3): title``; the parts the file does not give left out
    (``notes.toml — my notes, 26 Nov: title``, ``notes.toml: title``)."""
    document = str(r.source.get("document", "")).strip()
    equations = str(r.source.get("equations", "")).strip()
    where = " ".join(p for p in (document, f"eqs {equations}" if equations else "") if p)
    return f"{r.path.name} — {where}: {r.title}" if where else f"{r.path.name}: {r.title}"


def print_summary(results: Sequence[DerivationResult]) -> None:
    from ..report.markdown import summary_lines
    for r in results:
        print(summary_heading(r))
        for line in summary_lines(r):
            print(f"    {line}")


def _reused_tables(engine: ComparisonEngine, group: str) -> tuple[list[str], list[str], dict]:
    r""":func:`_table_sections`, reused from the results cache while no file of the group and
    nothing else it depends on changed."""
    from ..derivations import builtin_tables, load_comparison_table
    from ..derivations.builtin import builtin_derivations
    from ..compare.runtime.result_cache import result_key, reused
    tables = builtin_tables(group)
    if not tables:
        return [], [], {}
    model = load_comparison_table(tables[0]).model
    folder = tables[0].parent
    grid = ("tables", engine.samples, engine.param_sets, engine.seed)
    return reused(lambda: result_key(tables[0], model, grid, [*folder.glob("*.toml"),
                                                              *builtin_derivations(group)]),
                  tuple, lambda: tuple(_table_sections(engine, group)))


def _table_sections(engine: ComparisonEngine, group: str) -> tuple[list[str], list[str], dict]:
    r"""The shipped hand-made comparison tables of ``group``, reproduced by the machine."""
    import html as H

    from ..derivations import builtin_tables
    from ..derivations.table import load_comparison_table
    from ..compare.other_documents.tables import reproduce_table
    md, out_html, data = [], [], []
    for path in builtin_tables(group):
        rep = reproduce_table(load_comparison_table(path), engine)
        md.append(rep.markdown().replace("\n# ", "\n## ").replace("\n## Resulting", "\n### Resulting")
                  .replace("\n## Notes", "\n### Notes").replace("# Comparison", "## Comparison", 1))
        rows = "".join(
            f"<tr><td>{H.escape(r.element)}</td><td><code>{H.escape(r.derived)}</code></td>"
            f"<td><code>{H.escape(r.reference)}</code></td><td>{H.escape(r.machine)}"
            f"{' <b>≠ table</b>' if r.disagreement else ''}</td><td>{H.escape(r.table)}</td>"
            f"<td>{H.escape(r.truth)}</td><td>{H.escape(r.explanation)}</td></tr>" for r in rep.rows)
        notes = "".join(f"<li>{H.escape(n)}</li>" for n in rep.notes)
        out_html.append(
            f"<section><h2>Comparison table reproduced: {H.escape(path.name)}</h2>"
            f"<p>mismatched, table: {H.escape(', '.join(rep.table_mismatched))}; machine: "
            f"{H.escape(', '.join(rep.machine_mismatched))}</p><table><tr><th>element</th>"
            f"<th>derived</th><th>reference</th><th>machine</th><th>table</th>"
            f"<th>right (vs truth)</th><th>explanation</th></tr>{rows}</table><ul>{notes}</ul>"
            f"</section>")
        data.append({"table": path.name, "table_mismatched": list(rep.table_mismatched),
                     "machine_mismatched": list(rep.machine_mismatched),
                     "rows": [r.__dict__ for r in rep.rows], "notes": list(rep.notes)})
    return md, out_html, ({"tables": data} if data else {})


def _plots(results: Sequence[DerivationResult]) -> tuple[list[str], list[str], dict[str, bytes]]:
    r"""The optional section: each derivation simulated beside the truth (zero input)."""
    import base64

    from ..derivations import load_derivation
    from ..errors import WheeledDynError
    from .simulate_cmd import default_start
    from ..simulate.documented import side_by_side
    from ..simulate.plots import plot_side_by_side
    from ..compare.readings.row_combinations import as_compared
    md, html, files = ["## Simulations: truth and document from the same start", ""], [
        "<section><h2>Simulations: truth and document from the same start</h2>"], {}
    for r in results:
        if r.form == "linearised":              # published linear equations: nothing to run
            continue
        d = as_compared(load_derivation(r.path), r)
        try:
            factors = tuple(None if c is None else float(eval_fraction(c)) for c in r.row_factors)
            s = side_by_side(d, default_start(d), 4.0, row_factors=factors)
        except WheeledDynError as exc:
            md.append(f"- {r.path.name}: not simulated ({exc})")
            continue
        png = plot_side_by_side(s)
        name = f"{r.path.stem}_simulation.png"
        files[name] = png
        md.append(f"![{r.title}]({name})")
        html.append(f"<h3>{r.title}</h3><img alt='{name}' src='data:image/png;base64,"
                    f"{base64.b64encode(png).decode()}'>")
    html.append("</section>")
    return md, html, files


def eval_fraction(text: str) -> float:
    num, _, den = text.partition("/")
    return float(num) / float(den or 1)


def _write(results, title: str, out: Path, plots: bool = False,
           sections: tuple[list[str], list[str], dict] = ([], [], {}),
           html_sections: dict[Path, str] | None = None) -> None:
    from ..report import render, write_reports
    md, html, js = sections
    files: dict[str, bytes] = {}
    if plots:
        pmd, phtml, files = _plots(results)
        md, html = [*md, *pmd], [*html, *phtml]
    paths = write_reports({**render(results, title, md, html, js, html_sections), **files},
                          out)
    print("reports: " + ", ".join(str(p) for p in paths))


def _cmd_report(args: argparse.Namespace) -> int:
    from ..derivations import builtin_derivations
    from ..output import check_output_folder
    check_grid(args.samples, args.param_sets)
    check_output_folder(args.out)
    t0 = time.perf_counter()
    results, sections, html = compare_report(builtin_derivations(args.group), args.samples,
                                             args.param_sets, table_group=args.group)
    print_summary(results)
    for entry in sections[2].get("tables", []):
        print(f"{entry['table']}: mismatched per the seed's table: "
              f"{', '.join(entry['table_mismatched'])}; per the machine: "
              f"{', '.join(entry['machine_mismatched'])}")
    _write(results, f"wheeled_dyn: the derivations of {args.group} against the truth",
           Path(args.out), args.plots, sections, html)
    print(f"{len(results)} derivations, {args.samples} states × {args.param_sets} parameter "
          f"sets each, in {time.perf_counter() - t0:.1f} s")
    return 0


def _cmd_compare(args: argparse.Namespace) -> int:
    from ..output import check_output_folder
    check_grid(args.samples, args.param_sets)
    check_output_folder(args.out)
    files = input_files(args.files)
    from ..compare.engine import ComparisonEngine
    from ..models.registry import model_version
    engines: dict[tuple, ComparisonEngine] = {}

    def check() -> None:
        # one engine per content of the model's files: the truth is computed again when the
        # model file or the URDF was saved since
        try:
            version = model_version(args.model)
        except WheeledDynError:
            version = ()
        if version not in engines:
            engines.clear()
            engines[version] = ComparisonEngine(samples=args.samples,
                                                param_sets=args.param_sets, seed=2026,
                                                parallel_steps=True)
        results = run_comparison(files, args.samples, args.param_sets, model=args.model,
                                 engine=engines[version])
        print_summary(results)
        _write(results, f"wheeled_dyn: derivations of {args.model} against the truth",
               Path(args.out), args.plots)

    if not getattr(args, "watch", False):
        check()
        return 0
    from .watch import watch, watched_files
    try:
        check()
    except WheeledDynError as exc:          # the first version may be the broken one
        print(f"wheeled-dyn: error: {exc}", flush=True)
    return watch(lambda: watched_files(files, args.model), check)


def _without_cache(handler: Callable[[argparse.Namespace], int]
                   ) -> Callable[[argparse.Namespace], int]:
    r"""``handler`` run with the disk cache off when ``--no-cache`` is given."""
    def run(args: argparse.Namespace) -> int:
        from ..cache_trust import without_reuse
        with without_reuse(getattr(args, "no_cache", False)):
            return handler(args)
    return run


def add_commands(sub: argparse._SubParsersAction) -> None:
    for name, helptext, handler in (
            ("report", "compare the shipped derivations (seed 001's by default) with the truth; "
             "write reports/",
             _cmd_report),
            ("compare", "compare derivation files with the truth of a model", _cmd_compare)):
        p = sub.add_parser(name, help=helptext)
        if name == "compare":
            p.add_argument("model", help="model name (see 'wheeled-dyn list') or model file (.toml)")
            p.add_argument("files", nargs="+", help="derivation files (TOML) or folders")
            p.add_argument("--watch", action="store_true",
                           help="check the files again each time they are saved (the truth "
                                "is computed once); Ctrl-C to stop")
        else:
            from ..derivations.builtin import builtin_groups
            p.add_argument("--group", default="seed001", choices=builtin_groups(),
                           help="the shipped derivations to compare (default: seed001)")
        p.add_argument("--out", default="reports", help="folder for report.md/.html/.json")
        p.add_argument("--samples", type=int, default=DEFAULT_SAMPLES,
                       help="random states per parameter set")
        p.add_argument("--param-sets", type=int, default=DEFAULT_PARAM_SETS,
                       help="random physically consistent parameter sets")
        p.add_argument("--plots", action="store_true",
                       help="add simulations of each document beside the truth (PNG)")
        p.add_argument("--no-cache", action="store_true",
                       help="use nothing remembered from earlier runs (results, compiled "
                            "code, closed forms) and remember nothing; as WHEELED_DYN_REUSE=0")
        p.set_defaults(handler=_without_cache(handler))
