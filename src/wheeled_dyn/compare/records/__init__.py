r"""What a comparison says about one derivation, as frozen, picklable records.

The data flow of :mod:`wheeled_dyn.compare` is one way:

.. code-block:: text

    derivation → evaluation (truth and document on the same samples) → element records
               → causes (the few reasons that explain the records) → DerivationResult

- :class:`ElementRecord`: one element of A, C, Q, B, G or one velocity product of
  :math:`h = C\dot q`, or one component of an earlier step of the derivation (a velocity, an
  energy, a constraint, a claim), with its verdict and diagnoses.
- :class:`Cause`: one reason, named by its ``kind`` (:data:`CAUSE_KINDS`), the elements it
  explains and one sentence in the document's own symbols. A cause is reported once, however
  many elements (C-level and h-level) it explains.
- :class:`ConventionSummary`: the verdict counts under the convention the file declares and
  under the best one found (sign flips and scalings of coordinates, velocities and inputs,
  permutations of inputs, row scalings, half vs full track).
- :class:`DerivationResult`: everything the reports (Markdown, HTML, JSON) show of one
  derivation. ``as_dict`` is the JSON contract documented in ``docs/report-schema.json``.
"""

from __future__ import annotations

from .diagnosis import Diagnosis, diagnosis, first_of, has_kind, in_product
from .kinds import (CAUSE_KINDS, SPECIFIC_KINDS, STEPS, VERDICTS, CauseKind, DiagnosisKind,
                    Step, Verdict)
from .result import (Cause, Convention, ConventionSummary, DerivationResult, ElementRecord,
                     EnergyCheck, EquationRecord)

__all__ = ["CAUSE_KINDS", "SPECIFIC_KINDS", "STEPS", "VERDICTS", "Cause", "CauseKind",
           "Convention", "ConventionSummary", "DerivationResult", "Diagnosis", "DiagnosisKind",
           "ElementRecord", "EnergyCheck", "EquationRecord", "Step", "Verdict", "diagnosis",
           "first_of", "has_kind", "in_product"]
