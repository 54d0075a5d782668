"""shard.RunFile: a run.h5 as numpy arrays, read by the kernel's own reader (the one place that knows
the layout of docs/reference/output-format.md)."""
from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path

import numpy as np

from . import _shard
from .fragments import body_report, fragments

# Series columns stored as integers; the others are float64.
_INTEGER_SERIES = ("step", "bonds_intact", "bonds_broken", "contacts")
_FLOAT_SERIES = ("time", "kinetic_energy", "bond_energy", "contact_energy")


@dataclass(frozen=True)
class Frame:
    """One frame: per-particle arrays in the frame's row order, and its surviving bonds as rows."""
    number: int
    step: int
    time: float               # s
    id: np.ndarray            # int32 [N], stable particle id
    position: np.ndarray      # float64 [N, 3], m
    velocity: np.ndarray      # float64 [N, 3], m/s
    omega: np.ndarray         # float64 [N, 3], rad/s
    radius: np.ndarray        # float64 [N], m
    mass: np.ndarray          # float64 [N], kg
    mass_source: str          # where the masses came from (the mass dataset, or a density)
    material: np.ndarray      # int32 [N]
    body: np.ndarray          # int32 [N], the scene body each particle was generated in
    bonds: np.ndarray         # int32 [M, 2], row indices into this frame's arrays
    fragment: np.ndarray | None  # int32 [N], canonical fragment labels, when the run labelled them

    def __len__(self) -> int:
        return len(self.id)

    @property
    def total_mass(self) -> float:
        return float(self.mass.sum())

    @property
    def kinetic_energy(self) -> float:
        """Translational kinetic energy, J."""
        return float(0.5 * np.sum(self.mass * np.einsum("ij,ij->i", self.velocity, self.velocity)))

    def fragments(self):
        """The fragments of this frame (shard.fragments)."""
        return fragments(self)


class RunFile:
    """An open run file. Works as a context manager; frames are numbered as the file numbers them
    (0 .. n-1 for `shard run`), and frame(-1) is the last complete one."""

    def __init__(self, path):
        self._file = _shard.RunFile(str(path))
        self.path = Path(path)

    def __enter__(self) -> "RunFile":
        return self

    def __exit__(self, *exc) -> None:
        self.close()

    def close(self) -> None:
        self._file = None

    @property
    def _reader(self):
        if self._file is None:
            raise ValueError(f"{self.path}: the run file is closed")
        return self._file

    def metadata(self) -> dict:
        """Root attributes and the /plugins, /generator and /notes groups: scene (the resolved
        TOML text), scene_file, seed, shard_version, git_revision, plugins, generator_quality, notes."""
        return self._reader.metadata()

    @property
    def frame_numbers(self) -> list[int]:
        return list(self._reader.frames())

    def __len__(self) -> int:
        return len(self._reader.frames())

    def frame(self, index: int = -1, density: float | None = None) -> Frame:
        """The frame at `index` of frame_numbers (negative counts from the end). density (kg/m^3)
        gives masses to a file without a mass dataset."""
        numbers = self._reader.frames()
        if not numbers:
            raise IndexError(f"{self.path}: no complete frame")
        number = numbers[index]
        d = self._reader.read_frame(number, density)
        return Frame(number=number, **d)

    def frames(self):
        """Every complete frame, first to last (each read when reached)."""
        for index in range(len(self)):
            yield self.frame(index)

    def series(self) -> dict[str, np.ndarray]:
        """The time series, one array per column, cut to the rows every column holds."""
        out = {name: self._reader.read_integer_series(name) for name in _INTEGER_SERIES}
        out.update({name: self._reader.read_series(name) for name in _FLOAT_SERIES})
        return out

    @property
    def wall_names(self) -> list[str]:
        return list(self._reader.wall_names())

    def wall(self, name: str) -> dict[str, np.ndarray]:
        """A wall's series: force (N), torque (N m), displacement (m) as [n, 3], and impact_energy
        (J), impacts when the file recorded them."""
        out = {q: self._reader.read_wall_series(name, q) for q in ("force", "torque", "displacement")}
        try:
            out["impact_energy"] = self._reader.read_wall_impact_energy(name)
            out["impacts"] = self._reader.read_wall_impacts(name)
        except _shard.OutputError:
            pass  # written before the wall's impacts were recorded
        return out

    def break_events(self) -> dict[str, np.ndarray]:
        """The bond-break log: time, step, id_i, id_j, midpoint [n, 3], the stresses (Pa) and mode
        (1 tension, 2 bending, 3 shear, 4 torsion)."""
        return self._reader.read_break_events()

    def body_impacts(self) -> dict[str, np.ndarray]:
        """First wall contact per body id (row = body): hit, step, time, velocity, normal, wall,
        speed, angle; empty arrays when the run wrote none."""
        return self._reader.read_body_impacts()

    def body_statistics(self, index: int = -1, intact_fraction: float = 0.9, fines_size: float = 0.0,
                        density: float | None = None):
        """Per-body statistics of frame `index` with each body's first wall contact, as
        `shard fragments --by-body` computes them (shard.BodyStatistics)."""
        if not 0 < intact_fraction <= 1:
            raise ValueError("intact_fraction must lie in (0, 1]: 1 counts a body broken once any piece broke off")
        number = self._reader.frames()[index]
        return body_report(self._reader.body_statistics(number, float(intact_fraction), float(fines_size), density))

    def table(self, group: str) -> dict:
        """A table the analysis stored under `group` (e.g. "fragments/000012", "bodies/000050"):
        one numpy array per column dataset, and the table's figures under "attributes"."""
        import h5py  # only here: the rest of the package needs numpy alone
        with h5py.File(self.path, "r") as f:
            if group not in f:
                raise KeyError(f"{self.path}: no table '{group}'. Fix: store it with `shard fragments "
                               f"{self.path} --write-labels` (fragments/) or `--by-body` (bodies/)")
            g = f[group]
            columns = {name: g[name][()] for name in g if isinstance(g[name], h5py.Dataset)}
            columns["attributes"] = {k: _plain(v) for k, v in g.attrs.items()}
        return columns


def _plain(value):
    """HDF5 attribute values as Python numbers and strings."""
    if isinstance(value, bytes):
        return value.decode()
    if isinstance(value, np.generic):
        return value.item()
    return value
