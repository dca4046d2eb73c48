r"""How the reports write symbols: names as a reader of the document writes them.

Three rules.

1. **Multi-letter names are one symbol**, never a product: the part after the first capital
   (or after an underscore, or a trailing number) is a subscript,

   .. math::

       \mathtt{Ixy}\to I_{xy},\quad \mathtt{XX1}\to XX_{1},\quad \mathtt{I\_w2}\to I_{w2},
       \quad \mathtt{m\_S}\to m_{S},\quad \mathtt{theta\_l}\to\theta_{l},\quad
       \mathtt{Omega}\to\Omega .

2. **A velocity is a dotted position only where it is the rate of that position.** In a
   holonomic coordinate set every velocity :math:`\dot q_i` is; in a quasi-velocity set only a
   velocity named ``d<position>`` is (``dx0`` → :math:`\dot x_0`), every other one keeps the
   document's own letter (``q`` → :math:`q`, ``n`` → :math:`n`, ``xi`` → :math:`\xi`), and its
   derivative is dotted (``dq`` → :math:`\dot q`). Any other name ``d<position>`` (in a
   truth, a definition) is the rate :math:`\dot{q}`, never the product :math:`d\,q`.
3. **Expressions are re-read from the records' text** (SymPy's ``sstr``) with every name a
   plain symbol, so ``I``, ``E``, ``S``, ``N`` ... stay symbols of the document, then written
   by :func:`sympy.latex` with the names above; a standard parameter of a link written as a
   call (``XX(ball)``) is the symbol :math:`XX_{\mathrm{ball}}`.
"""

from __future__ import annotations

import re
from collections.abc import Mapping
from dataclasses import dataclass, field
from pathlib import Path

import sympy as sp

from ..disk_cache import DiskMemo
from ..expression_size import expand_trig_small
from ..sympy_text import parse

#: Names written as Greek letters (lower case; a capitalised one is the capital letter).
GREEK = ("alpha", "beta", "gamma", "delta", "epsilon", "varepsilon", "zeta", "eta", "theta",
         "vartheta", "iota", "kappa", "lambda", "mu", "nu", "xi", "pi", "rho", "sigma", "tau",
         "upsilon", "phi", "varphi", "chi", "psi", "omega")
_CAPITAL_GREEK = ("Gamma", "Delta", "Theta", "Lambda", "Xi", "Pi", "Sigma", "Upsilon", "Phi",
                  "Psi", "Omega")

#: Differences up to this many operations are simplified for display.
SIMPLIFY_LIMIT = 80
#: Simplified differences up to this many operations get their common factors pulled out.
FACTOR_LIMIT = 40

def _split(name: str) -> tuple[str, str]:
    r"""(LaTeX of the base letter(s), subscript text) of a name by rule 1."""
    if "_" in name.strip("_"):
        base, _, sub = name.strip("_").partition("_")
        head, inner = _split(base)
        return head, ",".join(x for x in (inner, _subscript(sub)) if x)
    if name in GREEK or name in _CAPITAL_GREEK:
        return "\\" + name, ""
    m = re.fullmatch(r"([A-Za-z]+?)(\d+)", name)              # XX1, u1, K11, theta1
    if m:
        head, inner = _split(m.group(1))
        return head, inner + m.group(2)
    m = re.fullmatch(r"([A-Z]+)([a-z][a-z0-9]*)", name)      # Ixy, Iw3, YZw, Mw
    if m:
        return m.group(1), _subscript(m.group(2))
    if len(name) > 1 and name.isalpha() and name.islower():
        return rf"\mathit{{{name}}}", ""
    return name, ""


def accented(name: str, accent: str) -> str:
    r"""``name`` with ``accent`` (``\dot``, ``\ddot``) over its letter, not its subscript:
    ``x0`` → ``\dot{x}_{0}``."""
    base, sub = _split(name)
    return f"{accent}{{{base}}}" + (f"_{{{sub}}}" if sub else "")


def name_latex(name: str) -> str:
    r"""LaTeX of one symbol name by rule 1 (``Ixy`` → ``I_{xy}``, ``theta_l`` → ``\theta_{l}``)."""
    base, sub = _split(name)
    if len(base) > 1 and base.isalpha():      # one symbol, not a product: {XX}_{1}
        base = f"{{{base}}}"
    return f"{base}_{{{sub}}}" if sub else base


def _subscript(text: str) -> str:
    parts = [p for p in text.split("_") if p]
    return ",".join("\\" + p if (p in GREEK or p in _CAPITAL_GREEK) else
                    (p if len(p) <= 3 or not p.isalpha() else rf"\mathrm{{{p}}}") for p in parts)


@dataclass(frozen=True)
class Notation:
    r"""The names of one derivation: document velocity and acceleration names → LaTeX
    (rule 2), positions, and symbols with a LaTeX form declared in the file."""

    positions: tuple[str, ...] = ()
    special: Mapping[str, str] = field(default_factory=dict)
    assumed: Mapping[str, str] = field(default_factory=dict)   # the file's [assume] values
    cache: dict = field(default_factory=dict, compare=False, hash=False, repr=False)

    def text(self, name: str) -> str:
        r"""Plain-text (Unicode) form of ``name`` in this derivation (``dpsi`` → ``ψ̇``)."""
        for n in (2, 1):
            base = name[n:]
            if name[:n] == "d" * n and (base in self.positions or base in GREEK):
                return name_text(base, n)
        tex = self.special.get(name, "")
        for source in (*self.positions, *self.special):
            for dots, accent in ((1, r"\dot"), (2, r"\ddot")):
                if tex and tex == accented(source, accent):
                    return name_text(source, dots)
        return name_text(name)

    def label(self, element: str) -> str:
        r"""An element label in plain text: ``h[2]:dx*dpsi`` → ``h[2] ẋψ̇``."""
        if ":" not in element:
            return element
        row, product = element.split(":", 1)
        return f"{row} " + "".join(self.text(v) for v in product.split("*"))

    def latex(self, name: str) -> str:
        r"""LaTeX of ``name`` in this derivation."""
        if name in self.special:
            return self.special[name]
        for n, accent in ((2, r"\ddot"), (1, r"\dot")):
            base = name[n:]
            if name[:n] == "d" * n and (base in self.positions or base in GREEK):
                return accented(base, accent)
        return name_latex(name)


def notation(positions: tuple[str, ...], velocities: tuple[str, ...],
             accelerations: tuple[str, ...], quasi: bool,
             declared: Mapping[str, str] | None = None) -> Notation:
    r"""The :class:`Notation` of a coordinate set (rule 2); ``declared``: symbol → LaTeX
    given by the derivation file."""
    special: dict[str, str] = dict(declared or {})
    for q, v, a in zip(positions, velocities, accelerations):
        rate = not quasi or v == "d" + q
        if rate:
            special.setdefault(v, accented(q, r"\dot"))
            special.setdefault(a, accented(q, r"\ddot"))
        else:
            special.setdefault(v, name_latex(v))
            special.setdefault(a, accented(v, r"\dot") if a == "d" + v else name_latex(a))
    return Notation(tuple(positions), special)


_NOTATIONS: dict[tuple[str, float], Notation] = {}       # (file, mtime) -> its notation


def _mtime(path: str | Path) -> float | None:
    try:
        return Path(path).stat().st_mtime
    except OSError:
        return None


def derivation_notation(path: str | Path) -> Notation:
    r"""The :class:`Notation` of a derivation file (read once per file and version); plain
    names (rule 1 only) when the file cannot be read any more."""
    from ..derivations import load_derivation
    from ..errors import WheeledDynError
    mtime = _mtime(path)
    if mtime is None:
        return Notation()
    key = (str(path), mtime)
    if key not in _NOTATIONS:
        try:
            _NOTATIONS[key] = notation_of(load_derivation(Path(path)))
        except (WheeledDynError, OSError):
            return Notation()
    return _NOTATIONS[key]


def remember_notation(d) -> None:
    r"""Keep the notation of the parsed derivation ``d`` for :func:`derivation_notation` of
    its file (a report renders the derivations it has parsed without reading them again)."""
    if (mtime := _mtime(d.path)) is not None:
        _NOTATIONS[(str(d.path), mtime)] = notation_of(d)


def notation_of(d) -> Notation:
    r"""The :class:`Notation` of a parsed derivation ``d``."""
    names = lambda xs: tuple(str(x) for x in xs)    # noqa: E731
    declared = {s.name: s.latex for s in d.symbols.values() if s.latex}
    out = notation(names(d.positions), names(d.velocities), names(d.accelerations),
                   d.coordinates.kind == "quasi", declared)
    return Notation(out.positions, out.special, {k: str(v) for k, v in d.assumptions.items()})




def expression_latex(expr: sp.Basic, names: Notation) -> str:
    r"""LaTeX of ``expr`` with every symbol written by ``names``."""
    from sympy.core.function import AppliedUndef
    calls = {c: sp.Symbol(f"{c.func.__name__}_{c.args[0]}") for c in expr.atoms(AppliedUndef)
             if len(c.args) == 1 and isinstance(c.args[0], sp.Symbol)}
    expr = expr.xreplace(calls) if calls else expr          # XX(ball) → XX_{ball}
    symbol_names = {s: names.latex(s.name) for s in expr.free_symbols if isinstance(s, sp.Symbol)}
    return sp.latex(expr, symbol_names=symbol_names)


def text_latex(text: str | None, names: Notation, fallback: str = "") -> str:
    r"""LaTeX of an expression (or a relation ``lhs = rhs``) given as text; ``fallback`` (e.g.
    the engine's own LaTeX) when the text cannot be read."""
    if not text:
        return fallback
    if text.count("=") == 1:                 # a printed relation: each side
        sides = [text_latex(side, names) for side in text.split("=")]
        return " = ".join(sides) if all(sides) else fallback
    key = ("text", text)
    if key not in names.cache:
        names.cache[key] = _remembered(key, names, lambda: None if (expr := parse(text)) is None
                                       else expression_latex(expr, names))
    return names.cache[key] if names.cache[key] is not None else fallback


def difference_latex(text: str | None, names: Notation, fallback: str = "") -> str:
    r"""LaTeX of a difference given as text, :func:`simplified`; ``""`` for none or zero."""
    if text in (None, "", "0"):
        return ""
    key = ("difference", text)
    if key not in names.cache:
        latex = _remembered(key, names, lambda: None if (expr := parse(text)) is None
                            else expression_latex(simplified(expr), names))
        names.cache[key] = fallback if latex is None else latex
    return names.cache[key]


#: Version of the rendered-LaTeX entries kept on disk (another version's are not read).
RENDER_CACHE_VERSION = "1"
#: The LaTeX of texts in a derivation's notation, remembered across runs (the disk cache's
#: ``report/latex-<code>.pickle``, named by SymPy's version and this package's code: LaTeX
#: made by other code is not read).
RENDERED = DiskMemo("report", "latex", lambda: Path(__file__).parent.glob("*.py"))


def _remembered(key: tuple, names: Notation, compute) -> str | None:
    r"""``compute()`` — the LaTeX of a text in a derivation's notation — remembered across
    runs (:data:`RENDERED`): a report rendered again does not simplify and print the same
    differences again."""
    full = (RENDER_CACHE_VERSION, *key, names.positions, tuple(sorted(names.special.items())))
    return RENDERED.get(full, compute)


def simplified(expr: sp.Expr) -> sp.Expr:
    r"""A shorter equal form of a difference for display (multiple angles expanded,
    :math:`\cos^2 = 1 - \sin^2`, common factors pulled out), when it has at most :data:`SIMPLIFY_LIMIT` operations."""
    if sp.count_ops(expr) > SIMPLIFY_LIMIT:
        return expr
    expanded = sp.expand(expand_trig_small(expr))
    pythagoras = {c ** 2: 1 - sp.sin(c.args[0]) ** 2 for c in expanded.atoms(sp.cos)}
    best = min([expr, expanded, sp.expand(expanded.xreplace(pythagoras))], key=sp.count_ops)
    return sp.factor_terms(best) if sp.count_ops(best) <= FACTOR_LIMIT else best


_GREEK_LETTERS = dict(zip(GREEK, "αβγδεεζηθϑικλμνξπρστυφφχψω"))
_GREEK_LETTERS.update(zip(_CAPITAL_GREEK, "ΓΔΘΛΞΠΣΥΦΨΩ"))
_SUBSCRIPT_DIGITS = str.maketrans("0123456789", "₀₁₂₃₄₅₆₇₈₉")


def name_text(name: str, dots: int = 0) -> str:
    r"""Plain-text (Unicode) form of a name with ``dots`` dots over its letter: ``theta_l``,
    1 → ``θ̇_l``; ``x0``, 1 → ``ẋ₀``."""
    base, sub = _split(name)
    base = _GREEK_LETTERS.get(base.lstrip("\\"), base.lstrip("\\")) if base.startswith("\\") \
        and not base.startswith("\\mathit") else re.sub(r"\\mathit\{(.*)\}", r"\1", base)
    base += ("\u0307" if dots == 1 else "\u0308" if dots == 2 else "")
    sub = sub.replace("\\mathrm", "").replace("{", "").replace("}", "")
    sub = "".join(_GREEK_LETTERS.get(p.lstrip("\\"), p) for p in re.split(r"(\\[a-zA-Z]+)", sub))
    return base + (sub.translate(_SUBSCRIPT_DIGITS) if sub.isdigit() else f"_{sub}" if sub else "")


def product_latex(label: str, names: Notation) -> str:
    r"""LaTeX of a velocity product as the records name it (``dpsi*dphi`` → :math:`\dot\psi
    \dot\phi`)."""
    return r"\,".join(names.latex(v) for v in label.split("*"))
