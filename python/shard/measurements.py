"""The measurement loop's results (`shard compare`, `diagnose`, `calibrate-effect`; docs/explanation/diagnosis.md)
as Python objects. Each class keeps the whole document in `data`; curves are numpy arrays.

The files are read tolerantly: a `format_version` field is accepted (and kept), a number the writer
could not give (null, or a bare nan/inf) becomes float('nan') / +-inf."""
from __future__ import annotations

import json
import math
import re
from dataclasses import dataclass, field, fields
from pathlib import Path

import numpy as np

# A JSON string, or a bare non-finite token outside strings (as printf writes nan and inf).
_TOKEN = re.compile(r'"(?:\\.|[^"\\])*"|(-?)\b(nan|inf|infinity)\b', re.IGNORECASE)


def _replace_non_finite(match: re.Match) -> str:
    if match.group(2) is None:
        return match.group(0)
    return "NaN" if match.group(2).lower() == "nan" else match.group(1) + "Infinity"


def load_json(path) -> dict:
    """A result file as a dict, its non-finite numbers read as floats; errors name the file."""
    path = Path(path)
    text = _TOKEN.sub(_replace_non_finite, path.read_text())
    try:
        return json.loads(text)
    except json.JSONDecodeError as e:
        raise ValueError(f"{path}:{e.lineno}:{e.colno}: not a result file of shard ({e.msg}). "
                         "Fix: give the compare.json, diagnose.json or calibrate.json a command wrote") from None


def _number(value) -> float:
    """A figure of the file: null (not finite, or not computed) as nan."""
    return math.nan if value is None else float(value)


def _numbers(values) -> np.ndarray:
    return np.array([_number(v) for v in values], dtype=float)


@dataclass(frozen=True)
class Feature:
    name: str
    unit: str
    measured: float
    u_measured: float
    simulated: float
    u_simulated: float
    error: float
    relative_error: float
    score: float          # (sim - meas) / sqrt(u_m^2 + u_s^2); |score| > 2 is beyond noise
    beyond_noise: bool
    judged: bool


@dataclass(frozen=True)
class Regime:
    name: str
    xi_first: float       # nan when the regime holds no grid point
    xi_last: float
    points: int
    mean_residual: float  # sigma
    rms_residual: float
    chi_square: float
    relative_error: float
    beyond_noise: bool


@dataclass(frozen=True)
class ComparisonCurves:
    """The curves behind compare.png (compare.dat beside it), sampled on the comparison grid."""
    w: np.ndarray                # m, loading-pin displacement
    measured_mean: np.ndarray    # N
    u_measured: np.ndarray       # N, standard uncertainty of the measured mean
    simulated_mean: np.ndarray   # N
    u_simulated: np.ndarray      # N
    residual: np.ndarray         # standardised residual, sigma
    individual: np.ndarray       # [curves, points] N: each measured specimen, then each simulated replicate

    def split(self, measured_count: int) -> tuple[np.ndarray, np.ndarray]:
        """(measured, simulated) individual curves, given how many specimens were compared."""
        return self.individual[:measured_count], self.individual[measured_count:]


def read_comparison_curves(dat) -> ComparisonCurves:
    """compare.dat: w_mm, measured mean and u, simulated mean and u, residual, then each curve."""
    table = np.loadtxt(dat, comments="#", ndmin=2)
    return ComparisonCurves(w=table[:, 0] * 1e-3, measured_mean=table[:, 1], u_measured=table[:, 2],
                            simulated_mean=table[:, 3], u_simulated=table[:, 4], residual=table[:, 5],
                            individual=table[:, 6:].T)


@dataclass(frozen=True)
class Comparison:
    """One comparison of measured and simulated curves at one loading rate."""
    verdict: str
    adequate: bool
    nrmse: float
    reference_displacement: float  # m
    measured_peak_force: float     # N
    features: dict                 # name -> Feature
    regimes: dict                  # name -> Regime
    dynamic_warning: str
    curves: ComparisonCurves | None  # from the plot's data file, when it is beside the JSON
    data: dict = field(repr=False)

    @classmethod
    def from_data(cls, data: dict, curves: ComparisonCurves | None = None) -> "Comparison":
        features = {f["name"]: _row(Feature, f) for f in data.get("features", [])}
        regimes = {g["name"]: _row(Regime, g) for g in data.get("regimes", [])}
        return cls(verdict=data["verdict"], adequate=bool(data["adequate"]), nrmse=_number(data["nrmse"]),
                   reference_displacement=_number(data["reference_displacement"]),
                   measured_peak_force=_number(data["measured_peak_force"]), features=features,
                   regimes=regimes, dynamic_warning=data.get("dynamic_warning", ""), curves=curves, data=data)


def _row(cls, d: dict):
    """A Feature or Regime from its JSON object: its own fields (others, of a newer file, are left in
    `data`), floats as numbers with null as nan."""
    kinds = {f.name: f.type for f in fields(cls)}
    return cls(**{k: _number(d.get(k)) if kinds[k] == "float" else d.get(k) for k in kinds})


@dataclass(frozen=True)
class RateComparison:
    """compare.json of a set measured at several loading rates: one Comparison per rate."""
    rates: np.ndarray  # m/s
    nrmse: float
    chi_square: float
    at: list           # Comparison per rate, in the order of rates
    dynamic_warning: str
    data: dict = field(repr=False)


def load_comparison(path):
    """compare.json (a folder holding it, or the file) as a Comparison, or a RateComparison for
    several rates; a single comparison's curves come from compare.dat when it is there."""
    path = Path(path)
    if path.is_dir():
        path = path / "compare.json"
    data = load_json(path)
    if "at" in data:
        return RateComparison(rates=_numbers(data["rates"]), nrmse=_number(data["nrmse"]),
                              chi_square=_number(data["chi_square"]),
                              at=[Comparison.from_data(c) for c in data["at"]],
                              dynamic_warning=data.get("dynamic_warning", ""), data=data)
    dat = path.with_suffix(".dat")
    curves = read_comparison_curves(dat) if dat.exists() else None
    return Comparison.from_data(data, curves)


class Record:
    """A JSON object with its keys as attributes: objects as Records, lists of numbers (null as nan)
    as numpy arrays, lists of objects as lists of Records. `data` is the dict as read, `source` the
    file it came from (None for a nested object); every other attribute is a field of the file."""

    def __init__(self, data: dict, source: Path | None = None):
        self.data = data
        self.source = source

    def __getattr__(self, name):
        data = self.__dict__.get("data", {})
        if name not in data:
            raise AttributeError(f"{type(self).__name__} has no field '{name}'; fields: {', '.join(data)}")
        return _value(data[name])

    def __dir__(self):
        return sorted(set(super().__dir__()) | set(self.data))

    def keys(self):
        return self.data.keys()

    def __repr__(self) -> str:
        return f"{type(self).__name__}({', '.join(self.data)})"


def _value(v):
    if isinstance(v, dict):
        return Record(v)
    if isinstance(v, list) and v and all(isinstance(x, dict) for x in v):
        return [Record(x) for x in v]
    if isinstance(v, list) and v and all(isinstance(x, bool) for x in v):
        return np.array(v, dtype=bool)
    if isinstance(v, list) and all(x is None or (isinstance(x, (int, float)) and not isinstance(x, bool)) for x in v):
        return _numbers(v)
    return math.nan if v is None else v


def _column(records: list, name: str) -> np.ndarray:
    values = [r.get(name) for r in records]
    if all(isinstance(x, str) for x in values):
        return np.array(values, dtype=object)
    if all(isinstance(x, bool) for x in values):
        return np.array(values, dtype=bool)
    return _numbers(values)


class Diagnosis(Record):
    """diagnose.json: the verdict, the ranking of candidate effects and the confirmation refits
    (the stepwise diagnosis and the contrast diagnosis write different fields: all are attributes)."""

    def table(self, name: str) -> dict[str, np.ndarray]:
        """A list of objects in the file (e.g. "ranking", "confirmations", "path") as columns."""
        records = self.data.get(name) or []
        keys = dict.fromkeys(k for r in records for k in r if not isinstance(r[k], (dict, list)))
        return {k: _column(records, k) for k in keys}


class Calibration(Record):
    """calibrate.json: the fitted effect and value, chi^2 and NRMSE before and after, and each
    regime's mean residual before and after."""

    def regime_residuals(self) -> tuple[list[str], np.ndarray, np.ndarray]:
        """(regime names, mean residual before, after), in sigma."""
        regimes = self.data.get("regimes") or {}
        names = list(regimes)
        return (names, _numbers([regimes[n][0] for n in names]), _numbers([regimes[n][1] for n in names]))

    def curves(self, which: str) -> ComparisonCurves:
        """The comparison "before" or "after" the fit, from before.dat / after.dat beside the file."""
        if which not in ("before", "after"):
            raise ValueError(f"curves: which is 'before' or 'after', not '{which}'")
        dat = Path(self.source or ".").parent / f"{which}.dat"
        if not dat.exists():
            raise FileNotFoundError(f"{dat}: missing. Fix: keep the --out folder calibrate-effect wrote whole")
        return read_comparison_curves(dat)


def load_result(path):
    """A result of the measurement loop by its file name: compare.json -> Comparison (or
    RateComparison), diagnose.json -> Diagnosis, calibrate.json -> Calibration. A folder is searched
    for those names in that order."""
    path = Path(path)
    if path.is_dir():
        found = [path / n for n in ("compare.json", "diagnose.json", "calibrate.json") if (path / n).exists()]
        if not found:
            raise FileNotFoundError(f"{path}: holds no compare.json, diagnose.json or calibrate.json. "
                                    "Fix: give the --out folder of shard compare, diagnose or calibrate-effect")
        path = found[0]
    kinds = {"compare": load_comparison, "diagnose": lambda p: Diagnosis(load_json(p), p),
             "calibrate": lambda p: Calibration(load_json(p), p)}
    for prefix, load in kinds.items():
        if path.name.startswith(prefix):
            return load(path)
    raise ValueError(f"{path}: not a result file name of the measurement loop. "
                     "Fix: give compare.json, diagnose.json or calibrate.json (or the folder holding one)")
