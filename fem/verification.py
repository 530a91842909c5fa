"""Verification cases with analytic references: Hertz line and point contact, cantilever, chains.

Hertz (Johnson, Contact Mechanics, ch. 4), equal materials, 1/E* = 2 (1 - nu^2) / E:

    line contact, load P' [N/mm], radius R against a flat:  a = sqrt(4 P' R / (pi E*)),
                                                             p0 = 2 P' / (pi a),
                                                             p(x) = p0 sqrt(1 - x^2 / a^2);
    point contact, load P [N], sphere R on a flat:           a = (3 P R / (4 E*))^(1/3),
                                                             p0 = 3 P / (2 pi a^2).

Cantilever (Saint-Venant flexure, end load P): sigma_xx = P (L - x) y / I exactly away from the
ends; Timoshenko tip deflection  P L^3 / (3 E I) + P L / (kappa G A), kappa = 5/6.

Each builder returns (mesh, model, reference dict); the models use the report's steel unless a
:class:`ModelSetup` (material, contact and solver options) says otherwise.
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from fem.mesh import primitives as prim
from fem.mesh.hexmesh import HexMesh

from fem.material import STEEL, Material
from fem.model import Body, ContactOptions, ContactPair, FEModel, Fixed, Rigid, SolverOptions, Traction

__all__ = ["ModelSetup", "hertz_line", "hertz_point", "cantilever", "block_chain", "gear_like"]


@dataclass(frozen=True)
class ModelSetup:
    """Material of every body, contact and solver options of a verification model."""

    material: Material = STEEL
    contact: ContactOptions = field(default_factory=ContactOptions)
    solver: SolverOptions = field(default_factory=SolverOptions)


def _estar(mat: Material) -> float:
    return mat.E / (2.0 * (1.0 - mat.nu**2))


def hertz_line(radius: float = 20.0, p0: float = 1000.0, elements_per_halfwidth: float = 10.0, growth: float = 1.2,
               block_ratio: float = 0.8, setup: ModelSetup = ModelSetup()):
    """Plane-strain slice of half a cylinder on a block: (mesh, model, {a, p0, load_per_length, thickness}).

    The block's fine elements are ``block_ratio`` times the cylinder's: the nodes of the two
    surfaces do not coincide, as on gear flanks.
    """
    mat = setup.material
    Es = _estar(mat)
    P = p0**2 * np.pi * radius / Es  # load per unit length giving the peak p0
    a = np.sqrt(4 * P * radius / (np.pi * Es))
    h = a / elements_per_halfwidth
    mesh = prim.cylinder_on_block(radius, h, 1.5 * a, growth=growth, block_h=block_ratio * h)
    t = h  # slice thickness: one element
    z = (2,)
    model = FEModel(
        bodies=(
            Body("roller", (Rigid("roller/inner", "roller", free=("uy",), force=(0.0, -P * t / 2, 0.0)),
                            Fixed("roller/sym", (0,)), Fixed("roller/front", z), Fixed("roller/back", z)), mat),
            Body("block", (Fixed("block/bottom"), Fixed("block/sym", (0,)), Fixed("block/front", z), Fixed("block/back", z)), mat),
        ),
        contacts=(ContactPair("roller/surface", "block/top", search_gap=0.05 * a),),
        contact=setup.contact,
        solver=setup.solver,
    )
    return mesh, model, {"a": a, "p0": 2 * P / (np.pi * a), "load_per_length": P, "thickness": t, "force": P * t / 2}


def hertz_point(radius: float = 20.0, p0: float = 1500.0, elements_per_radius: float = 6.0, growth: float = 1.5,
                size: float = 5.0, block_ratio: float = 0.8, setup: ModelSetup = ModelSetup()):
    """Quarter of a spherical cap on a block: (mesh, model, {a, p0, load}); non-coincident surface nodes."""
    mat = setup.material
    Es = _estar(mat)
    a = np.pi * radius * p0 / (2 * Es)
    P = 2 * np.pi * a**2 * p0 / 3
    h = a / elements_per_radius
    mesh = prim.sphere_on_block(radius, h, 1.3 * a, growth=growth, size=size, block_h=block_ratio * h)
    model = FEModel(
        bodies=(
            Body("cap", (Rigid("cap/top", "cap", free=("uz",), force=(0.0, 0.0, -P / 4)), Fixed("cap/symx", (0,)),
                         Fixed("cap/symy", (1,))), mat),
            Body("block", (Fixed("block/bottom"), Fixed("block/symx", (0,)), Fixed("block/symy", (1,))), mat),
        ),
        contacts=(ContactPair("cap/surface", "block/top", search_gap=0.1 * a),),
        contact=setup.contact,
        solver=setup.solver,
    )
    return mesh, model, {"a": (3 * P * radius / (4 * Es)) ** (1 / 3), "p0": p0, "load": P}


def cantilever(length: float = 12.0, depth: float = 4.0, width: float = 4.0, n_depth: int = 2, load: float = 1000.0,
               setup: ModelSetup = ModelSetup()):
    """Clamped block (x = 0) with a uniform shear traction -y at x = L: (mesh, model, references)."""
    mat = setup.material
    nx = int(round(n_depth * length / depth))
    mesh = prim.box("beam", np.linspace(0, length, nx + 1), np.linspace(-depth / 2, depth / 2, n_depth + 1),
                    np.linspace(0, width, n_depth + 1))
    model = FEModel(
        bodies=(Body("beam", (Fixed("beam/xmin"),), mat, (Traction("beam/xmax", (0.0, -load / (depth * width), 0.0)),)),),
        contact=setup.contact,
        solver=setup.solver,
    )
    I = width * depth**3 / 12
    G = mat.mu
    ref = {
        "sigma_mid": load * (length / 2) * (depth / 2) / I,  # |sigma_xx| at x = L/2 on y = +-depth/2
        "tip_timoshenko": load * length**3 / (3 * mat.E * I) + load * length / (5 / 6 * G * width * depth),
        "length": length,
        "depth": depth,
    }
    return mesh, model, ref


def block_chain(size: float = 4.0, n: int = 4, pressure: float = 100.0, setup: ModelSetup = ModelSetup()):
    """Three stacked cubes in confined compression; the middle one floats (free uy) between contacts.

    ``top`` is tied to a reference with free uy and loaded by p * size^2; ``mid`` is tied at its
    mid-plane with free uy (singular before contact closes); ``base`` is fixed at the bottom. All
    lateral faces are rollers, so the exact state is uniaxial strain: p uniform, and the top moves
    by 3 size p / (lambda + 2 mu) plus the two penalty penetrations.
    """
    mat = setup.material
    x = np.linspace(0, size, n + 1)
    blocks = []
    for k, name in enumerate(("base", "mid", "top")):
        y = np.linspace(k * size, (k + 1) * size, 2 * (n // 2) + 1)
        b = prim.box(name, x, y, x)
        mid_nodes = np.flatnonzero(np.isclose(b.points[:, 1], (k + 0.5) * size))
        blocks.append(HexMesh(b.points, b.cells, b.cell_body, b.bodies, {f"{name}/midplane": mid_nodes}, b.face_sets))
    mesh = prim.combine(*blocks)
    for name, y in (("top", 3 * size), ("mid", 1.5 * size)):
        mesh = prim.with_reference(mesh, name, (size / 2, y, size / 2), (0.0, 1.0, 0.0))
    F = pressure * size**2

    def rollers(name):
        return (Fixed(f"{name}/xmin", (0,)), Fixed(f"{name}/xmax", (0,)), Fixed(f"{name}/zmin", (2,)), Fixed(f"{name}/zmax", (2,)))

    # the reference axis is y: its frame is (x, -z, y), so 'uz' is the translation along y
    model = FEModel(
        bodies=(
            Body("base", (Fixed("base/ymin"),) + rollers("base"), mat),
            Body("mid", (Rigid("mid/midplane", "mid", free=("uz",)),) + rollers("mid"), mat),
            Body("top", (Rigid("top/ymax", "top", free=("uz",), force=(0.0, -F, 0.0)),) + rollers("top"), mat),
        ),
        contacts=(ContactPair("top/ymin", "mid/ymax", name="top-mid", search_gap=0.01),
                  ContactPair("mid/ymin", "base/ymax", name="mid-base", search_gap=0.01)),
        contact=setup.contact,
        solver=setup.solver,
    )
    return mesh, model, {"pressure": pressure, "force": F, "shortening": 3 * size * pressure / (mat.lam + 2 * mat.mu)}


def gear_like(torque: float = 5e5, sizes: prim.SplineMesh = prim.SplineMesh(), search_gap: float = 0.1,
              contact_point: bool = False, backlash=(0.0, 0.002, 0.005), setup: ModelSetup = ModelSetup()):
    """Hub (rigid bore, free rotation, torque [N mm]) driving a fixed sleeve through three tooth pairs.

    Like the report's ring/planet ties (Fig. 1.7): the body is singular before contact closes.
    ``sizes``: the element sizes of :func:`fem.mesh.primitives.spline_coupling`; ``backlash`` [mm]
    per tooth. Returns (mesh, model, {torque}); the sleeve's reaction torque about z is -torque exactly.
    """
    mesh = prim.spline_coupling(prim.SplineCoupling(backlash=backlash), sizes)
    pairs = []
    for k in range(3):
        cp = tuple(mesh.points[mesh.point_sets[f"hub/tooth{k}/contact_point"][0]]) if contact_point else None
        pairs.append(ContactPair(f"hub/tooth{k}/flank", f"sleeve/tooth{k}/flank", name=f"hub/tooth{k}", group="hub",
                                 search_gap=search_gap, contact_point=cp))
    model = FEModel(
        bodies=(Body("hub", (Rigid("hub/bore", "hub", free=("rz",), torque=torque),), setup.material),
                Body("sleeve", (Fixed("sleeve/outer"),), setup.material)),
        contacts=tuple(pairs),
        contact=setup.contact,
        solver=setup.solver,
        fillet_sets=tuple(f"hub/tooth{k}/fillet" for k in range(3)) + tuple(f"sleeve/tooth{k}/fillet" for k in range(3)),
    )
    return mesh, model, {"torque": torque}
