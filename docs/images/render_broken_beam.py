"""Renders the last frame of a four-point bending run, as ParaView opens its run.xmf: particles
as spheres (at 0.6 of their radius) coloured by fragment label, the surviving bonds as lines, seen along
the beam's width (y) so the crack and both halves show.

    xvfb-run -a -s "-screen 0 1600x900x24" pvpython docs/images/render_broken_beam.py \
        out/four_point_bending/run.xmf docs/images/four_point_bending_broken.png

The run must carry fragment labels in its frames (`[analysis] fragments_every` > 0, e.g.
`--set analysis.fragments_every=1`). Debian's ParaView renders through GLX only, hence xvfb-run
(Debian: xvfb, xauth; both in .ci/install-deps).
"""
import sys

from paraview.simple import (ColorBy, CreateView, GetColorTransferFunction, Glyph, Render,
                             SaveScreenshot, Show, Text, XDMFReader)

WIDTH, HEIGHT = 1600, 520
# Spheres drawn at their full radius hide the bonds between them (bonds join the centres of
# touching spheres); at 0.6 of it each bond shows as a short line between neighbours.
SPHERE_SCALE = 0.6
# Fragment labels are canonical (0 the heaviest, docs/reference/fragments.md): the two halves are 0 and 1,
# then chips. Distinct, colour-blind-safe hues for the first labels, grey for the rest.
FRAGMENT_COLOURS = [(0.0, 0.45, 0.70), (0.90, 0.62, 0.0), (0.0, 0.62, 0.45),
                    (0.80, 0.40, 0.0), (0.80, 0.47, 0.65), (0.34, 0.71, 0.91)]
CHIP_COLOUR = (0.6, 0.6, 0.6)


def grid_reader(xmf, grid):
    """A reader of run.xmf that loads only the grids named `grid` ('particles' or 'bonds'); the
    XDMF 2 reader names the grids of time step k 'grid[k]'."""
    reader = XDMFReader(FileNames=[xmf])
    names = reader.GetProperty("GridInfo")[::2]
    reader.GridStatus = [n for n in names if n.split("[")[0] == grid]
    return reader


def main(xmf, png):
    particles = grid_reader(xmf, "particles")
    if "fragment" not in particles.PointArrayStatus:
        sys.exit(f"error: {xmf} has no 'fragment' field: run the scene with "
                 "--set analysis.fragments_every=1 (or [analysis] fragments_every = 1)")
    last = particles.TimestepValues[-1]
    bonds = grid_reader(xmf, "bonds")

    view = CreateView("RenderView")
    view.ViewSize = [WIDTH, HEIGHT]
    view.ViewTime = last
    view.OrientationAxesVisibility = 1
    view.Background = [1.0, 1.0, 1.0]
    view.UseColorPaletteForBackground = 0

    spheres = Glyph(Input=particles, GlyphType="Sphere")
    spheres.ScaleArray = ["POINTS", "radius"]
    spheres.ScaleFactor = 2.0 * SPHERE_SCALE  # the glyph sphere has radius 0.5
    spheres.GlyphMode = "All Points"
    spheres.GlyphType.ThetaResolution = 16
    spheres.GlyphType.PhiResolution = 12
    shown = Show(spheres, view)
    ColorBy(shown, ("POINTS", "fragment"))
    lut = GetColorTransferFunction("fragment")
    lut.InterpretValuesAsCategories = 1
    particles.UpdatePipeline(last)
    count = int(particles.PointData["fragment"].GetRange()[1]) + 1
    lut.Annotations = sum(([str(k), f"fragment {k}" if k < 2 else ""] for k in range(count)), [])
    colours = [FRAGMENT_COLOURS[k] if k < len(FRAGMENT_COLOURS) else CHIP_COLOUR
               for k in range(count)]
    lut.IndexedColors = [c for colour in colours for c in colour]
    shown.SetScalarBarVisibility(view, False)

    lines = Show(bonds, view)
    lines.DiffuseColor = lines.AmbientColor = [0.15, 0.15, 0.15]
    lines.ColorArrayName = ["POINTS", ""]
    lines.LineWidth = 2.0

    label = Text(Text=f"t = {last:.3f} s, seen along the width: {count} fragments (the halves blue and "
                      "orange, chips grey or coloured); lines: surviving bonds; spheres at "
                      f"{SPHERE_SCALE:g} r")
    caption = Show(label, view)
    caption.Color = [0.1, 0.1, 0.1]
    caption.FontSize = 20
    caption.WindowLocation = "Upper Center"

    # Along the width: look in +y with z up, in parallel projection, framing the beam's x-z extent
    # with a 5 % margin. After a first render, which resets the camera to its own fit.
    Render(view)
    x0, x1, _, _, z0, z1 = particles.GetDataInformation().GetBounds()
    centre = [(x0 + x1) / 2, 0.0, (z0 + z1) / 2]
    view.CameraFocalPoint = centre
    view.CameraPosition = [centre[0], centre[1] - 1.0, centre[2]]
    view.CameraViewUp = [0.0, 0.0, 1.0]
    view.CameraParallelProjection = 1
    view.CameraParallelScale = 1.05 * max((z1 - z0) / 2, (x1 - x0) / 2 * HEIGHT / WIDTH)
    Render(view)
    SaveScreenshot(png, view, ImageResolution=[WIDTH, HEIGHT])
    print(f"wrote {png}: {xmf} at t = {last} s, {count} fragments")


if __name__ == "__main__":
    if len(sys.argv) != 3:
        sys.exit(__doc__)
    main(*sys.argv[1:])
