"""``gearfe rate``: the command's readers, one per case kind, on top of the ``[rating]`` reader.

Each reads the whole case (its gears or train, the tables the kind allows) and its ``[rating]`` table, and returns
the meshes to rate (:class:`RateJob`). They sit above :mod:`pipelines.cases.rating`, which the pair, planetary and
stress readers use for their optional ``[rating]`` table, so that no reader imports back into another.
"""

from __future__ import annotations

from dataclasses import dataclass

from tca.errors import InputError
from tca.rating.from_gears import rating_case

from pipelines.cases.planetary import read_installment, read_regulation_options, read_train
from pipelines.cases.rating import MeshRating, check_rating, rated_meshes, read_rating, train_meshes, train_names
from pipelines.cases.reader import read_gears, read_pair, read_tca_options
from pipelines.cases.schema import Table
from pipelines.cases.ltca import loaded, read_loaded_pair
from pipelines.cases.stress import TORQUE_KEYS, read_stress_case

__all__ = ["RateJob", "read_pair_rate", "read_planetary_rate", "read_stress_rate"]


@dataclass(frozen=True)
class RateJob:
    """What ``gearfe rate`` rates: the case's title and kind, and its meshes."""

    title: str
    kind: str
    meshes: tuple[MeshRating, ...]


def _need(t: Table) -> None:
    if not t.has("rating"):
        raise InputError("rating", None, "a [rating] table (speed, life, lubricant, material per gear: docs/cases.md)",
                         "gearfe rate needs it")


def read_pair_rate(t: Table) -> RateJob:
    """``gearfe rate`` of a ``kind = "pair"`` case: the pair and its ``[rating]`` (with a torque of its own); a pair
    file with a torque key is rated at that torque, as its stress case (one file per pair)."""
    _need(t)
    if any(t.has(k) for k in TORQUE_KEYS):
        return read_stress_rate(t)
    title = t.data.get("title", "")
    if loaded(t):  # position, [mesh], [fe], [ltca] checked, not used
        pair, _, spec = read_loaded_pair(t)
    else:
        t.get("kind", str)
        t.get("title", str, "")
        pair, _, _ = read_pair(t, read_gears(t))
        read_tca_options(t.table("tca", required=False))
        spec = read_rating(t.table("rating"), (pair.gear1.name, pair.gear2.name), case_has_torque=False)
    t.done()
    meshes = [MeshRating("pair", pair, rating_case(pair, spec.gears, spec.service, spec.load()))]
    check_rating(meshes)
    return RateJob(title, "pair", tuple(meshes))


def read_planetary_rate(t: Table) -> RateJob:
    """``gearfe rate`` of a ``kind = "planetary"`` case (Part 1 train); ``[rating]`` gives the ring's torque."""
    _need(t)
    t.get("kind", str)
    title = t.get("title", str, "")
    train = read_train(t)
    read_installment(t.table("installment", required=False), train.planets)
    read_regulation_options(t.table("regulation", required=False))
    read_tca_options(t.table("tca", required=False))
    spec = read_rating(t.table("rating"), train_names(train), case_has_torque=False)
    t.done()
    if spec.torque_of != "driven":
        raise InputError("rating.driver_torque_nm", spec.torque * 1e-3, "driven_torque_nm: the ring's torque (carrier "
                         "at rest) in a planetary case")
    meshes = train_meshes(train, spec, spec.torque, None)
    check_rating(meshes)
    return RateJob(title, "planetary", tuple(meshes))


def read_stress_rate(t: Table) -> RateJob:
    """``gearfe rate`` of a ``kind = "stress"`` case: its pair or twin train at the case's torque."""
    _need(t)
    rec = read_stress_case(t)
    return RateJob(rec.title, "stress", tuple(rated_meshes(rec)))
