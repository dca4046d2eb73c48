r"""Models: URDF loading, wheeled models on a ground-plane base, physical parameters."""

from .._lazy import attach

__getattr__, __dir__, __all__ = attach(__name__, {
    "ModelSpec": ".wheeled_model",
    "Wheel": ".wheeled_model",
    "WheeledModel": ".wheeled_model",
    "build_wheeled_model": ".builder",
    "coordinate_vector": ".wheeled_model",
    "UrdfSource": ".urdf_source",
    "read_urdf": ".urdf_source",
})
