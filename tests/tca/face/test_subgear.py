"""Pinion / face-gear sub-drive TCA (Eqs. 2.5-2.12): conjugate check, pitch point, transitions, bad input."""

import math

import numpy as np
import pytest

from tca.errors import InputError
from tca.face.face_gear import FaceGear
from tca.face.subgear import ARCSEC, SURFACE, FaceMesh, run_face_mesh, trace_reference_pair
from tca.geometry.gear import Gear

d = math.radians


def _shaper():
    return Gear("shaper", 20, 5.0, d(20), 120.0, helix=d(10), hand=1, addendum=1.25, tool_addendum=1.3)


@pytest.fixture(scope="module")
def face60():
    return FaceGear("f60", 60, _shaper(), d(75))


def test_pinion_identical_to_the_shaper_is_conjugate(face60):
    # The face gear is the envelope of the shaper: meshing it with the shaper itself (line contact)
    # transmits the exact ratio. |TE| < 1e-5 arcsec: the only error is the Chebyshev representation
    # (~1e-10 mm at a radius of ~150 mm, 1e-7 arcsec) and the accepted Newton residual (1e-9 mm).
    pin = Gear("shaper_as_pinion", 20, 5.0, d(20), 40.0, helix=d(10), hand=1, tool_addendum=1.3)
    mesh = FaceMesh(face60, pin, "face")
    tr = trace_reference_pair(mesh, 24)
    assert (tr.phi[-1] - tr.phi[0]) > mesh.pitches[0]  # the trace covers more than a cycle
    te = tr.x[:, 4] - mesh.ratio * tr.phi
    assert np.abs(te).max() / ARCSEC < 1e-5
    assert np.all(tr.kind == SURFACE)


@pytest.fixture(scope="module")
def crowned():
    g = FaceGear("gear1", 100, _shaper(), d(75), crowning=0.002)
    p = Gear("pinion2", 17, 5.0, d(20), 52.0, helix=d(10), hand=1, parabola_pos=0.001, parabola_neg=0.001,
             tool_tip_radius=0.45)
    return run_face_mesh(FaceMesh(g, p, "pinion"), steps_per_cycle=60)


def test_parabolic_te_with_apex_at_the_pitch_point(crowned):
    # Table 2.1 crowning (0.001 pinion, 0.002 face gear): the pinion and the face gear touch at the
    # pitch point P with the ideal ratio (both profile parabolas have their apex at P and P lies on the
    # axode), so the TE of a pair is zero there and negative elsewhere: a parabola with apex 0.
    r = crowned
    te = r.te_ref / ARCSEC
    i0 = int(np.argmin(np.abs(r.phi - r.mesh.start_angle())))
    assert te[i0] == pytest.approx(0.0, abs=1e-6)
    assert te.max() < 1e-6
    # parabolic: over the contact interval a quadratic fits to 2 % of the amplitude
    sel = (r.phi >= r.phi_min) & (r.phi <= r.phi_max)
    c = np.polyfit(r.phi[sel], te[sel], 2)
    amp = te[sel].max() - te[sel].min()
    assert amp > 1.0
    assert np.abs(np.polyval(c, r.phi[sel]) - te[sel]).max() < 0.02 * amp
    assert c[0] < 0


def test_transitions_are_simultaneous_contact_of_neighbouring_pairs(crowned):
    # Eqs. (2.11)-(2.12): at phi_min the middle pair and the forward pair are both in contact, i.e. give
    # the same driven angle (each an exact tangency, Eqs. 2.9-2.10); at phi_max the middle and the
    # backward pair. phi_max solved on its own equals phi_min + one pitch (identical teeth): 1e-9 rad.
    r = crowned
    T, Tn = r.mesh.pitches
    assert r.phi_max_direct == pytest.approx(r.phi_min + T, abs=1e-9)
    for phi, j in ((r.phi_min, -1), (r.phi_max, 1)):
        a = r.solve(np.array([phi]), 0)[0][0, 4]
        b = r.solve(np.array([phi]), j)[0][0, 4]
        assert a == pytest.approx(b, abs=1e-12)
    # inside the interval the middle pair drives the face gear furthest: its neighbours have backlash
    for j, ph in ((-1, r.phi_min + np.linspace(0.01, 0.25, 5) * T), (1, r.phi_max - np.linspace(0.01, 0.25, 5) * T)):
        assert np.all(r.solve(ph, j)[0][:, 4] < r.solve(ph, 0)[0][:, 4])
    assert r.edge_fraction == 0.0
    assert min(min(m.values()) for m in r.margins.values()) > 0


def test_bad_pairing_is_rejected(face60):
    p = Gear("p", 17, 5.0, d(20), 40.0, helix=d(10), hand=-1, tool_tip_radius=0.45)
    with pytest.raises(InputError, match="p.hand"):
        FaceMesh(face60, p, "pinion")
    p = Gear("p", 17, 4.0, d(20), 40.0, helix=d(10), hand=1, tool_tip_radius=0.45)
    with pytest.raises(InputError, match="p.module_mm"):
        FaceMesh(face60, p, "pinion")
    p = Gear("p", 23, 5.0, d(20), 40.0, helix=d(10), hand=1)
    with pytest.raises(InputError, match="p.teeth"):
        FaceMesh(face60, p, "pinion")
    p = Gear("p", 17, 5.0, d(20), 40.0, helix=d(10), hand=1, tool_tip_radius=0.45)
    with pytest.raises(InputError, match="driver"):
        FaceMesh(face60, p, "carrier")
