r"""Benchmark bodies with closed-form results: the textbook problems of seed 000 and the
rolling ball of seed 002.

Each is a URDF under ``urdf/`` (frames and numbers stated in its header comment) on a
``fixed`` or ``free`` base (:mod:`.builder`). Their joints are named as the documents name
their coordinates, so a model's coordinates read as the document's. Named constants that
coordinate maps need (a rolling radius, a gear ratio, ball and fixed-sphere radii) are the
model's ``geometry``.

=================== ================ ==========================================================
model               document         body
=================== ================ ==========================================================
compound_pendulum   seed 000, 2.6    a bar on a pivot (I_g, a)
rod_pendulum        seed 000, 4.4    uniform slender rod hinged at one end
rolling_disk        seed 000, 4.8    disk with a point mass, rolling (x = R theta imposed by
                                     the coordinate map)
pendulum_support    seed 000, 4.9    pendulum whose support moves vertically
bounce_pitch        seed 000, 4.12   car body in bounce y and pitch theta (no springs)
differential        seed 000, 4.13   two wheels and the pinion (gear coupling imposed by the
                                     coordinate map)
flywheel_rod        seed 000, 4.17   rod hinged on a driven flywheel
free_body           seed 000, 7.1/2  a block, free in space (free base)
gyroscope           seed 000, 7.7    rotor on an axle pivoted at one end
sphere_plane        seed 002         uniform ball rolling on the ground
sphere_sphere       seed 002         uniform ball rolling on a fixed sphere
rolling_coin        textbook         uniform thin disk rolling and leaning on the ground
bicycle             Meijaard 2007    Whipple bicycle at the benchmark parameters (Table 1)
=================== ================ ==========================================================
"""

from __future__ import annotations

import math
from collections.abc import Callable

from ..paths import urdf_dir
from .builder import ModelSpec
from .contact import SphereContact
from .rolling_wheel import WheelContact

#: Radius of the fixed sphere the ball of ``sphere_sphere`` rolls on (m).
FIXED_SPHERE_RADIUS = 0.30
#: Radius of the ball of ``ball.urdf`` (m).
BALL_RADIUS = 0.109
#: Radius of the thin disk of ``rolling_coin.urdf`` (m).
COIN_RADIUS = 0.30


def _fixed(name: str, urdf: str, description: str, **kw) -> Callable[[], ModelSpec]:
    def spec() -> ModelSpec:
        return ModelSpec(name=name, urdf=urdf_dir() / urdf, base="fixed",
                         description=description, **kw)
    return spec


def _ball(name: str, contact: SphereContact, description: str) -> Callable[[], ModelSpec]:
    def spec() -> ModelSpec:
        return ModelSpec(name=name, urdf=urdf_dir() / "ball.urdf", base="free", body="ball",
                         contact=contact, description=description)
    return spec


#: (name, one-line summary, spec function) of every benchmark body, in the table's order.
BENCHMARKS: tuple[tuple[str, str, Callable[[], ModelSpec]], ...] = (
    ("compound_pendulum", "compound pendulum, a bar on a pivot (seed 000, 2.6)",
     _fixed("compound_pendulum", "compound_pendulum.urdf",
            "bar swinging about a pivot 0.3 m above its centre of mass", body="body")),
    ("rod_pendulum", "uniform rod hinged at one end, omega_n = sqrt(3g/2l) (seed 000, 4.4)",
     _fixed("rod_pendulum", "rod_pendulum.urdf", "uniform slender rod, 1 m, hinged at its end",
            body="rod")),
    ("rolling_disk", "disk with an offset point mass rolling on the ground (seed 000, 4.8)",
     _fixed("rolling_disk", "rolling_disk.urdf", "disk of radius R on a carriage x; rolling "
            "x = R theta is a holonomic map of the coordinate set", body="disk",
            geometry={"R": 0.30})),
    ("pendulum_support", "pendulum on a vertically moving support (seed 000, 4.9)",
     _fixed("pendulum_support", "pendulum_support.urdf", "bob on a massless rod from a "
            "support of height x", body="bob", actuated=("x",), inputs=("F_x",))),
    ("bounce_pitch", "car body in bounce and pitch, springs not modelled (seed 000, 4.12)",
     _fixed("bounce_pitch", "bounce_pitch.urdf", "rigid car body, vertical displacement y of "
            "a reference point and pitch theta", body="body")),
    ("differential", "car differential: two wheels and the pinion (seed 000, 4.13)",
     _fixed("differential", "differential.urdf", "two wheel shafts and the pinion on vertical "
            "axes; pinion = G (theta1 + theta2)/2 is a holonomic map of the coordinate set",
            actuated=("theta1", "theta2", "pinion"), inputs=("tau_1", "tau_2", "tau_3"),
            geometry={"G": 3.5, "R": 0.32})),
    ("flywheel_rod", "rod hinged on a driven flywheel, omega_crit = sqrt(3g/2L) (seed 000, 4.17)",
     _fixed("flywheel_rod", "flywheel_rod.urdf", "slender rod hanging from a hinge on the axis "
            "of a motor-driven horizontal flywheel", body="rod", actuated=("phi",))),
    ("free_body", "free rigid block, Euler's equations and spin stability (seed 000, 7.1/7.2)",
     lambda: ModelSpec(name="free_body", urdf=urdf_dir() / "free_body.urdf", base="free",
                       body="block", description="block 0.15 x 0.03 x 0.23 m free in space "
                       "(ZYX angles, singular at pitch = +-pi/2)")),
    ("gyroscope", "gyroscope pivoted at one end of its axle, precession (seed 000, 7.7)",
     _fixed("gyroscope", "gyroscope.urdf", "rotor on an axle pivoted at O: precession psi, "
            "tilt theta, spin phi", body="rotor")),
    ("sphere_plane", "uniform ball rolling without slipping on the ground (seed 002)",
     _ball("sphere_plane", SphereContact("ball", BALL_RADIUS, "plane"),
           "uniform ball rolling on the plane z = 0")),
    ("sphere_sphere", "uniform ball rolling on a fixed sphere (seed 002)",
     _ball("sphere_sphere", SphereContact("ball", BALL_RADIUS, "sphere", FIXED_SPHERE_RADIUS),
           f"uniform ball rolling on the outside of a fixed sphere of radius "
           f"{FIXED_SPHERE_RADIUS} m centred at the origin")),
    ("rolling_coin", "uniform thin disk (coin) rolling and leaning on the ground",
     _fixed("rolling_coin", "rolling_coin.urdf", "thin disk m = 2 kg, R = 0.3 m: centre x, y, "
            "z, heading psi, lean phi, spin theta; z follows from the lean (contact)",
            body="coin", geometry={"R": COIN_RADIUS},
            rolling_wheels=(WheelContact("coin", COIN_RADIUS, axis=(0.0, 1.0, 0.0)),))),
    ("bicycle", "Whipple bicycle, benchmark parameters of Meijaard et al. 2007 (roll, steer)",
     _fixed("bicycle", "bicycle.urdf", "rear frame with rider, fork and handlebar, two "
            "knife-edge wheels (Meijaard, Papadopoulos, Ruina, Schwab 2007, Table 1); rear hub "
            "x, y, z, yaw, roll, pitch, rear_wheel, steer, front_wheel; z and pitch follow "
            "from the contacts", body="rear_frame", actuated=("roll", "steer"),
            inputs=("T_phi", "T_delta"),
            geometry={"rR": 0.3, "rF": 0.35, "w": 1.02, "c": 0.08, "lambda": math.pi / 10},
            rolling_wheels=(WheelContact("rear_wheel", 0.3), WheelContact("front_wheel", 0.35)))),
)
