r"""Refined zones of the loaded pairs of teeth of a mesh, from the loaded estimate (:mod:`pipelines.models.stress.loaded`).

A zone is centred on a point of both flanks (the TCA contact point of the pair in contact; for another
pair the point of :func:`pipelines.models.stress.scene.neighbour_params`) and must cover the pair's loaded
slices. Each slice point x is put on each gear's flank (:func:`tca.contact.systems.foot_points`, the
gear at the angle where the slices lie), giving its flank parameters (u, z); relative to the centre
(u_c, z_c) its profile distance is :math:`\Delta s = (u-u_c)\,\tfrac12(|r_u(u_c)| + |r_u(u)|)` and its
axial distance :math:`\Delta z = z - z_c`. The loaded line's direction is the principal axis of the points
(Δs, Δz) on the driver's flank (one slice: the TCA contact ellipse's major axis), at the angle θ from the
axis (s = |sin θ|, c = |cos θ|); with each slice's Hertz half-width :math:`b_i = p_i/\kappa_i` across the
line and the slice length ℓ (half a slice along it),

.. math:: e_u = f\,\max_i(|\Delta s_i| + b_i c + s\,\ell/2),\qquad e_z = f\,\max_i(|\Delta z_i| + b_i s + c\,\ell/2),

f = ``[mesh] zone`` (1.2): the zone's half-lengths along the profile and the axis (:class:`mesher.Focus`).
The line's half-length a (half the span of the points along it, plus ℓ/2) and s give the axial size
min(a/6, b/(3 s)), a/4 instead of a/6 on a line contact whose line load is uniform: the smallest over the largest
slice line load :math:`w_{min}/w_{max} = (b_{min}/b_{max})^2` (w ∝ b² at one curvature) at least 0.9
(:func:`pipelines.models.stress.sizing.zone_sizes`, (G7)).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from tca.contact.systems import PlacedFlank, foot_points
from tca.pair.gear_pair import GearPair

from pipelines.models.stress.loaded import PairLoad

__all__ = ["Zone", "pair_zone", "ZONE_SHARE"]

ZONE_SHARE = 0.1  # a loaded pair carrying less of its mesh's force gets the neighbour mesh, no zone (issue 26)


@dataclass(frozen=True)
class Zone:
    """A loaded pair's refined zone on both gears: centres (u1, z1, u2, z2) [mm], half-lengths per gear
    ((e_u1, e_z1), (e_u2, e_z2)) [mm], Hertz half-width b, line half-length a [mm], sine s of the line from
    the axis, the pair's teeth and share of its mesh's force, and the uniformity of its line load w_min/w_max over
    the loaded slices (module docstring)."""

    teeth: tuple
    centre: tuple
    extents: tuple
    b: float
    a: float
    s: float
    share: float
    uniform: float = 1.0


def _flank_offsets(f: PlacedFlank, uv: tuple, phi: float, x: np.ndarray) -> np.ndarray | None:
    """(Δs, Δz) [mm] of points x (n, 3) on flank f at angle phi from its point (u, z) = uv (module docstring)."""
    w, ok, got = foot_points(f, uv, phi, x)
    if not ok.any():
        return None
    got = got[ok]
    loc0 = f.surface.evaluate(np.array([uv[0]]), np.array([uv[1]]))
    loc = f.surface.evaluate(got[:, 0], got[:, 1])
    speed = 0.5 * (np.linalg.norm(loc0.r_u, axis=1) + np.linalg.norm(loc.r_u, axis=1))
    return np.stack([(got[:, 0] - uv[0]) * speed, got[:, 1] - uv[1]], 1)


def pair_zone(pair: GearPair, load: PairLoad, centre: tuple, zone: float, angle: float) -> Zone:
    """The zone of one loaded pair centred at ``centre`` = (u1, v1, u2, v2) [mm] (module docstring); ``angle`` [rad]:
    the contact ellipse's major axis from the axis, used when a single slice gives no direction."""
    m1, m2 = pair.mounts()
    flanks = (PlacedFlank(pair.gear1, pair.side1, m1), PlacedFlank(pair.gear2, pair.side2, m2))
    half_len = 0.5 * float(np.max(load.lengths)) if len(load.lengths) else 0.0
    offsets = []
    for i, f in enumerate(flanks):
        d = _flank_offsets(f, (float(centre[2 * i]), float(centre[2 * i + 1])), load.phi[i], load.points)
        offsets.append(np.zeros((1, 2)) if d is None else d)  # (no slice on the flank: cannot happen for LTCA slices)
    first = offsets[0]
    if len(first) >= 2:  # the loaded line: principal axis of the points on gear 1's flank
        c = first - first.mean(0)
        direction = np.linalg.svd(c, full_matrices=False)[2][0]
        s = abs(float(direction[0]))
        a = 0.5 * float(np.ptp(c @ direction)) + half_len
    else:
        s, a = abs(math.sin(angle)), max(half_len, load.b)
    co = math.sqrt(max(1.0 - s * s, 0.0))
    # each slice's band: its half-width b_i across the line, half a slice along it
    w = load.widths if len(load.widths) else np.array([load.b])
    ext = tuple((zone * float(np.max(np.abs(d[:, 0]) + w * co + half_len * s)),
                 zone * float(np.max(np.abs(d[:, 1]) + w * s + half_len * co))) for d in offsets)
    uniform = float((np.min(w) / np.max(w)) ** 2) if np.max(w) > 0 else 1.0
    return Zone(load.teeth, tuple(float(x) for x in centre), ext, load.b, a, s, load.share, uniform)
