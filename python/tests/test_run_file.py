"""shard.RunFile on a settling box (unbonded spheres poured onto a floor): frames, series, walls.
The box is filled to 25 mm instead of 50 mm and run for 0.2 s instead of 0.3 s: 754 spheres that
are at rest at the end (kinetic energy 8e-6 of its peak, the floor force 1.3 % above the weight)."""
import math

import numpy as np
import pytest

import shard

DENSITY = 3720.0  # kg/m^3, scenes/settling_box.toml
GRAVITY = 9.81


@pytest.fixture(scope="module")
def box(scenes, tmp_path_factory):
    result = shard.run(scenes / "settling_box.toml", out=tmp_path_factory.mktemp("box"), threads=1,
                       overrides={"generator.max_corner": [0.03, 0.03, 0.025], "simulation.duration": 0.2})
    with shard.RunFile(result.run_file) as f:
        yield result, f


def test_every_frame_keeps_the_particles_and_their_mass(box):
    result, f = box
    assert len(f) >= 2
    first = f.frame(0)
    assert len(first) == result.particles
    # Masses are rho 4/3 pi r^3 of the scene's density.
    np.testing.assert_allclose(first.mass, DENSITY * 4 / 3 * math.pi * first.radius ** 3, rtol=1e-12)
    for frame in f.frames():
        np.testing.assert_array_equal(np.sort(frame.id), np.sort(first.id))
        assert frame.total_mass == pytest.approx(first.total_mass, rel=1e-12)


def test_unbonded_spheres_are_one_fragment_each(box):
    _, f = box
    last = f.frame(-1)
    assert last.bonds.shape == (0, 2)
    pieces = last.fragments()
    assert len(pieces) == len(last)
    np.testing.assert_array_equal(pieces.particles, 1)
    # Each fragment's equivalent diameter is its sphere's.
    np.testing.assert_allclose(np.sort(pieces.d_eq), np.sort(2 * last.radius), rtol=1e-12)


def test_the_spheres_come_to_rest_on_the_floor(box):
    _, f = box
    series = f.series()
    last = f.frame(-1)
    # Settled: the kinetic energy is a small part of its peak during the fall.
    assert series["kinetic_energy"][-1] < 0.01 * series["kinetic_energy"].max()
    # No sphere sank through the floor by more than a tenth of its radius.
    assert np.all(last.position[:, 2] - last.radius > -0.1 * last.radius)
    # The floor carries the weight.
    floor = f.wall("floor")["force"][-1]
    assert -floor[2] == pytest.approx(last.total_mass * GRAVITY, rel=0.05)


def test_the_walls_are_the_scenes(box):
    _, f = box
    assert sorted(f.wall_names) == ["floor", "x_high", "x_low", "y_high", "y_low"]
    assert len(f.wall("floor")["force"]) == len(f.series()["time"])


def test_the_file_records_the_resolved_scene(box):
    result, f = box
    meta = f.metadata()
    assert "settling_box.toml" in meta["scene_file"]
    assert "hertz_mindlin" in meta["scene"]
    assert meta["seed"] == 1
    assert f.break_events()["time"].shape == (0,)


def test_a_closed_file_says_so(box, scenes, tmp_path):
    result, _ = box
    f = shard.RunFile(result.run_file)
    f.close()
    with pytest.raises(ValueError, match="closed"):
        f.frame(0)


def test_a_missing_file_is_named(tmp_path):
    with pytest.raises(shard.OutputError, match="nothing.h5"):
        shard.RunFile(tmp_path / "nothing.h5")
