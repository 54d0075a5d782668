"""The measurement loop's results as Python objects: a real `shard compare` of two tiny-beam runs
with themselves (through the CLI helper), and the loaders' tolerance of the file variants."""
import json
import math
from pathlib import Path

import numpy as np
import pytest

import shard

SPECIMENS = "id,length,width,height,span,pin_distance,loading_rate\n"
# The tiny beam of scenes/measurements/tiny_bending.toml: 40 x 8 x 8 mm, supports 36 mm apart,
# pins 16 mm apart at 0.02 m/s.
GEOMETRY = "0.040,0.008,0.008,0.036,0.016,0.02"


def write_curve(path, curve):
    """A curve file of the measurement format: time, displacement, force."""
    table = np.column_stack([curve.time, curve.displacement, curve.load])
    np.savetxt(path, table, delimiter=",", header="time,displacement,force", comments="", fmt="%.17g")
    return path


def measurement_folder(folder, runs):
    """A measurement folder (docs/how-to/bring-lab-data.md) whose specimens are the runs' load curves."""
    (folder / "curves").mkdir(parents=True)
    (folder / "metadata.toml").write_text(
        'name = "tiny beam runs"\n[uncertainty]\nload_cell = 0.01\ndisplacement = 1e-6\n')
    for k, r in enumerate(runs):
        write_curve(folder / "curves" / f"seed{k + 1}.csv", r.curve)
    rows = [f"seed{k + 1},{GEOMETRY}\n" for k in range(len(runs))]
    (folder / "specimens.csv").write_text(SPECIMENS + "".join(rows))
    return folder


@pytest.fixture(scope="module")
def runs(scenes, tmp_path_factory):
    scene = scenes / "measurements" / "tiny_bending.toml"
    return [shard.run(scene, out=tmp_path_factory.mktemp(f"seed{s}"), overrides={"simulation.seed": s}, threads=1)
            for s in (1, 2)]


@pytest.fixture(scope="module")
def measurements(runs, tmp_path_factory):
    return measurement_folder(tmp_path_factory.mktemp("meas") / "meas", runs)


@pytest.fixture(scope="module")
def self_comparison(runs, measurements):
    root = measurements.parent
    sims = [write_curve(root / f"sim{k + 1}.csv", r.curve) for k, r in enumerate(runs)]
    return shard.compare(measurements, out=root / "cmp", sim=sims)


def test_a_model_compared_with_its_own_curves_is_adequate(self_comparison):
    c = self_comparison
    assert isinstance(c, shard.Comparison)
    assert c.adequate
    assert c.nrmse == pytest.approx(0, abs=1e-6)
    for f in c.features.values():
        if math.isfinite(f.measured):
            assert f.simulated == pytest.approx(f.measured, rel=1e-6), f.name
    assert {"toe", "elastic", "peak"} <= set(c.regimes)
    assert not any(g.beyond_noise for g in c.regimes.values())


def test_the_peak_force_feature_is_the_mean_of_the_curves_peaks(self_comparison, runs):
    peak = self_comparison.features["peak_force"]
    assert peak.unit == "N"
    # compare.json prints 6 significant digits.
    assert peak.measured == pytest.approx(np.mean([r.peak_load for r in runs]), rel=1e-5)


def test_the_plot_data_comes_back_as_curves(self_comparison):
    curves = self_comparison.curves
    assert curves.individual.shape[0] == 4  # two specimens, then the same two as simulated replicates
    measured, simulated = curves.split(2)
    np.testing.assert_allclose(simulated, measured, rtol=1e-6, atol=1e-9)
    np.testing.assert_allclose(curves.measured_mean, measured.mean(axis=0), rtol=1e-5, atol=1e-6)
    assert np.all(np.diff(curves.w) > 0)
    np.testing.assert_allclose(curves.residual, 0, atol=1e-6)


def test_a_calibration_comes_back_with_its_curves(scenes, measurements, self_comparison):
    root = measurements.parent
    cal = shard.calibrate_effect(measurements, out=root / "cal", scene=scenes / "measurements" / "tiny_bending.toml",
                                 work=root / "work", seeds=1, workers=1, with_="machine_compliance",
                                 max_evaluations=2)
    assert isinstance(cal, shard.Calibration)
    assert cal.effect == "machine_compliance" and cal.evaluations == 2
    assert cal.chi_square_before > 0 and 0 < cal.nrmse_before < 1
    names, before, after = cal.regime_residuals()
    assert set(names) <= {"toe", "elastic", "pre-peak", "peak", "post-peak"} and len(before) == len(after) > 0
    # The same measurements on the same grid as the comparison's.
    np.testing.assert_allclose(cal.curves("before").measured_mean, self_comparison.curves.measured_mean, rtol=1e-5)
    assert cal.curves("after").individual.shape == (3, len(self_comparison.curves.w))  # 2 specimens, 1 seed


def test_a_result_folder_is_loaded_by_its_file_name(self_comparison, tmp_path):
    folder = tmp_path / "cmp"
    folder.mkdir()
    (folder / "compare.json").write_text(json.dumps(self_comparison.data))
    assert shard.load_result(folder).verdict == self_comparison.verdict


def test_non_finite_numbers_and_a_format_version_are_accepted(tmp_path):
    path = tmp_path / "calibrate.json"
    path.write_text('{"format_version": 1, "effect": "machine_compliance", "value": 2.9e-4, '
                    '"nrmse_before": nan, "nrmse_after": null, "chi_square_before": inf, '
                    '"chi_square_after": -inf, "regimes": {"toe": [0.5, null], "elastic": [1.5, -0.2]}, '
                    '"note": "a nan in text stays"}')
    cal = shard.load_result(path)
    assert isinstance(cal, shard.Calibration)
    assert cal.format_version == 1 and cal.effect == "machine_compliance"
    assert math.isnan(cal.nrmse_before) and math.isnan(cal.nrmse_after)
    assert cal.chi_square_before == math.inf and cal.chi_square_after == -math.inf
    assert cal.note == "a nan in text stays"
    names, before, after = cal.regime_residuals()
    assert names == ["toe", "elastic"]
    np.testing.assert_array_equal(before, [0.5, 1.5])
    assert math.isnan(after[0]) and after[1] == -0.2


def test_a_diagnosis_lists_its_tables_as_columns(tmp_path):
    path = tmp_path / "diagnose.json"
    path.write_text(json.dumps({
        "verdict": "machine_compliance", "chi_square": 98.9, "p_value": None,
        "ranking": [{"name": "machine_compliance", "score": 121.5, "explained": 0.78},
                    {"name": "support_friction", "score": 95.8, "explained": None}],
        "rivals": []}))
    d = shard.load_result(path)
    assert isinstance(d, shard.Diagnosis)
    assert math.isnan(d.p_value)
    ranking = d.table("ranking")
    assert list(ranking["name"]) == ["machine_compliance", "support_friction"]
    np.testing.assert_array_equal(ranking["score"], [121.5, 95.8])
    assert math.isnan(ranking["explained"][1])
    assert d.ranking[0].name == "machine_compliance"
    with pytest.raises(AttributeError, match="verdict"):
        d.no_such_field


def test_a_file_of_another_kind_is_refused_by_name(tmp_path):
    path = tmp_path / "compare.json"
    path.write_text("{not json")
    with pytest.raises(ValueError, match="compare.json:1"):
        shard.load_result(path)
    empty = tmp_path / "empty"
    empty.mkdir()
    with pytest.raises(FileNotFoundError, match="compare.json, diagnose.json"):
        shard.load_result(empty)


def test_keyword_options_become_the_commands_options():
    from shard.cli import _arguments
    assert _arguments({"work": "w", "param": ["a", "b"], "with_": "machine_compliance", "judge_fracture": True,
                       "quiet": False, "force_noise": 0.01}) == [
        "--work", "w", "--param", "a", "--param", "b", "--with", "machine_compliance", "--judge-fracture",
        "--force-noise", "0.01"]
    assert shard.cli_path().name == "shard"


def test_a_real_diagnosis_reads_as_columns():
    # `shard diagnose` of the tiny beam's tutorial measurements (hidden machine compliance), with
    # one packing seed and the base parameters E_b and sigma_crit.
    d = shard.load_result(Path(__file__).parent / "data" / "diagnose.json")
    assert d.verdict == "unexplained structured residual"
    ranking = d.table("ranking")
    assert list(ranking["name"][:3]) == ["bond_softening", "weibull_strength", "machine_compliance"]
    assert np.all(np.diff(ranking["score"]) <= 0)  # ranked by the score test
    assert ranking["at_bound"].dtype == bool and ranking["identifiable"].dtype == bool
    assert d.chi_square_unabsorbed < d.chi_square
    first = d.confirmations[0]
    assert "regime:elastic" in first.residual.keys()
    assert math.isnan(d.resized_p)  # null: no resized test was run
