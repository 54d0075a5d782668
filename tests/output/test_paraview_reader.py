"""ParaView reads run.xmf as Shard wrote run.h5.

Runs a scene that breaks bonds, opens its run.xmf with ParaView's XDMF reader (paraview.simple,
as a user's ParaView would), goes to the last time step and checks the particles (Polyvertex),
the surviving bonds (Polyline) and the point fields against run.h5 read independently with h5py.

    pvpython test_paraview_reader.py SHARD_EXECUTABLE SCENE WORK_FOLDER

Registered with ctest by tests/output/CMakeLists.txt when pvpython is found (Debian: paraview,
python3-paraview; h5py: python3-h5py, all from .ci/install-deps). Exit status 0 or 1.
"""
import shutil
import subprocess
import sys
from pathlib import Path

try:
    import h5py
    import numpy as np
    from paraview import servermanager
    from paraview.simple import XDMFReader
    from vtkmodules.util.numpy_support import vtk_to_numpy
    from vtkmodules.vtkCommonDataModel import VTK_POLY_LINE, VTK_POLY_VERTEX
except ImportError as error:
    sys.exit(f"error: {error}; run this with pvpython (Debian: apt-get install paraview "
             "python3-paraview python3-h5py, or bash .ci/install-deps)")

# The reader hands over the float64 datasets as float64 (checked below), so the values are the
# same bytes and agree exactly. The bound only allows for nothing: a float32 round trip anywhere
# on the way would show as ~1e-8 relative, four orders above it.
RELATIVE_TOLERANCE = 1e-12

failures = []


def check(condition, message):
    if not condition:
        failures.append(message)
        print(f"FAIL: {message}")
    return condition


def check_close(name, got, want):
    got, want = np.asarray(got), np.asarray(want)
    if not check(got.shape == want.shape, f"{name}: shape {got.shape}, run.h5 has {want.shape}"):
        return
    scale = float(np.max(np.abs(want))) if want.size else 0.0
    difference = float(np.max(np.abs(got - want))) if want.size else 0.0
    print(f"{name}: max |xmf - h5| = {difference:.3g} (scale {scale:.3g})")
    check(difference <= RELATIVE_TOLERANCE * scale,
          f"{name}: max difference {difference:.3g} exceeds {RELATIVE_TOLERANCE:g} x {scale:.3g}")


def check_equal(name, got, want):
    got, want = np.asarray(got), np.asarray(want)
    if check(got.shape == want.shape, f"{name}: shape {got.shape}, run.h5 has {want.shape}"):
        mismatches = int(np.count_nonzero(got != want))
        check(mismatches == 0, f"{name}: {mismatches} of {want.size} values differ from run.h5")


def run_scene(shard, scene, work):
    shutil.rmtree(work, ignore_errors=True)
    result = subprocess.run([shard, "run", scene, "--out", str(work), "--quiet"],
                            capture_output=True, text=True)
    if result.returncode != 0:
        sys.exit(f"error: shard run {scene} failed ({result.returncode}):\n{result.stderr}")


def read_h5(run_h5):
    """Frame times and the last frame's arrays, straight from the file."""
    with h5py.File(run_h5, "r") as f:
        names = sorted(f["frames"])
        times = [float(f["frames"][k].attrs["time"]) for k in names]
        first, last = f["frames"][names[0]], f["frames"][names[-1]]
        frame = {key: last[key][()] for key in
                 ("position", "velocity", "radius", "id", "material", "body", "fragment", "bonds")}
        frame["first_bonds"] = first["bonds"].shape[0]
    return times, frame


def blocks_by_name(data):
    """The leaf grids of the reader's output by grid name ('particles', 'bonds')."""
    found = {}
    for i in range(data.GetNumberOfBlocks()):
        block = data.GetBlock(i)
        if block is None:
            continue
        if block.IsA("vtkMultiBlockDataSet"):
            found.update(blocks_by_name(block))
        else:
            # The XDMF 2 reader appends the time-step index: "particles[10]".
            name = data.GetMetaData(i).Get(data.NAME()) if data.HasMetaData(i) else ""
            found[name.split("[")[0]] = block
    return found


def cells(grid):
    """(cell types, points per cell, flat connectivity) of an unstructured grid."""
    array = grid.GetCells()
    offsets = vtk_to_numpy(array.GetOffsetsArray())
    types = np.array([grid.GetCellType(c) for c in range(grid.GetNumberOfCells())])
    return types, np.diff(offsets), vtk_to_numpy(array.GetConnectivityArray())


def point_array(grid, name):
    array = grid.GetPointData().GetArray(name)
    if not check(array is not None, f"particles: no point field '{name}' in ParaView"):
        return None
    return vtk_to_numpy(array)


def main(shard, scene, work):
    work = Path(work)
    run_scene(shard, scene, work)
    times, h5 = read_h5(work / "run.h5")
    n, m = h5["radius"].shape[0], h5["bonds"].shape[0]
    labels = np.unique(h5["fragment"])
    print(f"run.h5: {len(times)} frames; last frame {n} particles, {m} bonds "
          f"(first frame {h5['first_bonds']}), {labels.size} fragments")
    # Without a break the bond count and fragment labels would not tell the frames apart.
    if not (m < h5["first_bonds"] and labels.size >= 2):
        sys.exit(f"error: {scene} broke no bond by its last frame; the test needs a scene that breaks")

    reader = XDMFReader(FileNames=[str(work / "run.xmf")])
    # Written with %.17g, the times parse back to the same doubles.
    check_equal("time steps", np.array(reader.TimestepValues, dtype=float), np.array(times))
    reader.UpdatePipeline(times[-1])
    grids = blocks_by_name(servermanager.Fetch(reader))
    if not check("particles" in grids and "bonds" in grids,
                 f"the last time step holds the grids {sorted(grids)}, not particles and bonds"):
        return

    particles, bonds = grids["particles"], grids["bonds"]
    check(particles.GetNumberOfPoints() == n,
          f"particles: {particles.GetNumberOfPoints()} points, run.h5 has {n}")
    types, sizes, connectivity = cells(particles)
    check(particles.GetNumberOfCells() == n and np.all(types == VTK_POLY_VERTEX) and np.all(sizes == 1),
          f"particles: expected {n} one-point Polyvertex cells, got {particles.GetNumberOfCells()} cells")
    check_equal("particle cell points", connectivity, np.arange(n))
    check(particles.GetPoints().GetDataType() == 11,  # VTK_DOUBLE
          f"particle positions arrive as VTK type {particles.GetPoints().GetDataType()}, not double")
    check_close("position", vtk_to_numpy(particles.GetPoints().GetData()), h5["position"])
    for name, exact in (("radius", False), ("velocity", False), ("id", True), ("material", True),
                        ("body", True), ("fragment", True)):
        values = point_array(particles, name)
        if values is not None:
            (check_equal if exact else check_close)(name, values, h5[name])

    check(bonds.GetNumberOfCells() == m, f"bonds: {bonds.GetNumberOfCells()} cells, run.h5 has {m}")
    types, sizes, connectivity = cells(bonds)
    check(np.all(types == VTK_POLY_LINE) and np.all(sizes == 2),
          "bonds: not every cell is a two-point Polyline")
    check_equal("bond end points", connectivity, h5["bonds"].reshape(-1))
    check_close("bond grid positions", vtk_to_numpy(bonds.GetPoints().GetData()), h5["position"])


if __name__ == "__main__":
    if len(sys.argv) != 4:
        sys.exit(__doc__)
    main(*sys.argv[1:])
    if failures:
        sys.exit(f"{len(failures)} check(s) failed")
    print("ParaView reads the last frame of run.xmf as run.h5 holds it")
