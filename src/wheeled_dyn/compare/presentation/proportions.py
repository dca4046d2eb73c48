r"""The parameter families of a model without a physical record, as relations between Khalil's
standard parameters (for writing the truth in a document's symbols; nothing here decides).

The random parameter sets (:mod:`..grid.samples`) keep some of the URDF's structure, and the
truth a report prints holds only under it:

- a link *scaled as a whole* (every link with mass under ``urdf_proportions``; the two drive
  wheels of a wheeled model always, with one shared pair of factors) has parameters
  :math:`p = p_0\,\mu\,\sigma^{d(p)}` — :math:`p_0` the URDF's value, :math:`\mu` a mass factor,
  :math:`\sigma` a size factor, :math:`d = 0` for the mass, 1 for its first moments
  :math:`MX, MY, MZ`, 2 for the inertia entries;
- under ``urdf_structure`` (and in a link scaled as a whole) a parameter that is zero in the
  URDF stays zero.

The relations are used in two stages, so that a document's own symbols stay where it declared
them: :func:`equalities` — the zeros, and in a group scaled together the parameters of one
power that are equal in the URDF (a wheel's two diameters, the second wheel's parameters) —
before the declarations are solved; :func:`completed` after, for a group's parameters no
declaration determined, from the factors its solved ones give:
:math:`\mu = M/M_0`, :math:`\sigma = MX/(MX_0\mu)`, :math:`\tau = \sigma^2 = I/(I_0\mu)`.
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence

import sympy as sp

from ...models.builder import WheeledModel
from ...models.registry import model_parameters
from ...symbolic.parameter_modes import carrier_parameters
from ...symbolic.parameters import PARAMETER_NAMES

#: The size power of each standard parameter in a link scaled as a whole.
POWERS: dict[str, int] = {"M": 0, "MX": 1, "MY": 1, "MZ": 1, "XX": 2, "XY": 2, "XZ": 2,
                          "YY": 2, "YZ": 2, "ZZ": 2}


def _symbol(kind: str, link: str) -> sp.Symbol:
    return sp.Symbol(f"{kind}_{link}", real=True)


def _exact(x: float) -> sp.Expr:
    return sp.nsimplify(x, rational=True)


def _links(values: Mapping[str, float]) -> list[str]:
    out: dict[str, None] = {}
    for key in values:
        kind, _, rest = key.partition("(")
        if kind in POWERS and rest.endswith(")"):
            out.setdefault(rest[:-1], None)
    return list(out)


def scaled_groups(wm: WheeledModel, families: Sequence[str]) -> list[tuple[str, ...]]:
    r"""The groups of links scaled together (module text)."""
    values = model_parameters(wm)
    wheels = tuple(getattr(wm.spec, "wheels", ()) or ())
    groups: list[tuple[str, ...]] = [wheels] if len(wheels) == 2 else []
    if "urdf_proportions" in families:
        groups += [(link,) for link in _links(values)
                   if link not in wheels and values.get(f"M({link})", 0.0) > 0]
    return groups


def equalities(wm: WheeledModel, families: Sequence[str]) -> dict[sp.Symbol, sp.Expr]:
    r"""The zeros and the equal parameters of the groups (module text), as a substitution."""
    values = model_parameters(wm)
    groups = scaled_groups(wm, families)
    grouped = {link for g in groups for link in g}
    out: dict[sp.Symbol, sp.Expr] = {}
    zeros = "urdf_structure" in families or "urdf_proportions" in families
    carried = carrier_parameters(wm)
    for link in _links(values):
        if link in carried:                # its body's zeros, in its joint frame (below)
            continue
        if zeros or link in grouped:
            out.update({_symbol(k, link): sp.Integer(0) for k in POWERS
                        if values.get(f"{k}({link})") == 0.0})
    for link, symbols in carried.items():  # the draws keep the joint frame's zeros
        if zeros or link in grouped:
            jid = wm.model.getJointId(symbols["M"].name[len("M_"):])
            body = wm.model.inertias[jid].toDynamicParameters()
            out.update({sp.Symbol(f"{k}_{symbols['M'].name[len('M_'):]}", real=True):
                        sp.Integer(0) for k, v in zip(PARAMETER_NAMES, body) if v == 0.0})
    if "principal_axes" in families:     # IXY = 0 about the centre: XY = -MX MY / M ...
        for link in _links(values):
            if link in carried or not values.get(f"M({link})"):
                continue
            first_moment = {a: _symbol(f"M{a}", link) for a in "XYZ"}
            for a, b in ("XY", "XZ", "YZ"):
                out.setdefault(_symbol(a + b, link),
                               -first_moment[a] * first_moment[b] / _symbol("M", link))
    for group in groups:
        first: dict[tuple[int, float], sp.Symbol] = {}
        for link in group:
            for kind, power in POWERS.items():
                v = values.get(f"{kind}({link})")
                if v is None or v == 0.0:
                    continue
                key = (power, round(v, 12))
                sym = _symbol(kind, link)
                if key in first:
                    out[sym] = first[key]
                else:
                    first[key] = sym
    return out


def completed(wm: WheeledModel, families: Sequence[str], solved: Mapping[sp.Symbol, sp.Expr]
              ) -> dict[sp.Symbol, sp.Expr]:
    r"""The parameters of each scaled group that ``solved`` leaves out, from the factors its
    solved parameters give (module text); a group without a solved mass is left as it is."""
    values = model_parameters(wm)
    out: dict[sp.Symbol, sp.Expr] = {}
    for group in scaled_groups(wm, families):
        known = {(kind, link): solved[_symbol(kind, link)] for link in group for kind in POWERS
                 if _symbol(kind, link) in solved and values.get(f"{kind}({link})")}
        mu = next((v / _exact(values[f"M({link})"]) for (kind, link), v in known.items()
                   if kind == "M"), None)
        if mu is None:
            continue
        sigma = next((v / (_exact(values[f"{kind}({link})"]) * mu)
                      for (kind, link), v in known.items() if POWERS[kind] == 1), None)
        tau = next((v / (_exact(values[f"{kind}({link})"]) * mu)
                    for (kind, link), v in known.items() if POWERS[kind] == 2), None)
        tau = sigma ** 2 if tau is None and sigma is not None else tau
        sigma = sp.sqrt(tau) if sigma is None and tau is not None else sigma
        scale = (sp.Integer(1), sigma, tau)
        for link in group:
            for kind, power in POWERS.items():
                v = values.get(f"{kind}({link})")
                sym = _symbol(kind, link)
                if v and sym not in solved and scale[power] is not None:
                    out[sym] = sp.simplify(_exact(v) * mu * scale[power])
    return out


__all__ = ["POWERS", "completed", "equalities", "scaled_groups"]
