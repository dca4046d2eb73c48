r"""Rolling constraints and the equations of motion in a document's coordinates."""

from .reduction import CoordinateMap, multipliers
from .rolling import contact_jacobian, contact_points, contact_velocities

__all__ = ["CoordinateMap", "multipliers", "contact_jacobian", "contact_points",
           "contact_velocities"]
