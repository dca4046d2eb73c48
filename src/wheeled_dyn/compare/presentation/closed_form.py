r"""Closed forms for the reports: the document's elements in the model's own parameters, and
(when the symbolic engine provides them) the true expressions and simplified residuals.

For the WIP, Khalil's standard parameters are functions of the physical ones
(:func:`~wheeled_dyn.models.wip_parameters.standard_parameters` applied to SymPy symbols), so a
document written with XX1, MY1 ... reads, after the parameter map, in m_S, d, I1 ... — the
"equivalent form" column of seed 001's own table.
"""

from __future__ import annotations

from collections.abc import Callable, Mapping

import sympy as sp
from sympy.core.function import AppliedUndef

from ...derivations.expressions import physical_in_standard
from ...derivations.schema import Derivation
from ...expression_size import ops_over
from ...models.registry import model_entry, model_version
from ...models.wip_parameters import WipParameters, standard_parameters
from ..records import Diagnosis, DiagnosisKind
from .in_document import in_document
from .linearised import linearised_truth
from .printing import printed
from .residuals import residual_text
from .solved_frame import solved_truth, solved_weights

#: Elements of the document longer than this many operations are not printed again in the
#: model's parameters (a form solved for the accelerations: a page of text nobody reads).
MODEL_PRINT_LIMIT = 150


def _physical_symbols() -> dict[str, sp.Symbol]:
    from dataclasses import fields
    return {f.name: sp.Symbol(f.name, real=True) for f in fields(WipParameters)}


def _standard_names(model: str) -> Callable[[sp.Expr], sp.Expr]:
    r"""For a model without a physical record: Khalil calls ``XX(link)`` → the symbolic
    engine's symbols ``XX_link`` (of a link whose frame is not its body's joint frame, the
    body's symbols moved to it: :func:`~wheeled_dyn.symbolic.parameter_modes.carrier_parameters`),
    the model's lengths and constants as its closed forms write
    them (a drawn length a symbol: ``origin_x(elbow)`` → ``origin_x_elbow``, a length listed
    with a constant → that constant; gravity's magnitude ``g``; a spring's stiffness and rest
    position ``k_<name>``, ``rest_<name>``), its other names → their values as exact
    numbers, as in its closed forms."""
    from ...models.registry import load_model, model_parameters
    from ...symbolic.lengths import gravity_symbol, length_symbols
    from ...symbolic.parameter_modes import carrier_parameters
    wm = load_model(model)
    lengths = length_symbols(wm) if wm.lengths is not None else {}
    if (g := gravity_symbol(wm)) is not None:     # drawn: the symbol g, as the closed forms
        lengths = {**lengths, "g": g}
    for spring in wm.springs:                      # symbols in the closed forms, drawn
        lengths = {**lengths, **{n: sp.Symbol(n, real=True)
                                 for n in spring.spec.parameter_names}}
    numbers = {sp.Symbol(k, real=True): lengths.get(k, sp.nsimplify(v, rational=True))
               for k, v in model_parameters(wm).items() if "(" not in k}
    plain = {sp.Symbol(s.name): v for s, v in numbers.items()}
    carried = carrier_parameters(wm)

    def convert(out: sp.Expr) -> sp.Expr:
        calls = {}
        for c in out.atoms(AppliedUndef):
            name = f"{c.func.__name__}({c.args[0]})"
            body = carried.get(str(c.args[0]), {})
            calls[c] = lengths[name] if name in lengths else body[c.func.__name__] \
                if c.func.__name__ in body else \
                sp.Symbol(f"{c.func.__name__}_{c.args[0]}", real=True)
        return out.xreplace(calls).xreplace(numbers).xreplace(plain)

    return convert


def model_expression(d: Derivation, standard: bool = False
                     ) -> Callable[[sp.Expr | None], sp.Expr | None]:
    r"""A function: document expression → the same in the model's parameters (for the WIP,
    Khalil calls replaced by the physical parameters; with ``standard``, for a model without a
    physical record, in the symbols of its standard-parameter closed forms)."""
    mapping = {s.symbol: s.value for s in d.symbols.values() if s.value is not None}
    physical = model_entry(d.model).parameters is WipParameters
    names = _physical_symbols()
    std = standard_parameters(names) if physical else None
    to_standard = _standard_names(d.model) if standard and not physical else None

    def convert(expr: sp.Expr | None) -> sp.Expr | None:
        if expr is None:
            return None
        out = sp.sympify(physical_in_standard(sp.sympify(expr).xreplace(mapping)))  # CX -> MX/M
        if to_standard is not None:
            return to_standard(out)
        if std is not None:
            calls = {}
            for call in out.atoms(AppliedUndef):
                link = str(call.args[0])
                if link in std and call.func.__name__ in std[link]:
                    calls[call] = sp.sympify(std[link][call.func.__name__])
            out = out.xreplace(calls)
            out = out.xreplace({s: names.get(s.name, s) for s in out.free_symbols})
        return out

    return convert


def document_in_model(d: Derivation, families: tuple[str, ...] = ()
                      ) -> Callable[[sp.Expr | None], tuple[str, str]]:
    r"""A function: document expression → (text, LaTeX) in the model's parameters, read under
    the parameter ``families`` the document assumes (as the truth beside it is)."""
    to_model = model_expression(d)
    dots = {v: rf"\dot{{{sp.latex(q)}}}" for q, v in zip(d.positions, d.velocities)}
    assumed = family_substitution(families) \
        if model_entry(d.model).parameters is WipParameters else {}

    def convert(expr: sp.Expr | None) -> tuple[str, str]:
        if expr is None or ops_over(expr, MODEL_PRINT_LIMIT):
            return "", ""                 # (a solved form's elements: too long to read)
        out = to_model(expr)
        if out is None:
            return "", ""
        return printed(out.xreplace(assumed), dots)

    return convert


def family_substitution(families: tuple[str, ...]) -> dict[sp.Symbol, sp.Expr]:
    r"""The WIP's special parameter families (:data:`~.samples.WIP_SPECIAL_CASES`) as a
    substitution of its physical symbols, so a closed-form truth reads under what a document
    assumes (``com_on_axis``: :math:`d_x = d_z = 0` ...)."""
    p = _physical_symbols()
    table = {
        "no_products": {p["Ixy"]: 0, p["Ixz"]: 0, p["Iyz"]: 0},
        "com_on_axis": {p["d_x"]: 0, p["d_z"]: 0},
        "disc_wheels": {p["Iw3"]: p["m_C"] * p["R"] ** 2 / 2, p["Iw2"]: p["m_C"] * p["R"] ** 2 / 4},
        "I1_eq_I2": {p["I2"]: p["I1"]},
        "no_armature": {p["I_a"]: 0},
    }
    out: dict[sp.Symbol, sp.Expr] = {}
    for name in families:
        out.update({k: sp.sympify(v) for k, v in table.get(name, {}).items()})
    return out


def uniform_substitution(d: Derivation, links: frozenset[str]) -> dict[sp.Symbol, sp.Expr]:
    r"""A model without a physical record: its ``links`` that the document's families keep
    uniform (:func:`~wheeled_dyn.compare.grid.samples.uniform_links`) as a substitution of its
    closed forms' symbols. Each such link, alone with mass on its joint and at its joint's
    frame, is the URDF's scaled by a length :math:`s` and its mass by :math:`M/M_0`: its first
    moments :math:`\mathrm{MX} = (M/M_0)\,\mathrm{MX}_0\,s`, its second
    :math:`\mathrm{XX} = (M/M_0)\,\mathrm{XX}_0\,s^2`, each length of its class
    :math:`\ell_0 s`, with :math:`s` one of them (one the document uses, if any) over its URDF
    value (:func:`~wheeled_dyn.models.geometry_apply.uniform_scales`)."""
    import pinocchio as pin

    from ...models.geometry_apply import bodies_of, uniform_scales
    from ...models.registry import load_model
    from ...symbolic.parameters import PARAMETER_NAMES
    from ...symbolic.lengths import length_symbols
    from ...symbolic.parameter_modes import standard_names
    wm = load_model(d.model)
    if not links or wm.lengths is None or model_entry(d.model).parameters is not None:
        return {}
    lengths = length_symbols(wm)
    names = standard_names(wm)
    used = {f"{c.func.__name__}({c.args[0]})" if isinstance(c, AppliedUndef) else c.name
            for s in d.symbols.values() if s.value is not None
            for c in (*s.value.atoms(AppliedUndef), *s.value.free_symbols)}
    values = wm.lengths.values()
    massive = {jid: [k for k in ks if wm.lengths.inertials.get(k, (0.0,))[0] > 0]
               for jid, ks in bodies_of(wm).items()}
    out: dict[sp.Symbol, sp.Expr] = {}
    for link, (group, _, members) in uniform_scales(wm, links).items():
        group = next((m for m in members if m in used and values.get(m)), group)
        scale = lengths[group] / sp.nsimplify(values[group], rational=True)
        for name in members:
            symbol = lengths.get(name)
            if isinstance(symbol, sp.Symbol) and symbol != lengths[group]:
                out[symbol] = sp.nsimplify(values[name], rational=True) * scale
        body = wm.joint_id_of_link(link)
        frame = wm.model.frames[wm.model.getFrameId(link, pin.FrameType.BODY)]
        if massive.get(body) != [link] or not frame.placement.isIdentity(1e-12):
            continue
        # the uniform body's where the URDF prints it rounded, as the grid draws it (its
        # moments m (3 r² + L²)/12 computed in floats: written as the fractions they are)
        read = link in wm.lengths.uniform
        pi = wm.lengths.uniform[link][0] if read else \
            wm.model.inertias[body].toDynamicParameters()
        exact = [_fraction(x) if read else sp.nsimplify(x, rational=True) for x in pi]
        mass = sp.Symbol(f"M_{names[body]}", real=True) / exact[0]
        for k, (key, x) in enumerate(zip(PARAMETER_NAMES, exact)):
            if k:
                out[sp.Symbol(f"{key}_{names[body]}", real=True)] = \
                    mass * x * scale ** (1 if k < 4 else 2)
    return out


def _fraction(x: float) -> sp.Rational:
    r"""``x`` as the fraction of denominator at most 10⁶ it is to 10⁻¹² (a float's exact
    binary fraction where it is none)."""
    near = sp.Rational(x).limit_denominator(10 ** 6)
    return near if abs(float(near) - x) <= 1e-12 * abs(x) else sp.nsimplify(x, rational=True)


def massless_substitution(d: Derivation, links: frozenset[str]) -> dict[sp.Symbol, sp.Expr]:
    r"""The ``links`` a declared ``massless(link, ...)`` family takes off (each the only link
    with mass of its rigid body, :func:`~wheeled_dyn.compare.grid.samples.massless_family`):
    every inertial parameter of its body zero in the closed forms (a caster the document
    leaves out printed its mass terms in the truth and in truth − document)."""
    from ...models.registry import load_model
    from ...symbolic.parameter_modes import standard_names
    from ...symbolic.parameters import PARAMETER_NAMES
    if not links or model_entry(d.model).parameters is not None:
        return {}
    wm = load_model(d.model)
    names = standard_names(wm)
    return {sp.Symbol(f"{key}_{names[wm.joint_id_of_link(link)]}", real=True): sp.Integer(0)
            for link in sorted(links) for key in PARAMETER_NAMES}


def _row_label(label: str, row: int) -> str:
    r"""``A[2,3]`` → ``A[row+1,3]``, ``h[2]:dx*dpsi`` → ``h[row+1]:dx*dpsi``."""
    head, _, rest = label.partition("[")
    inner, _, tail = rest.partition("]")
    parts = inner.split(",")
    parts[0] = str(row + 1)
    return f"{head}[{','.join(parts)}]{tail}"


def annotate(d: Derivation, drafts: list, cs, frames: dict[int, tuple[sp.Expr, ...] | sp.Expr],
             families: tuple[str, ...] = (), uniform: frozenset[str] = frozenset(),
             linearised: tuple[tuple[tuple[str, float], ...], bool] | None = None,
             massless: frozenset[str] = frozenset(),
             solved: Mapping[int, tuple[int, sp.Expr]] | None = None
             ) -> dict[str, sp.Expr] | None:
    r"""Fill ``truth`` (every element, in its row's frame: the truth it is compared with) and
    ``residual`` (truth − document, expanded, for the elements that do not agree) of the
    ``drafts`` where the symbolic engine provides closed forms; without them the drafts keep
    their numeric verdicts. ``frames``: per row, the
    document's frame in its own symbols — a factor :math:`c` (the row is :math:`c` × the true
    one) or the weights :math:`f_i` of a combination of the true rows; rows absent from it get
    no residual. The truth and the document are both read under the parameter ``families`` the
    document assumes (:func:`family_substitution`), a model without a physical record with its
    ``uniform`` links scaled as a whole (:func:`uniform_substitution`) and its ``massless``
    ones without mass (:func:`massless_substitution`); in the document's own
    symbols where its declarations determine the parameters (:func:`.in_document.in_document`:
    then the truth so written is returned), else in the model's. ``linearised``: (the
    point, whether the potential is measured from the equilibrium) of a document that
    declares ``linearised_about``: the truth linearised there
    (:func:`.linearised.linearised_truth`), as it is judged. ``solved``: rows solved for an
    acceleration whose weights were not fitted, row ``i`` as ``(k, c)`` (:math:`A_{doc,i} =
    c\,e_k`): their frame is :math:`c` × row :math:`k` of the true :math:`A^{-1}`
    (:func:`solved_weights`), where it is small enough to write, else they are shown no truth
    (it would be that of the equations before solving)."""
    found = true_forms(d, cs, families, uniform, linearised, massless)
    if found is None:
        return None
    truth, physical, to_model, in_symbols = found
    dots = {v: rf"\dot{{{sp.latex(q)}}}" for q, v in zip(d.positions, d.velocities)}
    by_name = {str(v): text for v, text in dots.items()}
    solved = solved or {}
    inverse = solved_weights(truth, d.n) if solved else None
    for r in drafts:
        expr = truth.get(r.element)
        if expr is None or r.key == "B":
            continue
        if r.row in solved and inverse is None:
            continue                     # compared in a frame that has no closed form here
        if r.row in solved and inverse is not None:
            in_frame = solved_truth(solved[r.row][1] * _combined(
                r.element, inverse[solved[r.row][0]], truth))
            if in_frame is None:
                continue                 # too long to write in the solved frame
        else:
            in_frame = _in_frame(r.element, expr, frames.get(r.row), truth, to_model)
        shown = expr if in_frame is None else in_frame     # the truth the row is compared with
        names = {sym: by_name[sym.name] for sym in shown.free_symbols if sym.name in by_name}
        r.truth, r.truth_latex = printed(shown, names)
        if r.verdict == "agrees" or in_frame is None:
            continue
        doc = to_model(r.expr)
        if doc is None:
            continue
        text = residual_text(in_frame, doc, physical, r.row in solved)
        if text is None:
            continue
        r.residual = text
        if text != "0":
            r.diagnoses.append(Diagnosis(DiagnosisKind.RESIDUAL, f"truth − document = {text}",
                                         text))
    return truth if in_symbols else None


#: :func:`true_forms`' last answer, by the identity of its derivation and coordinate set and
#: its other arguments and the model's files (the judge's read-backs and the reports'
#: annotations ask for the same).
_FORMS: list = [None, None]


def true_forms(d: Derivation, cs, families: tuple[str, ...] = (),
               uniform: frozenset[str] = frozenset(),
               linearised: tuple[tuple[tuple[str, float], ...], bool] | None = None,
               massless: frozenset[str] = frozenset()
               ) -> tuple[dict[str, sp.Expr], bool, Callable, bool] | None:
    r"""The truth's closed forms as :func:`annotate` compares with them (arguments as there):
    (the truth by element label, whether the document's side is read in the same parameters,
    the map of a document expression to them, whether they are the document's own symbols);
    None where the symbolic engine gives none."""
    # a model file or URDF saved since (compare --watch keeps the derivation): other forms
    key = (families, uniform, linearised, massless, model_version(d.model))
    last = _FORMS[0]
    if last is not None and last[0] is d and last[1] is cs and last[2] == key:
        return _FORMS[1]
    try:
        from ...symbolic import lengths_are_symbols, true_expressions
    except ImportError:
        return None
    truth = true_expressions(d.model, cs)
    if not truth:
        return None
    physical = model_entry(d.model).parameters is WipParameters
    to_model = model_expression(d, standard=not physical)
    assumed = family_substitution(families) if physical else {
        **uniform_substitution(d, uniform), **massless_substitution(d, massless)}
    ours = in_document(d, truth, to_model, assumed, families, standard=not physical) \
        if lengths_are_symbols(d.model) else None        # else true at the URDF's lengths only
    if ours is not None:                 # the document's side in the same symbols
        truth, physical, unsolved = ours.truth, True, ours.unsolved

        def to_model(e: sp.Expr | None) -> sp.Expr | None:
            return None if e is None else sp.sympify(e).xreplace(unsolved)
    elif assumed:
        truth = {k: sp.sympify(v).xreplace(assumed) for k, v in truth.items()}
        plain = to_model

        def to_model(e: sp.Expr | None) -> sp.Expr | None:
            out = plain(e)
            return None if out is None else out.xreplace(assumed)
    if linearised is not None:
        # gravity, by the name the truth writes it with: the document's symbol valued g, or
        # the model's g (where the document names none, or the truth is in the model's)
        g = {spec.symbol.name for spec in d.symbols.values()
             if isinstance(spec.value, sp.Symbol) and spec.value.name == "g"} \
            if ours is not None else set()
        if not g and (ours is None or all(s.symbol.name != "g" for s in d.symbols.values())):
            g = {"g"}
        truth = linearised_truth(truth, d.positions, *linearised, gravity=frozenset(g))
    _FORMS[:] = [(d, cs, key), (truth, physical, to_model, ours is not None)]
    return _FORMS[1]


def _combined(element: str, weights: tuple[sp.Expr, ...], truth: dict[str, sp.Expr]) -> sp.Expr:
    r"""The combination of the true rows' ``element`` with ``weights`` (in the truth's
    symbols); an element a row lacks counts 0."""
    return sp.Add(*(w * truth.get(_row_label(element, k), sp.Integer(0))
                    for k, w in enumerate(weights) if w != 0))


def _in_frame(element: str, expr: sp.Expr, frame: tuple[sp.Expr, ...] | sp.Expr | None,
              truth: dict[str, sp.Expr], to_model: Callable[[sp.Expr | None], sp.Expr | None]
              ) -> sp.Expr | None:
    r"""The true ``element`` (``expr``) in its row's ``frame``: the factor times it, or the
    combination of the true rows' same elements; None where the row has no frame here or one
    of them has no closed form."""
    if frame is None:
        return None
    if not isinstance(frame, tuple):
        factor = to_model(frame)
        return None if factor is None else expr if factor == 1 else expr * factor
    out = sp.Integer(0)
    for k, w in enumerate(frame):
        if w == 0:
            continue
        weight, true = to_model(w), truth.get(_row_label(element, k))
        if weight is None or true is None:
            return None
        out += weight * true
    return out
