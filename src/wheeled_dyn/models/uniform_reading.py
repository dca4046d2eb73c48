r"""A link a document declares uniform, its inertia read as the uniform body's where the URDF
prints the body's value to as many digits as it prints.

URDFs print inertias rounded: a slender rod of 0.2 kg and 0.8 m written
``ixx="0.0106667"`` for :math:`mL^2/12 = 0.010666\overline{6}`. A document that declares the
rod uniform writes :math:`mL^2/12` (or :math:`\tfrac43 m l^2` about its end) exactly, and the
truth drawn in the URDF's proportions differed from it by the rounding, 3·10⁻⁶ of the
moment: beyond the comparison's tolerance of 10⁻⁷, "the document is 1.000001 × the truth".

So each principal moment of a link's ``<inertia>`` (the tensor diagonal, its products of
inertia printed zero, printed to three significant digits or more; its ``<origin rpy>`` none or
right angles, each moment then about the link axis the turn puts it on) is compared with the
moments of the uniform bodies its first cylinder or sphere gives (radius :math:`r`, length
:math:`L`, mass :math:`m` as printed):

.. math::

    \tfrac12 mr^2,\quad \tfrac1{12}m(3r^2 + L^2),\quad \tfrac1{12}mL^2\ \text{(slender)},
    \quad \tfrac25 mr^2\ \text{(ball)},

and where exactly one lies within a unit of the last digit printed (the value rounded there,
or cut: ``"0.024645"`` for 0.0246458), and the printed value is not already it, the link's
moment is read as that body's (:func:`uniform_inertials`; where two do, it is not read —
but for a slender rod's and a thin cylinder's, where it is read as the cylinder's when the
URDF prints the cylinder's axial moment :math:`mr^2/2` too — the body it means has a radius —
and as the rod's when it prints that moment 0). The reading is made only for the links a
document declares uniform (``[assumes] uniform``, the families ``uniform(link)`` and
``urdf_proportions``): their inertia is the uniform body's by declaration, and the URDF agrees
with it to its printed digits. The report says so (a note).
"""

from __future__ import annotations

import xml.etree.ElementTree as ET
from collections.abc import Mapping
from decimal import Decimal, InvalidOperation

import numpy as np

#: The diagonal entries of an ``<inertia>`` element and their off-diagonal ones.
DIAGONAL, PRODUCTS = ("ixx", "iyy", "izz"), ("ixy", "ixz", "iyz")


#: Largest unit of the last printed digit, relative to the value, of a moment read as a
#: uniform body's (three significant digits and more: "1e-05" tells nothing).
DIGITS = 1e-2


def half_unit(text: str) -> float | None:
    r"""Half a unit of the last digit ``text`` prints (``"0.0106667"`` → 5e-8, ``"1e-5"`` →
    5e-6); None where it is no decimal number."""
    try:
        exponent = Decimal(text.strip()).as_tuple().exponent
    except InvalidOperation:
        return None
    return 0.5 * 10.0 ** exponent if isinstance(exponent, int) else None


#: The moments of a cylinder about a diameter through its centre, and of a slender rod.
CYLINDER, ROD = "m (3 r² + L²)/12", "m L²/12"


def _candidates(mass: float, radius: float | None, length: float | None
                ) -> list[tuple[float, str]]:
    out: list[tuple[float, str]] = []
    if radius is not None:
        out += [(mass * radius ** 2 / 2, "m r²/2"), (2 * mass * radius ** 2 / 5, "2 m r²/5")]
    if radius is not None and length is not None:
        out.append((mass * (3 * radius ** 2 + length ** 2) / 12, CYLINDER))
    if length is not None:
        out.append((mass * length ** 2 / 12, ROD))
    return out


def uniform_inertials(text: str, shapes: Mapping[str, tuple[float | None, float | None]],
                      inertials: Mapping[str, tuple[float, ...]]
                      ) -> dict[str, tuple[tuple[float, ...], str]]:
    r"""Per link whose printed moments a uniform body's match (module text): its dynamic
    parameters (:math:`m, mc, I_O`, as ``inertials`` holds them) with those moments the
    body's, and the reading in words. ``shapes``: link → (radius, length) of its first
    sphere or cylinder."""
    import pinocchio as pin
    out: dict[str, tuple[tuple[float, ...], str]] = {}
    for link in ET.fromstring(text).findall("link"):
        name = link.get("name", "")
        element = link.find("inertial/inertia")
        radius, length = shapes.get(name, (None, None))
        if name not in inertials or element is None or (radius is None and length is None):
            continue
        origin = link.find("inertial/origin")
        rpy = "0 0 0" if origin is None else origin.get("rpy", "0 0 0")
        try:
            axes = _link_axes([float(x) for x in rpy.split()])
            products = any(float(element.get(k, "0")) != 0.0 for k in PRODUCTS)
        except ValueError:                 # not numbers: the URDF's checks say so, not this
            continue
        if axes is None or products:
            continue                       # its principal axes are not the tensor's axes
        own = pin.Inertia.FromDynamicParameters(np.asarray(inertials[name]))
        moments, said = np.diag(own.inertia).copy(), []
        axial = None if radius is None else _axial(element, own.mass, radius)
        for printed_axis, key in enumerate(DIAGONAL):
            axis = axes[printed_axis]
            printed, half = element.get(key, "0"), half_unit(element.get(key, "0"))
            if half is None:
                continue
            value = float(printed)
            if not 2 * half <= DIGITS * abs(value):
                continue                   # too few digits to tell one body from another
            near = [(v, f) for v, f in _candidates(own.mass, radius, length)   # rounded or
                    if abs(v - value) <= 2 * half]                          # cut at its digits
            if {f for _, f in near} == {CYLINDER, ROD} and axial is not None:
                near = [x for x in near if x[1] == (CYLINDER if axial else ROD)]
            # one body's only, and not printed exactly; where a slender rod's m L²/12 and the
            # cylinder's are both the printed value to its digits (0.0807 for 0.8 kg, 1.1 m,
            # r = 0.02 m), the cylinder's where the URDF prints the cylinder's axial moment
            # m r²/2 too, the rod's where it prints none (izz="0"), else neither
            if len(near) == 1 and near[0][0] != value:
                moments[axis] = near[0][0]
                said.append(f"{key} {printed} as {near[0][1]} = {near[0][0]:.10g}")
        if said:
            read = pin.Inertia(own.mass, own.lever, np.diag(moments))
            out[name] = (tuple(float(x) for x in read.toDynamicParameters()),
                         f"link {name}, declared uniform: its URDF inertia read as the uniform "
                         f"body's, which it is to the digits the URDF prints ("
                         + "; ".join(said) + ")")
    return out


#: A printed moment within this fraction of a uniform body's is taken to be meant as one
#: (:func:`unlike_uniform`: a URDF computed from a shape other than the one it draws).
LIKE = 0.01


def _every_body(link: ET.Element, mass: float) -> list[tuple[float, str]] | None:
    r"""The moments of the uniform bodies of every geometry the link draws (collision and
    visual: each cylinder's and sphere's of module text, each box's
    :math:`m(b^2 + c^2)/12` about each axis), with their formulas; None where it draws a
    shape of no known moments (a mesh) or none at all."""
    out: list[tuple[float, str]] = []
    for geometry in [*link.findall("collision/geometry"), *link.findall("visual/geometry")]:
        for shape in geometry:
            try:
                if shape.tag == "cylinder":
                    out += _candidates(mass, float(shape.get("radius", "nan")),
                                       float(shape.get("length", "nan")))
                elif shape.tag == "sphere":
                    out += _candidates(mass, float(shape.get("radius", "nan")), None)
                elif shape.tag == "box":
                    a, b, c = (float(x) for x in shape.get("size", "").split())
                    out += [(mass * (u * u + v * v) / 12, "m (b² + c²)/12")
                            for u, v in ((b, c), (a, c), (a, b))]
                else:
                    return None            # a mesh: its moments are its own
            except ValueError:
                return None
    return out or None


def unlike_uniform(text: str, inertials: Mapping[str, tuple[float, ...]]) -> dict[str, str]:
    r"""Per link whose printed moments (tensor diagonal, products zero, axes turned by right
    angles at most) are none of them within :data:`LIKE` of the moments of a uniform body of
    any cylinder, sphere or box it draws (collision or visual; :func:`_every_body`): in
    words, what it prints and what a uniform body of its first shape would have. Such a link
    declared uniform is the file contradicting its URDF: the truth keeps the URDF's inertia
    (its proportions). A link drawing a mesh, or nothing, is never said so."""
    import pinocchio as pin
    out: dict[str, str] = {}
    for link in ET.fromstring(text).findall("link"):
        name = link.get("name", "")
        element = link.find("inertial/inertia")
        if name not in inertials or element is None:
            continue
        origin = link.find("inertial/origin")
        try:
            axes = _link_axes([float(x) for x in ("0 0 0" if origin is None else
                                                   origin.get("rpy", "0 0 0")).split()])
            printed = [float(element.get(k, "0")) for k in DIAGONAL]
            products = any(float(element.get(k, "0")) != 0.0 for k in PRODUCTS)
        except ValueError:
            continue
        mass = pin.Inertia.FromDynamicParameters(np.asarray(inertials[name])).mass
        bodies = _every_body(link, mass) if mass > 0 else None
        if axes is None or products or bodies is None or not any(v > 0 for v in printed) \
                or any(abs(v - b) <= LIKE * b for v in printed for b, _ in bodies):
            continue
        moments = ", ".join(f"{k} {v:g}" for k, v in zip(DIAGONAL, printed))
        out[name] = (f"link {name}'s URDF moments ({moments}) are no uniform body's of the "
                     f"shapes it draws, of mass {mass:g} kg ("
                     + ", ".join(f"{f} = {b:.4g}" for b, f in bodies[:6]) + ")")
    return out


def _axial(element: ET.Element, mass: float, radius: float) -> bool | None:
    r"""Whether ``element`` prints a cylinder's axial moment :math:`mr^2/2` (to its digits,
    not zero: True), or a slender rod's, zero (False); None where it prints neither."""
    values = []
    for key in DIAGONAL:
        text = element.get(key, "0")
        half = half_unit(text)
        try:
            values.append((float(text), half))
        except ValueError:
            continue
    if any(v != 0.0 and h is not None and abs(v - mass * radius ** 2 / 2) <= 2 * h
           for v, h in values):
        return True
    return False if any(v == 0.0 for v, _ in values) else None


def _link_axes(rpy: list[float]) -> tuple[int, ...] | None:
    r"""The link axis each axis of an ``<inertial>`` turned by ``rpy`` lies along, where the
    turn is right angles (to the rounding :func:`~.conventions.right_angles` reads:
    ``rpy="1.5708 0 0"``, a wheel's tensor written about its own axes, as ROS URDFs do); None
    for another turn."""
    import pinocchio as pin

    from .conventions import right_angles
    if len(rpy) != 3:
        return None
    snapped = right_angles(np.asarray(rpy, dtype=float))
    quarter = snapped / (np.pi / 2)
    if np.abs(quarter - np.rint(quarter)).max() > 1e-12:
        return None
    P = np.rint(np.asarray(pin.rpy.rpyToMatrix(*snapped)))
    return tuple(int(np.argmax(np.abs(P[:, a]))) for a in range(3))


__all__ = ["LIKE", "half_unit", "uniform_inertials", "unlike_uniform"]
