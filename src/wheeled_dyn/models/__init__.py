r"""Models: URDF loading, wheeled models on a ground-plane base, physical parameters."""

from .builder import ModelSpec, Wheel, WheeledModel, build_wheeled_model, coordinate_vector
from .urdf_source import UrdfSource, read_urdf

__all__ = ["ModelSpec", "Wheel", "WheeledModel", "build_wheeled_model", "coordinate_vector",
           "UrdfSource", "read_urdf"]
