r"""Published linearised equations compared with the model's own linearisation.

A linearised-equation file (:mod:`~wheeled_dyn.derivations.linear_document`, e.g. the Whipple
bicycle benchmark of Meijaard et al. 2007) prints :math:`M, C_1, K_0, K_2` of

.. math:: M\ddot p + v C_1\dot p + (g K_0 + v^2 K_2)\,p = f,

eigenvalues against the speed :math:`v`, and stability boundaries. The truth is the model's
reduced dynamics (rolling eliminated in the independent velocities the file's ``[reduction]``
names) linearised about steady straight running (:func:`~.rolling_linear.speed_form`), its
eigenvalues at each printed speed from a fresh linearisation, and the boundaries found where
the largest real part of the eigenvalues changes sign.

A number **agrees to the published digits** when the truth rounds to it: it differs from the
printed value by at most half a unit in its last printed decimal (the printed number's
shortest representation gives its decimals; a printed 0 is exact), plus
:data:`ROUNDING_SLACK` relative to the number (at least 1).
"""

from __future__ import annotations

import tomllib
from pathlib import Path

import numpy as np

from ...derivations.linear_document import LinearDocument, load_linear_document
from ..judge.diagnose import value_diagnoses
from ..records import (Diagnosis, DiagnosisKind as K, DerivationResult, ElementRecord, Step,
                       Verdict, diagnosis)

#: Relative slack beyond half a unit of the last printed decimal (floating point).
ROUNDING_SLACK = 1e-12
#: Speeds scanned for sign changes of the spectral abscissa (m/s), and the root's tolerance.
SCAN_SPEEDS = np.linspace(0.0, 10.0, 201)
ROOT_XTOL = 1e-14
#: Step names of the records.
STEP = Step.LINEARISED_EQUATIONS


def is_linear_document(path: str | Path) -> bool:
    r"""A TOML file with a ``[form]`` table and no ``[matrices]`` (a linearised-equation file,
    not a derivation file). False for anything unreadable, a FIFO or a device included (the
    derivation parser then reports it)."""
    from ...derivations.source import read_small_text
    from ...errors import InputFileError
    try:                                  # a regular file of bounded size only (not a FIFO)
        data = tomllib.loads(read_small_text(Path(path)))
    except (InputFileError, OSError, tomllib.TOMLDecodeError, RecursionError):
        return False
    return isinstance(data.get("form"), dict) and "matrices" not in data


def half_unit(value: float) -> float:
    r"""Half a unit in the last decimal of ``value`` as printed (its shortest repr); 0 for a
    printed 0, which is exact (a structural zero of the equations)."""
    if value == 0:
        return 0.0
    text = repr(float(value)).lower()
    mantissa, _, exponent = text.partition("e")
    decimals = len(mantissa.split(".")[1]) if "." in mantissa else 0
    decimals -= int(exponent) if exponent else 0
    return 0.5 * 10.0 ** (-decimals)


def _record(element: str, key: str, index: tuple[int, ...], printed: float, truth: float,
            equation: str) -> ElementRecord:
    tol = half_unit(printed) + ROUNDING_SLACK * max(abs(printed), abs(truth), 1.0)
    error = abs(printed - truth)
    ok = bool(np.isfinite(truth)) and error <= tol
    diags: tuple[Diagnosis, ...] = ()
    if not ok:
        diags = tuple(value_diagnoses(np.array([printed]), np.array([truth]), max(tol, 1e-300)))
        diags += (diagnosis(K.NOTE, f"the truth is {truth!r}: it does not round to the "
                            f"printed digits (off by {error:.3g}, half a unit of the last "
                            f"digit is {tol:.1g})", prefix=""),)
    return ElementRecord(element=element, key=key, index=index,
                         verdict=Verdict.AGREES if ok else Verdict.DIFFERS, diagnoses=diags,
                         document=repr(printed), document_model="", truth=repr(truth),
                         residual=None, max_error=error, scale=max(abs(truth), 1e-300),
                         truth_sample=truth, document_sample=printed, step=STEP,
                         equation=equation)


class LinearTruth:
    r"""The model's linearisation for a linear document: the speed form, and eigenvalues of
    fresh linearisations at any speed."""

    def __init__(self, doc: LinearDocument) -> None:
        from ...constraints.rolling_linear import linearise, speed_form
        from ...constraints.wheel_reduction import RollingReduction
        from ...models.registry import load_model
        self.doc = doc
        self._linearise = linearise
        wm = load_model(doc.model)
        independent, dependent, unit = doc.reduction
        self.red = RollingReduction(wm, independent, dependent)
        self.q0 = self.red.on_ground(np.zeros(wm.nv))
        self.unit = np.array([unit.get(name, 0.0) for name in independent], dtype=float)
        self.rates = [independent.index(p) for p in doc.positions]
        self.form, _, _ = speed_form(self.red, self.q0, doc.positions, self.unit, self.rates,
                                     doc.form.g)

    def eigenvalues(self, speed: float) -> np.ndarray:
        r"""Eigenvalues of the roll-steer block of a fresh linearisation at ``speed``."""
        lin = self._linearise(self.red, self.q0, self.doc.positions, speed * self.unit)
        sel = self.rates
        M, D, K = lin.M[np.ix_(sel, sel)], lin.D[np.ix_(sel, sel)], lin.K[sel][:, :len(sel)]
        k = len(sel)
        A = np.block([[np.zeros((k, k)), np.eye(k)],
                      [-np.linalg.solve(M, K), -np.linalg.solve(M, D)]])
        return np.linalg.eigvals(A)

    def boundaries(self) -> list[float]:
        r"""Speeds where the largest real part of the eigenvalues changes sign, in order."""
        abscissa = self.form.eigenvalues(SCAN_SPEEDS).real.max(axis=1)
        out = []
        for a, b, fa, fb in zip(SCAN_SPEEDS, SCAN_SPEEDS[1:], abscissa, abscissa[1:]):
            if fa * fb < 0:
                from scipy.optimize import brentq    # stability boundaries only
                out.append(brentq(lambda v: self.eigenvalues(v).real.max(), a, b,
                                  xtol=ROOT_XTOL))
        return out


def compare_linear(path: str | Path) -> DerivationResult:
    r"""The records of a linear document: every printed entry of :math:`M, C_1, K_0, K_2`,
    every printed eigenvalue (real and imaginary parts against the nearest computed one) and
    the claimed stability boundaries (``weave_speed``, ``capsize_speed``: the first and the
    second sign change of the spectral abscissa)."""
    doc = load_linear_document(path)
    truth = LinearTruth(doc)
    records: list[ElementRecord] = []
    for name in ("M", "C1", "K0", "K2"):
        printed, ours = getattr(doc.form, name), getattr(truth.form, name)
        for i, j in np.ndindex(printed.shape):
            records.append(_record(f"{name}[{i + 1},{j + 1}]", name, (i, j), float(printed[i, j]),
                                   float(ours[i, j]), "(5.3)"))
    for speed, values in sorted(doc.eigenvalues.items()):
        ours = truth.eigenvalues(speed)
        for k, value in enumerate(values):
            near = ours[int(np.argmin(np.abs(ours - value)))]
            for part, p, t in (("re", value.real, near.real), ("im", value.imag, near.imag)):
                records.append(_record(f"eigenvalue {k + 1} at v = {speed:g} ({part})",
                                       "eigenvalue", (k,), float(p), float(t), "Table 2"))
    found = truth.boundaries()
    for k, key in enumerate(("weave_speed", "capsize_speed")):
        if key in doc.claims:
            value = found[k] if k < len(found) else float("nan")
            records.append(_record(key.replace("_", " "), "claim", (k,), doc.claims[key],
                                   value, "section 5"))
    return DerivationResult(
        path=doc.path, title=doc.title, model=doc.model, source=dict(doc.source or {}),
        coordinates="linearised: " + ", ".join(doc.positions),
        velocities=tuple(doc.positions), form="linearised", records=tuple(records),
        row_factors=(), energy=None, asymmetric=(), constraints=(), reconstructed={},
        samples=1, parameter_sets=1,
        notes=("the truth is the model's reduced dynamics linearised about steady straight "
               "running; a number agrees when the truth rounds to its printed digits",))


__all__ = ["LinearTruth", "ROUNDING_SLACK", "compare_linear", "half_unit", "is_linear_document"]
