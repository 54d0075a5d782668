"""shard.run on the CI-size four-point bending beam, made short as the MPI run test makes it (pins
ten times faster, weaker bonds, no damping): the result, the file and the CSV agree."""
import os
import signal
import threading
import time

import numpy as np
import pytest

import shard


@pytest.fixture(scope="module")
def bending(scenes, tmp_path_factory):
    out = tmp_path_factory.mktemp("bending")
    # Fragments labelled in every frame, so the stored labels can be checked against the analysis.
    return shard.run(scenes / "four_point_bending_ci.toml", out=out, threads=1, overrides=SHORT)


SHORT = {"bond.youngs_modulus": 13e6, "bond.critical_stress": 0.05e6, "simulation.global_damping": 0,
         "wall.pin_left.velocity": [0, 0, -0.1], "wall.pin_right.velocity": [0, 0, -0.1],
         "simulation.duration": 0.03, "analysis.fragments_every": 1}


def test_the_run_ends_where_the_scene_says(bending):
    assert bending.run_file.name == "run.h5" and bending.run_file.is_file()
    assert bending.stop in ("load_drop", "max_displacement", "duration")
    assert bending.bonds_broken > 0  # the beam failed


def test_the_override_reached_the_bond_law(bending):
    with bending.open() as f:
        meta = f.metadata()
    # "version=...; youngs_modulus=13000000; ..."
    law = dict(item.split("=", 1) for item in meta["plugins"]["bond/beam_bond"].split("; "))
    assert float(law["youngs_modulus"]) == 13e6
    assert float(law["critical_stress"]) == 0.05e6


def test_the_load_curve_has_one_row_per_series_row(bending):
    with bending.open() as f:
        series = f.series()
    assert len(bending.curve) == len(series["time"])
    np.testing.assert_array_equal(bending.curve.time, series["time"])
    assert bending.peak_load == bending.curve.load.max()
    k = int(np.argmax(bending.curve.load))
    assert bending.displacement_at_peak == bending.curve.displacement[k]


def test_the_curve_csv_holds_the_returned_curve(bending):
    table = np.loadtxt(bending.curve_csv, delimiter=",", skiprows=1, ndmin=2)
    # The CSV prints each figure to at least 6 significant digits.
    np.testing.assert_allclose(table[:, 1], bending.curve.displacement, rtol=1e-5, atol=1e-12)
    np.testing.assert_allclose(table[:, 2], bending.curve.load, rtol=1e-5, atol=1e-9 * bending.peak_load)


def test_bond_counts_agree_between_result_series_events_and_frames(bending):
    with bending.open() as f:
        series = f.series()
        events = f.break_events()
        first, last = f.frame(0), f.frame(-1)
    assert len(first.bonds) == bending.bonds_initial
    assert series["bonds_broken"][-1] == bending.bonds_broken == len(events["time"])
    assert series["bonds_intact"][-1] == len(last.bonds) == bending.bonds_initial - bending.bonds_broken
    # Every series row: intact + broken is the initial count.
    np.testing.assert_array_equal(series["bonds_intact"] + series["bonds_broken"], bending.bonds_initial)
    assert np.all(np.diff(events["time"]) >= 0)
    assert set(np.unique(events["mode"])) <= {1, 2, 3, 4}


def test_mass_is_conserved_between_frames(bending):
    with bending.open() as f:
        first, last = f.frame(0), f.frame(-1)
    assert len(first) == len(last) == bending.particles
    np.testing.assert_array_equal(np.sort(first.id), np.sort(last.id))
    assert last.total_mass == pytest.approx(first.total_mass, rel=1e-12)


def test_stored_labels_are_the_analysis_labels(bending):
    with bending.open() as f:
        last = f.frame(-1)
    pieces = shard.fragments(last)
    np.testing.assert_array_equal(last.fragment, pieces.labels)
    # The driver's count per fragment, largest first, is the table's.
    np.testing.assert_array_equal(bending.fragment_particles, np.sort(pieces.particles)[::-1])
    assert pieces.mass.sum() == pytest.approx(last.total_mass, rel=1e-12)
    assert len(pieces) >= 2  # a failed beam is in pieces


def test_a_mistyped_key_is_refused_by_name(scenes, tmp_path):
    with pytest.raises(shard.SceneError, match="youngs_modulu"):
        shard.run(scenes / "four_point_bending_ci.toml", out=tmp_path, overrides={"bond.youngs_modulu": 1e7})


def test_key_value_strings_are_parsed_as_set_parses_them(scenes, tmp_path):
    with pytest.raises(shard.SceneError, match=r"\[simulation\] duration = -1"):
        shard.run(scenes / "four_point_bending_ci.toml", out=tmp_path, overrides=["simulation.duration=-1"])


def test_a_value_of_no_scene_type_is_refused_by_key(scenes, tmp_path):
    with pytest.raises(TypeError, match="bond.youngs_modulus"):
        shard.run(scenes / "four_point_bending_ci.toml", out=tmp_path, overrides={"bond.youngs_modulus": {"a": 1}})


def test_a_run_continues_from_its_checkpoint(scenes, tmp_path):
    first = shard.run(scenes / "four_point_bending_ci.toml", out=tmp_path, threads=1,
                      overrides={**SHORT, "simulation.duration": 0.004})
    assert first.stop == "duration" and first.checkpoint is not None
    more = shard.run(restart=first.run_file, out=tmp_path, threads=1, overrides={"simulation.duration": 0.008})
    assert more.restarted_from == first.checkpoint_step
    assert more.steps > first.steps
    straight = shard.run(scenes / "four_point_bending_ci.toml", out=tmp_path / "straight", threads=1,
                         overrides={**SHORT, "simulation.duration": 0.008})
    assert (more.steps, more.time) == (straight.steps, straight.time)
    with more.open() as f:
        time = f.series()["time"]
    assert np.all(np.diff(time) > 0)  # one series, continued
    assert time[-1] == more.time


def test_ctrl_c_stops_the_run_with_a_checkpoint(scenes, tmp_path):
    # The beam at its own rate runs ~100 000 steps; the signal comes once the run file exists. The
    # thread that sends it runs only because the run released the GIL.
    def interrupt_once_running():
        while not (tmp_path / "run.h5").exists():
            time.sleep(0.01)
        os.kill(os.getpid(), signal.SIGINT)

    threading.Thread(target=interrupt_once_running, daemon=True).start()
    with pytest.raises(shard.RunInterrupted) as caught:
        shard.run(scenes / "four_point_bending_ci.toml", out=tmp_path, threads=1)
    r = caught.value.result
    assert r.stop == "interrupted"
    assert r.checkpoint.is_file() and r.checkpoint_step == r.steps
    assert r.time < 1.2  # the scene's duration
