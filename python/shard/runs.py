"""shard.run: one run of a scene in this process, through the same driver as `shard run`."""
from __future__ import annotations

import numbers
import os
from collections.abc import Iterable, Mapping
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

from . import _shard
from .run_file import RunFile


@dataclass(frozen=True)
class LoadCurve:
    """The load walls' force against their mean displacement, one row per series row (empty for a
    scene without [stop] load_walls)."""
    time: np.ndarray          # s
    displacement: np.ndarray  # m
    load: np.ndarray          # N

    def __len__(self) -> int:
        return len(self.load)


@dataclass(frozen=True)
class RunResult:
    """What a run ended with: the driver's figures, the load curve and where the files are."""
    run_file: Path        # run.h5
    steps: int
    time: float           # s, simulated
    dt: float             # s
    particles: int
    bonds_initial: int
    bonds_broken: int
    curve: LoadCurve
    peak_load: float             # N
    displacement_at_peak: float  # m
    final_displacement: float    # m
    max_kinetic_to_elastic: float
    kinetic_before_break: np.ndarray  # J, deformation kinetic energy per series row before the first break
    elastic_before_break: np.ndarray  # J
    fragment_particles: np.ndarray    # particles per fragment at the last labelled frame, largest first
    wall_seconds: float
    stop: str          # duration, load_drop, max_displacement, interrupted, observer or rest
    stop_reason: str   # the same in words
    checkpoint: Path | None
    checkpoint_step: int
    restarted_from: int
    log: list[str] = field(repr=False)  # the lines `shard run` prints (report, warnings)

    @property
    def run_dir(self) -> Path:
        return self.run_file.parent

    @property
    def curve_csv(self) -> Path | None:
        """<run>_curve.csv (time_s, displacement_m, force_N), written when the scene has load walls."""
        path = self.run_dir / f"{self.run_file.stem}_curve.csv"
        return path if path.exists() else None

    def open(self) -> RunFile:
        return RunFile(self.run_file)


def _scene_value(value):
    """numpy scalars and arrays, tuples and paths as the plain Python values the binding takes."""
    if isinstance(value, os.PathLike):
        return os.fspath(value)
    if isinstance(value, np.ndarray):
        return value.tolist()
    if isinstance(value, np.generic):
        return value.item()
    if isinstance(value, numbers.Integral) and not isinstance(value, bool):
        return int(value)
    if isinstance(value, numbers.Real) and not isinstance(value, (int, float)):
        return float(value)
    if isinstance(value, tuple):
        return list(value)
    return value


def _split_overrides(overrides) -> tuple[list[tuple[str, object]], list[str]]:
    """A mapping {"bond.youngs_modulus": 13e6} gives typed values; "key=value" strings are parsed
    with TOML's rules, as `--set` parses them."""
    if overrides is None:
        return [], []
    if isinstance(overrides, Mapping):
        return [(str(k), _scene_value(v)) for k, v in overrides.items()], []
    if isinstance(overrides, str) or not isinstance(overrides, Iterable):
        raise TypeError("overrides: give a dict {'section.key': value} or a list of 'section.key=value' strings")
    return [], [str(text) for text in overrides]


def _result(d: dict) -> RunResult:
    curve = LoadCurve(d["curve_time"], d["curve_displacement"], d["curve_load"])
    checkpoint = Path(d["checkpoint"]) if d["checkpoint"] is not None else None
    keep = {k: d[k] for k in ("steps", "time", "dt", "particles", "bonds_initial", "bonds_broken", "peak_load",
                              "displacement_at_peak", "final_displacement", "max_kinetic_to_elastic",
                              "kinetic_before_break", "elastic_before_break", "fragment_particles",
                              "wall_seconds", "stop", "stop_reason", "checkpoint_step", "restarted_from", "log")}
    return RunResult(run_file=Path(d["output"]), curve=curve, checkpoint=checkpoint, **keep)


class RunInterrupted(KeyboardInterrupt):
    """Ctrl-C (or SIGTERM) stopped a run; `result` holds what it reached and its checkpoint."""

    def __init__(self, result: RunResult):
        super().__init__(f"run interrupted at step {result.steps}; checkpoint {result.checkpoint}. "
                         f"Continue with shard.run(restart='{result.run_file}')")
        self.result = result


def run(scene=None, out=".", overrides=None, *, restart=None, threads=0, checkpoint_every=1,
        plugin_dirs=(), progress=False, echo=False) -> RunResult:
    """Runs `scene` (a .toml path) into the folder `out` and returns its RunResult.

    overrides: {"section.key": value} (bool, int, float, str, list of numbers or strings) or
    ["section.key=value", ...]. restart: a run.h5 to continue from its checkpoint (scene ignored).
    threads: OpenMP threads (0: OpenMP's default). plugin_dirs: searched before $SHARD_PLUGIN_PATH,
    the build tree and the install tree. progress: the progress line on stderr; echo: the closing
    report on stderr as well as in result.log. Ctrl-C during the run writes a checkpoint and raises
    RunInterrupted (a KeyboardInterrupt) carrying the result.
    """
    if scene is None and restart is None:
        raise TypeError("run: give a scene file, or restart= a run.h5 to continue")
    typed, assignments = _split_overrides(overrides)
    d = _shard.run(str(scene or ""), typed, assignments, str(out), str(restart or ""), int(threads),
                   int(checkpoint_every), [str(p) for p in plugin_dirs], bool(progress), bool(echo))
    result = _result(d)
    if d["interrupt_signal"] != 0:
        raise RunInterrupted(result)
    return result


def plugin_search_path(plugin_dirs=()) -> list[Path]:
    """The folders searched for plugins, in priority order, as `shard run` searches them."""
    return [Path(p) for p in _shard.plugin_search_path([str(p) for p in plugin_dirs])]
