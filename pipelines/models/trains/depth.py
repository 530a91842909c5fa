r"""How far a planet's pin may move before the planet leaves a mesh: the range of pin errors a train can carry load with.

A pin error :math:`(\Delta r_c, \Delta E_t)` (radial outwards, tangential) puts planet i's axis at the distance
:math:`d = |(E + \Delta r_c, \Delta E_t)|` from the sun's and the ring's (held) axis. Both meshes of the planet
change depth with d (transverse quantities, base radii :math:`r_{b}`, tip radii :math:`r_a`, base pitch
:math:`p_b = 2\pi r_{b1}/N_1`, :math:`s_k = \sqrt{r_{a,k}^2 - r_{b,k}^2}` the length from the base circle's
tangency to the tip circle along the line of action):

.. math::
    \varepsilon_{12}(d) = \frac{s_1 + s_2 - \sqrt{d^2 - (r_{b1} + r_{b2})^2}}{p_b},\qquad
    \varepsilon_{23}(d) = \frac{s_2 - s_3 + \sqrt{d^2 - (r_{b3} - r_{b2})^2}}{p_b}                    \qquad (D1)

the transverse contact ratios of the sun mesh (external) and of the ring mesh (internal,
:math:`\cos\alpha_w = (r_{b3} - r_{b2})/d`). Moving the planet out (d grows) takes it out of the sun's depth;
moving it in, out of the ring's. At :math:`\varepsilon = 0` the tip circles no longer cross the line of action:
no pair of teeth of that mesh can touch at any position, and a planet that touches one side only carries no
load on either (the planet turns freely about its pin). The distances at which that happens,

.. math::
    d_\text{max} = \sqrt{(r_{b1} + r_{b2})^2 + (s_1 + s_2)^2},\qquad
    d_\text{min} = \sqrt{(r_{b3} - r_{b2})^2 + (s_3 - s_2)^2}                                       \qquad (D2)

bound the pin errors a loaded train can be given: an error with :math:`d \notin (d_\text{min}, d_\text{max})`
separates the planet from both meshes. Long before that a tip meets a root: the tip-root clearances of both
meshes (the rule of :class:`tca.isostatic.train.IsostaticTrain`)

.. math::
    d - r_{a1} - r_{f2} > 0,\quad d - r_{a2} - r_{f1} > 0,\quad r_{f3} - d - r_{a2} > 0,\quad
    r_{a3} - d - r_{f2} > 0                                                                           \qquad (D3)

(:math:`r_f` root radii; the ring's root and tip radii are its larger and smaller circles) keep d within about
:math:`\pm c^* m` of E (:math:`c^* = h_{a0} - h_a`, the tool's clearance). The range of the pin errors is the
intersection of (D2) and (D3) (bad input outside it, :func:`check_pin_errors`). Inside the range a planet that carries
no load at some positions (a tangential error that opens its path more than the load closes it) is a result.
The loaded TCA enters pin errors to first order (:mod:`pipelines.models.trains.geometry`): the range is that of
the geometry, not a claim that the first-order model is accurate up to its ends.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

from tca.errors import InputError

__all__ = ["DepthRange", "depth_range", "check_pin_errors"]


@dataclass(frozen=True)
class DepthRange:
    """The planet axis distances [mm] at which the planet leaves the ring mesh (d_min) and the sun mesh (d_max),
    Eq. (D2), and the nominal E."""

    d_min: float
    d_max: float
    center_distance: float
    lo_why: str = "ring mesh"  # what bounds d from below: the ring mesh's depth (D2) or a tip-root clearance (D3)
    hi_why: str = "sun mesh"

    def radial_range(self) -> tuple[float, float]:
        """The radial pin errors [mm] (no tangential error) the planet keeps both meshes with."""
        return self.d_min - self.center_distance, self.d_max - self.center_distance


def depth_range(sun, planet, ring) -> DepthRange:
    """Eqs. (D2), (D3) from the gears' transverse base, tip and root radii."""
    s = [math.sqrt(max(g.r_tip ** 2 - g.r_b ** 2, 0.0)) for g in (sun, planet, ring)]
    lo = [(math.hypot(ring.r_b - planet.r_b, max(s[2] - s[1], 0.0)), "ring mesh (contact ratio 0, Eq. D2)"),
          (sun.r_tip + planet.r_root, "sun tip / planet root clearance (Eq. D3)"),
          (planet.r_tip + sun.r_root, "planet tip / sun root clearance (Eq. D3)")]
    hi = [(math.hypot(sun.r_b + planet.r_b, s[0] + s[1]), "sun mesh (contact ratio 0, Eq. D2)"),
          (ring.r_root - planet.r_tip, "planet tip / ring root clearance (Eq. D3)"),
          (ring.r_tip - planet.r_root, "ring tip / planet root clearance (Eq. D3)")]
    (d_min, lw), (d_max, hw) = max(lo), min(hi)
    return DepthRange(d_min, d_max, sun.r_p + planet.r_p, lw, hw)


def check_pin_errors(rng: DepthRange, pins, key) -> None:
    """InputError when a planet's pin error (radial, tangential) [mm] puts its axis outside (d_min, d_max) (module
    docstring). ``key(i)``: the case key of planet i's radial error (0-based)."""
    lo, hi = rng.radial_range()
    for i, (dr, dt) in enumerate(pins):
        d = math.hypot(rng.center_distance + dr, dt)
        if not rng.d_min < d < rng.d_max:
            why = rng.hi_why if d >= rng.d_max else rng.lo_why
            raise InputError(key(i), round(dr * 1e3, 6), f"a radial pin error in ({lo * 1e3:.1f}, {hi * 1e3:.1f}) um",
                             f"planet {i + 1}'s axis at {d:.4f} mm from the sun's is beyond the {why}, docs/trains.md")
