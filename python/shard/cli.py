"""The `shard` command beside this module, for the commands that are not bound in-process: the
measurement loop (compare, diagnose, calibrate-effect) runs many scenes on worker processes and
writes its results as files, which shard.load_result reads."""
from __future__ import annotations

import os
import shutil
import subprocess
from pathlib import Path

from .measurements import load_result

_HERE = Path(__file__).resolve().parent
# The build tree puts the module in <build>/python/shard and the command in <build>/bin; an install
# puts them in <prefix>/lib/python3/dist-packages/shard and <prefix>/bin.
_CANDIDATES = (_HERE.parents[1] / "bin" / "shard", _HERE.parents[3] / "bin" / "shard")


def cli_path() -> Path:
    """$SHARD_CLI when set, else the `shard` of the same build or install as this module, else the
    one on PATH."""
    if os.environ.get("SHARD_CLI"):
        return Path(os.environ["SHARD_CLI"])
    for candidate in _CANDIDATES:
        if candidate.is_file() and os.access(candidate, os.X_OK):
            return candidate
    found = shutil.which("shard")
    if found:
        return Path(found)
    raise FileNotFoundError("no `shard` command beside the module nor on PATH. "
                            "Fix: build the `shard` target, or set SHARD_CLI to the command's path")


def _arguments(options: dict) -> list[str]:
    """{"work": "w", "param": ["a", "b"], "judge_fracture": True} -> --work w --param a --param b
    --judge-fracture. A trailing underscore is dropped: with_="x" is --with x (`with` is a keyword)."""
    out = []
    for key, value in options.items():
        flag = "--" + key.rstrip("_").replace("_", "-")
        if value is True:
            out.append(flag)
        elif value is False or value is None:
            continue
        elif isinstance(value, (list, tuple)):
            for item in value:
                out += [flag, str(item)]
        else:
            out += [flag, str(value)]
    return out


class CliError(subprocess.CalledProcessError):
    """A `shard` command that failed; its message ends with what the command printed on stderr."""

    def __str__(self) -> str:
        return f"{super().__str__()}\n{(self.stderr or '').strip()}"


def run_cli(*args, check: bool = True, capture: bool = True, **options) -> subprocess.CompletedProcess:
    """Runs `shard ARGS... --OPTION VALUE...` (options as in _arguments); raises CliError when it
    fails and `check` is set."""
    command = [str(cli_path()), *map(str, args), *_arguments(options)]
    done = subprocess.run(command, capture_output=capture, text=True)
    if check and done.returncode != 0:
        raise CliError(done.returncode, command, done.stdout, done.stderr)
    return done


def _result_of(command: str, measurements, out, options: dict):
    run_cli(command, measurements, out=out, **options)
    return load_result(Path(out))


def compare(measurements, out="compare", **options):
    """`shard compare MEASUREMENTS --out OUT ...`, then its compare.json as a Comparison.
    E.g. compare("meas", scene="model.toml", work="w") or compare("meas", sim=["run_curve.csv"])."""
    return _result_of("compare", measurements, out, options)


def diagnose(measurements, out="diagnose", **options):
    """`shard diagnose MEASUREMENTS --out OUT ...`, then its diagnose.json as a Diagnosis."""
    return _result_of("diagnose", measurements, out, options)


def calibrate_effect(measurements, out="calibrate", **options):
    """`shard calibrate-effect MEASUREMENTS --out OUT ...`, then its calibrate.json as a Calibration.
    E.g. calibrate_effect("meas", scene=S, work="w", param=[...], with_="machine_compliance")."""
    return _result_of("calibrate-effect", measurements, out, options)
