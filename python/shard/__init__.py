"""Shard from Python: run scenes in-process, read run files as numpy arrays, analyse fragments,
and load the measurement loop's results (docs/reference/python.md)."""
from ._shard import CheckpointError, NumericalError, OutputError, PluginError, SceneError
from .cli import calibrate_effect, cli_path, compare, diagnose, run_cli
from .fragments import (BodyStatistics, Fragments, SizeDistribution, body_statistics, fragments,
                        size_distribution)
from .measurements import (Calibration, Comparison, Diagnosis, RateComparison, load_json,
                           load_result)
from .run_file import Frame, RunFile
from .runs import LoadCurve, RunInterrupted, RunResult, plugin_search_path, run

__all__ = [
    "Calibration", "CheckpointError", "Comparison", "Diagnosis", "Frame", "Fragments", "LoadCurve",
    "NumericalError", "OutputError", "PluginError", "RateComparison", "RunFile", "RunInterrupted", "RunResult",
    "SceneError", "SizeDistribution", "BodyStatistics", "body_statistics", "calibrate_effect", "cli_path",
    "compare", "diagnose", "fragments", "load_json", "load_result", "plugin_search_path", "run",
    "run_cli", "size_distribution",
]
