r"""The comparison engine: the stages wired (:mod:`.core`), the element pipeline
(:mod:`.judgement`), the convention search as an explanation (:mod:`.conventions`)."""

from .core import STAGES, ComparisonEngine, StageCallback

__all__ = ["ComparisonEngine", "STAGES", "StageCallback"]
