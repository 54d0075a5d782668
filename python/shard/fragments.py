"""Fragments (connected components of the surviving bonds) and their size distribution, computed
by the analysis library's functions (docs/fragments.md)."""
from __future__ import annotations

from dataclasses import dataclass

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
        """x_p for p in (0, 1]: d interpolated linearly in Q (docs/fragments.md)."""
        return _shard.characteristic_size(self.d, self.cumulative, float(p))


@dataclass(frozen=True)
class Fragments:
    """The fragments of one frame: a canonical label per particle (0 the heaviest fragment) and one
    table row per fragment, row k = fragment k."""
    labels: np.ndarray        # int32 [N]
    label: np.ndarray         # int32 [K]
    particles: np.ndarray     # int64 [K]
    mass: np.ndarray          # kg
    volume: np.ndarray        # m^3, sum of sphere volumes
    centre: np.ndarray        # [K, 3] m, centre of mass
    velocity: np.ndarray      # [K, 3] m/s, mass-weighted
    d_eq: np.ndarray          # m, diameter of the sphere of the fragment's volume
    box_min: np.ndarray       # [K, 3] m
    box_max: np.ndarray       # [K, 3] m
    body: np.ndarray          # int32 [K], parent body holding the largest share of its mass
    mixed_bodies: np.ndarray  # bool [K]
    smallest_id: np.ndarray   # int32 [K]

    def __len__(self) -> int:
        return len(self.label)

    def size_distribution(self, fines_size: float = 0.0) -> SizeDistribution:
        return size_distribution(self, fines_size=fines_size)


@dataclass(frozen=True)
class BodyStatistics:
    """Per parent body of a frame: fragments, largest fragment's mass fraction, broken or not."""
    body: np.ndarray              # int32 [B], ascending; ids without particles left out
    particles: np.ndarray
    mass: np.ndarray              # kg
    fragments: np.ndarray         # fragments whose parent body is this one
    largest_fraction: np.ndarray  # largest fragment's mass / body mass
    broken: np.ndarray            # bool: largest_fraction < intact_fraction
    x10: np.ndarray               # m, per body
    x50: np.ndarray
    x90: np.ndarray
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
    return Fragments(**d)


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
    d = _shard.body_statistics(*_frame_arrays(frame), float(intact_fraction), float(fines_size))
    d["distributions"] = [_distribution(x) for x in d["distributions"]]
    d["pooled"] = _distribution(d["pooled"])
    return BodyStatistics(**d)
