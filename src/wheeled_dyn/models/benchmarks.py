r"""Benchmark bodies with closed-form results: the textbook problems of seed 000 and the
rolling ball of seed 002.

Each is a URDF under ``urdf/`` (frames and numbers stated in its header comment) on a
``fixed`` or ``free`` base (:mod:`.builder`), described by a model file
``data/models/<name>.toml`` (:mod:`.model_file`). Their joints are named as the documents name
their coordinates, so a model's coordinates read as the document's. Named constants that
coordinate maps need (a rolling radius, a gear ratio, ball and fixed-sphere radii) are the
model's ``geometry``.

==================== ================ ==========================================================
model                document         body
==================== ================ ==========================================================
car4                 seed 000, 1.11/  car body on four wheels rolling without side slip, both
                     1.12             front wheels steered (steer_fl, steer_fr)
particle_table       seed 000, 1.15   ball (a particle) on a smooth table, polar r, theta about
                                      the hole its string runs through
spring_table         seed 000, 4.6    the same particle tied to the origin by a linear spring
                                      along r (k, free length l0)
compound_pendulum    seed 000, 2.6    a bar on a pivot (I_g, a)
spring_block         seed 000, 2.19   block on a pin riding a horizontal slider, a horizontal
                                      spring K and a torsional spring K_T at the pin
rod_pendulum         seed 000, 4.4    uniform slender rod hinged at one end
rolling_disk         seed 000, 4.8    disk with a point mass, rolling (x = R theta imposed by
                                      the coordinate map)
pendulum_support     seed 000, 4.9    pendulum whose support moves vertically
bounce_pitch         seed 000, 4.12   car body in bounce y and pitch theta (no springs)
differential         seed 000, 4.13   two wheels and the pinion (gear coupling imposed by the
                                      coordinate map)
flywheel_rod         seed 000, 4.17   rod hinged on a driven flywheel
free_body            seed 000, 7.1/2  a block, free in space (free base)
gyroscope            seed 000, 7.7    rotor on an axle pivoted at one end
sphere_plane         seed 002         uniform ball rolling on the ground
sphere_sphere        seed 002         uniform ball rolling on a fixed sphere
sphere_paraboloid    seed 002         uniform ball rolling inside a fixed paraboloid bowl
offset_sphere_plane  seed 002         body of revolution bounded by a sphere, centre of mass on
                                      its axis off the centre, rolling on the ground
offset_sphere_sphere seed 002         the same body rolling on a fixed sphere
spheroid_plane       textbook         uniform oblate spheroid (ellipsoid of revolution) rolling
                                      on the ground; rocking on its flat side
rolling_coin         textbook         uniform thin disk rolling and leaning on the ground
bicycle              Meijaard 2007    Whipple bicycle at the benchmark parameters (Table 1)
==================== ================ ==========================================================
"""

from __future__ import annotations

from collections.abc import Callable
from typing import TYPE_CHECKING

from .listing import shipped_model_files

if TYPE_CHECKING:       # the listing reads this module without Pinocchio
    from .wheeled_model import ModelSpec

#: Radius of the fixed sphere the ball of ``sphere_sphere`` rolls on (m) (``sphere_sphere.toml``).
FIXED_SPHERE_RADIUS = 0.30
#: Radius of curvature at the vertex of the paraboloid bowl of ``sphere_paraboloid`` (m)
#: (``sphere_paraboloid.toml``).
PARABOLOID_VERTEX_RADIUS = 0.50
#: Radius of the ball of ``ball.urdf`` (m) (``sphere_plane.toml``, ``sphere_sphere.toml``).
BALL_RADIUS = 0.109
#: Equatorial and polar radii (m) of the uniform spheroid of ``spheroid.urdf``
#: (``spheroid_plane.toml``).
SPHEROID_RADII = (0.10, 0.06)
#: Radius of the thin disk of ``rolling_coin.urdf`` (m) (``rolling_coin.toml``).
COIN_RADIUS = 0.30

#: The benchmark bodies described by model files, in the table's order.
BENCHMARK_NAMES: tuple[str, ...] = (
    "car4", "particle_table", "spring_table", "compound_pendulum", "spring_block", "rod_pendulum", "rolling_disk", "pendulum_support",
    "bounce_pitch", "differential", "flywheel_rod", "free_body", "gyroscope", "sphere_plane",
    "sphere_sphere", "sphere_paraboloid", "offset_sphere_plane", "offset_sphere_sphere",
    "spheroid_plane", "rolling_coin", "bicycle")

#: Benchmark bodies written in Python instead of a model file: (name, one-line summary, spec
#: function). A model defined here is registered like a file's.
PYTHON_BENCHMARKS: tuple[tuple[str, str, Callable[[], "ModelSpec"]], ...] = ()


def _from_files() -> tuple[tuple[str, str, Callable[[], "ModelSpec"]], ...]:
    files = shipped_model_files()
    return tuple((name, files[name].summary, files[name].spec) for name in BENCHMARK_NAMES)


#: (name, one-line summary, spec function) of every benchmark body, in the table's order.
BENCHMARKS: tuple[tuple[str, str, Callable[[], "ModelSpec"]], ...] = (*_from_files(),
                                                                     *PYTHON_BENCHMARKS)
