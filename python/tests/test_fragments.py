"""Fragments and size distributions: a hand-made frame with known pieces, and a many-body scene
whose six bodies are six fragments before they land."""
import math
import subprocess
import sys
from pathlib import Path
from types import SimpleNamespace

import numpy as np
import pytest

import shard


def frame_of(radius, bonds, body=None):
    n = len(radius)
    radius = np.asarray(radius, dtype=float)
    return SimpleNamespace(id=np.arange(n, dtype=np.int32), position=np.zeros((n, 3)) + np.arange(n)[:, None],
                           velocity=np.zeros((n, 3)), radius=radius, mass=1000 * 4 / 3 * math.pi * radius ** 3,
                           body=np.zeros(n, dtype=np.int32) if body is None else np.asarray(body, dtype=np.int32),
                           bonds=np.asarray(bonds, dtype=np.int32).reshape(-1, 2))


def test_connected_components_heaviest_first():
    # Particles 0-1-2 bonded (three of radius 1), 3-4 bonded (radius 2): the pair is heavier.
    frame = frame_of([1, 1, 1, 2, 2], [[0, 1], [1, 2], [3, 4]])
    pieces = shard.fragments(frame)
    assert len(pieces) == 2
    np.testing.assert_array_equal(pieces.labels, [1, 1, 1, 0, 0])
    np.testing.assert_array_equal(pieces.particles, [2, 3])
    v_pair, v_chain = 2 * 4 / 3 * math.pi * 8, 3 * 4 / 3 * math.pi
    np.testing.assert_allclose(pieces.volume, [v_pair, v_chain], rtol=1e-12)
    np.testing.assert_allclose(pieces.d_eq, np.cbrt(6 / math.pi * np.array([v_pair, v_chain])), rtol=1e-12)
    np.testing.assert_allclose(pieces.centre[0], [3.5, 3.5, 3.5], rtol=1e-12)


def test_size_distribution_interpolates_in_mass_fraction():
    # Two fragments of d = 1 and 3 m with masses 1 and 3 kg: Q = 0.25 at d = 1, 1 at d = 3.
    fsd = shard.size_distribution([3.0, 1.0], [3.0, 1.0])
    np.testing.assert_array_equal(fsd.d, [1.0, 3.0])
    np.testing.assert_allclose(fsd.cumulative, [0.25, 1.0])
    assert fsd.x10 == 1.0  # below the first point: the smallest size
    assert fsd.x50 == pytest.approx(1 + (0.5 - 0.25) / 0.75 * 2)
    assert fsd.characteristic_size(0.9) == pytest.approx(fsd.x90)
    fines = shard.size_distribution([3.0, 1.0], [3.0, 1.0], fines_size=2.0)
    assert fines.fines_fraction == pytest.approx(0.25)


def test_bad_arrays_are_refused_with_the_reason():
    frame = frame_of([1, 1], [[0, 5]])
    with pytest.raises(ValueError, match="5"):
        shard.fragments(frame)
    with pytest.raises(ValueError, match="p must lie"):
        shard.size_distribution([1.0], [1.0]).characteristic_size(0)


@pytest.fixture(scope="module")
def falling(scenes, tmp_path_factory):
    # Stopped long before the first shard reaches the floor (~35 ms).
    return shard.run(scenes / "plates_drop.toml", out=tmp_path_factory.mktemp("plates"),
                     overrides={"simulation.duration": 0.002}, threads=1)


def test_six_falling_bodies_are_six_unbroken_fragments(falling):
    with falling.open() as f:
        frame = f.frame(-1)
        from_file = f.body_statistics()
    pieces = shard.fragments(frame)
    assert len(pieces) == 6
    assert sorted(pieces.body.tolist()) == [0, 1, 2, 3, 4, 5]
    bodies = shard.body_statistics(frame)
    np.testing.assert_array_equal(bodies.body, [0, 1, 2, 3, 4, 5])
    np.testing.assert_array_equal(bodies.fragments, 1)
    np.testing.assert_allclose(bodies.largest_fraction, 1.0)
    assert bodies.broken_count == 0 and bodies.breakage_probability == 0 and not bodies.broken.any()
    assert bodies.pooled.total_mass == pytest.approx(frame.total_mass, rel=1e-12)
    # Read from the run file, the same statistics, and no shard has touched the floor yet.
    np.testing.assert_array_equal(from_file.mass, bodies.mass)
    assert not from_file.impacted.any()


def test_the_table_is_the_one_shard_fragments_stores(falling):
    shard.run_cli("fragments", falling.run_file, write_labels=True)
    with falling.open() as f:
        frame = f.frame(-1)
        stored = f.table(f"fragments/{frame.number:06d}")
    pieces = shard.fragments(frame)
    for name in ("particles", "mass", "volume", "d_eq", "centre", "velocity", "box_min", "box_max", "body"):
        np.testing.assert_array_equal(stored[name], getattr(pieces, name), err_msg=name)
    assert stored["attributes"]["x50"] == pieces.size_distribution().x50


def test_plugins_are_searched_where_the_command_searches(tmp_path):
    path = shard.plugin_search_path([tmp_path])
    assert path[0] == tmp_path
    assert any(sorted(p.glob("shard_*.so")) for p in path if p.is_dir())


def test_the_size_distribution_example_draws_its_figure(falling, tmp_path):
    example = Path(__file__).resolve().parents[1] / "examples" / "fragment_size_distribution.py"
    png = tmp_path / "fsd.png"
    done = subprocess.run([sys.executable, str(example), "--run", str(falling.run_file), "--png", str(png)],
                          capture_output=True, text=True, check=True)
    assert "1146 particles, 6 fragments" in done.stdout
    assert png.stat().st_size > 10_000
