r"""Instantaneous contact ellipse from the curvatures of the two surfaces at the contact point.

With :math:`n` the unit normal out of body 1 and :math:`s` coordinates in the common tangent
plane, each surface is locally :math:`h_i(s) = \tfrac12 s^T K_i s` along :math:`n`, where
:math:`K_i = A^{-T}\,\mathrm{II}_i\,A^{-1}` (second fundamental form w.r.t. :math:`n`,
:math:`A = Q^T[r_u\ r_v]` the map from parameters to tangent-plane coordinates). The separation
of the surfaces is :math:`\tfrac12 s^T (K_2 - K_1) s`; the contact ellipse is where it equals the
elastic approach :math:`\delta` (0.0065 mm in the report's TCA), so its semi-axes are
:math:`\sqrt{2\delta/\lambda_i}` with :math:`\lambda_i` the eigenvalues of :math:`K_2-K_1`
(Litvin's :math:`\sqrt{\delta/A}`, :math:`\sqrt{\delta/B}` with :math:`A,B=\lambda/2`).
A non-positive eigenvalue means line contact (conjugate surfaces): that axis is infinite.
"""

from __future__ import annotations

import numpy as np

from tca.geometry.surfaces import SurfacePoints

__all__ = ["curvature_matrix", "contact_ellipse", "LINE_CONTACT_CURVATURE"]


def curvature_matrix(sp: SurfacePoints, n: np.ndarray, Q: np.ndarray) -> np.ndarray:
    """Second fundamental form w.r.t. normal n in the tangent basis Q (..., 3, 2) [1/mm]."""
    P = np.stack([sp.r_u, sp.r_v], -1)  # (..., 3, 2)
    A = np.einsum("...ki,...kj->...ij", Q, P)
    II = np.stack(
        [
            np.stack([np.einsum("...i,...i", sp.r_uu, n), np.einsum("...i,...i", sp.r_uv, n)], -1),
            np.stack([np.einsum("...i,...i", sp.r_uv, n), np.einsum("...i,...i", sp.r_vv, n)], -1),
        ],
        -2,
    )
    Ai = np.linalg.inv(A)
    return np.einsum("...ki,...kl,...lj->...ij", Ai, II, Ai)


LINE_CONTACT_CURVATURE = 1e-9  # [1/mm] relative curvature below which the surfaces are conjugate


def contact_ellipse(sp1: SurfacePoints, sp2: SurfacePoints, delta: float, axis_hint: np.ndarray):
    """Semi-axes a >= b [mm] and angle [rad] of the major axis from `axis_hint` projected.

    All inputs in the same (fixed) frame, shapes (..., 3); `axis_hint` (..., 3) is typically
    the axis of gear 1, so the angle is measured from the longitudinal direction of the tooth.
    """
    n = sp1.n
    e1 = axis_hint - np.einsum("...i,...i", axis_hint, n)[..., None] * n
    e1 /= np.linalg.norm(e1, axis=-1, keepdims=True)
    e2 = np.cross(n, e1)
    Q = np.stack([e1, e2], -1)
    K = curvature_matrix(sp2, n, Q) - curvature_matrix(sp1, n, Q)
    K = 0.5 * (K + np.swapaxes(K, -1, -2))
    lam, vec = np.linalg.eigh(K)  # ascending: lam[...,0] belongs to the major axis
    with np.errstate(divide="ignore", invalid="ignore"):
        a = np.where(lam[..., 0] > LINE_CONTACT_CURVATURE, np.sqrt(2 * delta / lam[..., 0]), np.inf)
        b = np.where(lam[..., 1] > LINE_CONTACT_CURVATURE, np.sqrt(2 * delta / lam[..., 1]), np.inf)
    v = vec[..., :, 0]
    ang = np.arctan2(v[..., 1], v[..., 0])
    ang = (ang + np.pi / 2) % np.pi - np.pi / 2  # an axis, not a direction
    return a, b, ang, lam
