"""Hertz-equivalent contact patch of nodal contact forces.

Of nodal forces F_a at x_a: the resultant P, the centre c = sum F x / P, and the tangential
second moments mu = sum F (t.(x - c))^2 / P along the principal directions t. A semi-ellipsoidal
pressure has int x^2 p dA / P = a^2 / 5, an elliptic line pressure a^2 / 4 across (uniform along:
L^2 / 12 = l^2 / 3 with l the half-length), so a = sqrt(5 mu) (point), b = sqrt(4 mu) (line).
Integral quantities of the forces, they do not jump by an element when the edge of the contact
passes a node.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from fem.errors import FEInputError

__all__ = ["ContactPatch", "PATCH_FACTORS", "contact_patch"]


@dataclass(frozen=True)
class ContactPatch:
    """Hertz-equivalent contact patch of nodal forces (module docstring): force [N], centre [mm],
    semi-axes a >= b [mm] and their unit directions."""

    force: float
    centre: tuple[float, float, float]
    semi_axes: tuple[float, float]
    directions: tuple[tuple[float, float, float], tuple[float, float, float]]


PATCH_FACTORS = {"point": (5.0, 5.0), "line": (3.0, 4.0)}


def contact_patch(points: np.ndarray, forces: np.ndarray, normal, centre=None, kind: str = "point", major=None) -> ContactPatch:
    """Semi-axes of the Hertz pressure with the same resultant and second moments as the nodal forces.

    points (n, 3) [mm], forces (n,) >= 0 [N], normal (3,) the common normal; ``centre`` [mm]
    (default the force centroid; give the symmetry point of a half or quarter model); ``kind``
    'point' (semi-ellipsoid: a^2 = 5 mu) or 'line' (semi-ellipse across, uniform along: b^2 = 4 mu,
    half-length^2 = 3 mu), mu the second moments about the centre along the axes. The axes are the
    eigenvectors of the tangential second-moment tensor, or ``major`` (3,) and n x major when given.
    """
    if kind not in PATCH_FACTORS:
        raise FEInputError("kind", kind, "'point' or 'line'")
    F = np.clip(np.asarray(forces, float), 0.0, None)
    P = float(F.sum())
    if P <= 0.0:
        nan = float("nan")
        return ContactPatch(0.0, (nan, nan, nan), (0.0, 0.0), ((nan,) * 3, (nan,) * 3))
    x = np.asarray(points, float)
    c = (F @ x) / P if centre is None else np.asarray(centre, float)
    n = np.asarray(normal, float) / np.linalg.norm(normal)
    d = x - c
    d -= np.outer(d @ n, n)  # tangential offsets
    S = np.einsum("p,pi,pj->ij", F, d, d) / P
    if major is None:
        mu, vec = np.linalg.eigh(S)  # ascending; the smallest is along the normal
        e1, e2 = vec[:, 2], vec[:, 1]
    else:
        e1 = np.asarray(major, float) - (np.asarray(major, float) @ n) * n
        e1 /= np.linalg.norm(e1)
        e2 = np.cross(n, e1)
    fa, fb = PATCH_FACTORS[kind]
    a, b = np.sqrt(fa * max(float(e1 @ S @ e1), 0.0)), np.sqrt(fb * max(float(e2 @ S @ e2), 0.0))
    return ContactPatch(P, tuple(float(v) for v in c), (float(a), float(b)),
                        (tuple(float(v) for v in e1), tuple(float(v) for v in e2)))
