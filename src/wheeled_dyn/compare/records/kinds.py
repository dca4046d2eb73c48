r"""The kinds a comparison speaks in, as enums (their values are the JSON's strings): the
verdicts, the kinds of causes, the steps of a derivation and the kinds of diagnoses."""

from __future__ import annotations

from enum import StrEnum


class Verdict(StrEnum):
    r"""Verdict of an element or of an equation. ``UNDECIDED``: the comparison cannot decide
    (values not finite at some samples, and no finite sample differs); never counted as
    agreeing. ``FACTORIZATION``: a C element that differs while :math:`C\dot q` agrees."""

    AGREES = "agrees"
    AGREES_IF = "agrees_if"
    FACTORIZATION = "factorization"
    DIFFERS = "differs"
    UNDECIDED = "undecided"


#: Verdicts of an element, in report order.
VERDICTS: tuple[str, ...] = tuple(v.value for v in Verdict)


class CauseKind(StrEnum):
    r"""Kinds of causes (what the reports group and explain)."""

    CONVENTION = "convention"          # a sign or scaling of a coordinate, velocity, input or row
    QUASI_COORDINATE_CHRISTOFFEL = "quasi_coordinate_christoffel"   # SᵀAṠ missing
    CONSTRAINT_IN_LAGRANGIAN = "constraint_in_lagrangian"
    C_INCONSISTENT_WITH_A = "c_inconsistent_with_a"
    CLAIMED_RELATION = "claimed_relation"
    UPSTREAM_STEP = "upstream_step"
    SIGN = "sign"                      # one additive term with the wrong sign
    POWER = "power"                    # a symbol to the wrong power (G for G², R for R²)
    FACTOR = "factor"                  # a constant factor
    SWAP = "swap"                      # one variable or symbol written for another
    SMALL_ANGLE = "small_angle"        # sin x ≈ x, cos x ≈ 1 in equations compared as exact
    SWAPPED_INPUTS = "swapped_inputs"  # input columns exchanged
    DIMENSION = "dimension"            # a term with inconsistent units
    MISSING_PHYSICS = "missing_physics"  # an effect the document leaves out and does not state
    EXTRA_TERM = "extra_term"          # a term the truth does not have
    POINT_MASS = "point_mass"          # a rigid body treated as a point mass
    PARALLEL_AXIS = "parallel_axis"    # the inertia about the centre where the pivot's fits
    ASSUMPTION = "assumption"          # holds only under a condition the document did not state
    ENERGY = "energy"                  # the model as printed does not conserve energy
    NOT_POSITIVE_DEFINITE = "not_positive_definite"
    NOT_EQUIVALENT = "not_equivalent"  # equations lost, repeated, or scaled by a vanishing factor
    UNDECIDED = "undecided"            # values not finite: no verdict
    FILE_ERROR = "file_error"          # the derivation file contradicts the model or itself


#: Kinds of causes (their values, in order).
CAUSE_KINDS: tuple[str, ...] = tuple(k.value for k in CauseKind)


class Step(StrEnum):
    r"""Steps of a derivation a record can belong to."""

    EQUATIONS_OF_MOTION = "equations of motion"
    VELOCITY = "velocity"
    ANGULAR_VELOCITY = "angular velocity"
    ACCELERATION = "acceleration"
    ANGULAR_ACCELERATION = "angular acceleration"
    KINETIC_ENERGY = "kinetic energy"
    POTENTIAL_ENERGY = "potential energy"
    CONSTRAINT = "constraint"
    CLAIM = "claim"
    GENERALIZED_FORCE = "generalized force"
    NEWTON_EULER = "newton-euler"
    LINEARISED_EQUATIONS = "linearised equations"
    FREQUENCY = "frequency"
    CRITICAL_SPEED = "critical speed"
    STABILITY = "stability"
    STEADY_MOTION = "steady motion"
    ORIENTATION = "orientation"
    GRAVITY = "gravity"


#: Steps (their values, in order).
STEPS: tuple[str, ...] = tuple(s.value for s in Step)


class DiagnosisKind(StrEnum):
    r"""What a diagnosis says, as data: the causes and the reports read this, never the text.

    Whole-element findings (``term`` empty) or one additive term's (``term`` set):
    ``SIGN``, ``FACTOR`` (``factor``), ``POWER``/``SWAP`` (``written`` where ``fits`` fits),
    ``MISSING``/``EXTRA`` (the document has 0 / the truth is 0; with ``terms``: the terms
    named one by one), ``POINT_MASS`` (a body's own inertia about its centre is missing),
    ``PARALLEL_AXIS`` (its mass times its centre's squared distance from the joint's axis is:
    the inertia about the centre written for the one about the axis; ``fits`` ``Pyy(link)``),
    ``DIMENSION``; ``SMALL_ANGLE`` (``written`` where ``fits`` fits, e.g. ``phi`` where
    ``sin(phi)`` fits, in ``position``); ``CONDITION`` (agrees only if ``condition``), ``FACTORIZATION`` (C differs,
    C q̇ agrees), ``UNDECIDED`` (values not finite), ``RESIDUAL`` (truth − document, as
    text), ``COINCIDENCE`` (numerically equal only because an inconsistent term vanishes
    here), ``NOT_EQUIVALENT`` (an equation that is no combination of the true ones),
    ``SINGULAR`` (equations lost, repeated, or scaled by a factor that vanishes somewhere:
    :math:`W` singular), ``NOTE`` (words only), ``DECLARED`` (an equation right as printed but
    not as the file declares it: its declared row scale contradicted; the declaration binds),
    ``COMMON_DIVISOR`` (every solved equation's elements the truth's times one function: the
    determinant it solved with is wrong)."""

    SIGN = "sign"
    FACTOR = "factor"
    POWER = "power"
    SWAP = "swap"
    SMALL_ANGLE = "small_angle"
    MISSING = "missing"
    EXTRA = "extra"
    POINT_MASS = "point_mass"
    PARALLEL_AXIS = "parallel_axis"
    DIMENSION = "dimension"
    CONDITION = "condition"
    FACTORIZATION = "factorization"
    UNDECIDED = "undecided"
    RESIDUAL = "residual"
    COINCIDENCE = "coincidence"
    NOT_EQUIVALENT = "not_equivalent"
    SINGULAR = "singular"
    NOTE = "note"
    DECLARED = "declared"
    COMMON_DIVISOR = "common_divisor"


#: Diagnoses that name one term's error precisely (an element carrying one is left to its
#: single-term cause rather than to a method cause).
SPECIFIC_KINDS = frozenset({DiagnosisKind.SIGN, DiagnosisKind.FACTOR, DiagnosisKind.SWAP,
                            DiagnosisKind.SMALL_ANGLE,
                            DiagnosisKind.POWER, DiagnosisKind.DIMENSION})
