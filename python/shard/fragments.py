"""Fragments (connected components of the surviving bonds) and their size distribution, computed
by the analysis library's functions (docs/reference/fragments.md)."""
from __future__ import annotations

from dataclasses import dataclass, fields

import numpy as np

from . import _shard


@dataclass(frozen=True)
class SizeDistribution:
    """Mass-weighted cumulative distribution Q(d) of the fragments' equivalent diameter."""
    d: np.ndarray           # m, ascending (fragments of equal d_eq merged)
    cumulative: np.ndarray  # Q(d): mass fraction of fragments no larger than d
    fragments: int
    total_mass: float       # kg
    x10: float              # m
    x50: float
    x90: float
    fines_size: float       # m; fragments with d_eq below it are fines
    fines_mass: float       # kg

    @property
    def fines_fraction(self) -> float:
        return self.fines_mass / self.total_mass if self.total_mass > 0 else 0.0

    def characteristic_size(self, p: float) -> float:
        """x_p for p in (0, 1]: d interpolated linearly in Q (docs/reference/fragments.md)."""
        return _shard.characteristic_size(self.d, self.cumulative, float(p))


@dataclass(frozen=True)
class Fragments:
    """The fragments of one frame: a canonical label per particle (0 the heaviest fragment) and the
    fragment table with the columns `shard fragments` stores (row k = fragment k)."""
    labels: np.ndarray     # int32 [N]
    particles: np.ndarray  # int64 [K]
    mass: np.ndarray       # kg
    volume: np.ndarray     # m^3, sum of sphere volumes
    d_eq: np.ndarray       # m, diameter of the sphere of the fragment's volume
    centre: np.ndarray     # [K, 3] m, centre of mass
    velocity: np.ndarray   # [K, 3] m/s, mass-weighted
    box_min: np.ndarray    # [K, 3] m, bounds of the spheres
    box_max: np.ndarray    # [K, 3] m
    body: np.ndarray       # int32 [K], parent body holding the largest share of its mass

    def __len__(self) -> int:
        return len(self.particles)

    def size_distribution(self, fines_size: float = 0.0) -> SizeDistribution:
        return size_distribution(self, fines_size=fines_size)


@dataclass(frozen=True)
class BodyStatistics:
    """Per parent body of a frame, the columns `shard fragments --by-body` stores: its fragments,
    the largest one's mass fraction, broken or not, and its first wall contact when read from a run
    file (RunFile.body_statistics; impacted is False for a frame given alone)."""
    body: np.ndarray              # int32 [B], ascending; ids without particles left out
    broken: np.ndarray            # bool: largest_fraction < intact_fraction
    particles: np.ndarray
    fragments: np.ndarray         # fragments whose parent body is this one
    mass: np.ndarray              # kg
    largest_fraction: np.ndarray  # largest fragment's mass / body mass
    x10: np.ndarray               # m, per body
    x50: np.ndarray
    x90: np.ndarray
    fines_mass: np.ndarray        # kg
    impacted: np.ndarray          # bool
    impact_time: np.ndarray       # s
    impact_speed: np.ndarray      # m/s, centre-of-mass speed at the first wall contact
    impact_angle: np.ndarray      # degrees from head-on
    distributions: list           # SizeDistribution per body
    broken_count: int
    breakage_probability: float   # broken / bodies
    intact_fraction: float
    pooled: SizeDistribution      # every fragment of every body

    def __len__(self) -> int:
        return len(self.body)


def _frame_arrays(frame) -> tuple:
    return (frame.id, frame.position, frame.velocity, frame.radius, frame.mass, frame.body,
            np.asarray(frame.bonds).reshape(-1, 2))


def fragments(frame) -> Fragments:
    """Fragments of a frame (shard.Frame, or any object with id, position, velocity, radius, mass,
    body and bonds arrays): union-find over the bonds, canonical numbering, fragment table."""
    d = _shard.fragments(*_frame_arrays(frame))
    return Fragments(labels=d["labels"], **_known(Fragments, d["columns"]))


def _known(cls, columns: dict) -> dict:
    """The table's columns that are fields of `cls`; stored 0/1 flags as bool."""
    names = {f.name: f for f in fields(cls)}
    out = {k: v for k, v in columns.items() if k in names}
    for flag in ("broken", "impacted"):
        if flag in out:
            out[flag] = out[flag].astype(bool)
    return out


def body_report(d: dict) -> BodyStatistics:
    """A BodyStatistics from the binding's dict (the stored table, the distributions)."""
    figures = d["figures"]
    return BodyStatistics(**_known(BodyStatistics, d["columns"]),
                          distributions=[_distribution(x) for x in d["distributions"]],
                          broken_count=int(figures["broken_count"]),
                          breakage_probability=float(figures["breakage_probability"]),
                          intact_fraction=float(figures["intact_fraction"]), pooled=_distribution(d["pooled"]))


def _distribution(d: dict) -> SizeDistribution:
    return SizeDistribution(**d)


def size_distribution(source, mass=None, fines_size: float = 0.0) -> SizeDistribution:
    """Q(d) of a Fragments table, or of equivalent diameters `source` (m) with their `mass` (kg)."""
    if isinstance(source, Fragments):
        if mass is not None:
            raise TypeError("size_distribution: a Fragments table carries its masses; give no mass")
        return _distribution(_shard.size_distribution(source.d_eq, source.mass, float(fines_size)))
    if mass is None:
        raise TypeError("size_distribution: give the fragments' masses with the diameters")
    return _distribution(_shard.size_distribution(np.asarray(source, dtype=float),
                                                  np.asarray(mass, dtype=float), float(fines_size)))


def body_statistics(frame, intact_fraction: float = 0.9, fines_size: float = 0.0) -> BodyStatistics:
    """Per-body statistics of a many-body frame (`shard fragments --by-body`): a body is broken
    when its largest fragment holds less than intact_fraction of its mass."""
    return body_report(_shard.body_statistics(*_frame_arrays(frame), float(intact_fraction), float(fines_size)))
