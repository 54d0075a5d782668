"""Renders a frame of scenes/belt_to_chute.toml as ParaView opens its run.xmf: particles as spheres
coloured by a per-particle field, `body` (which plate a sphere came from) or `fragment` (canonical
fragment label), seen from the side (-y, slightly above) so the belt's plates, the flight and the
chute read left to right. The time is the last frame unless given.

    xvfb-run -a -s "-screen 0 1600x900x24" pvpython docs/images/render_belt_to_chute.py \
        out/belt_to_chute/run.xmf body docs/images/belt_to_chute_body.png [time_s]
    xvfb-run -a -s "-screen 0 1600x900x24" pvpython docs/images/render_belt_to_chute.py \
        out/belt_to_chute/run.xmf fragment docs/images/belt_to_chute_fragment.png [time_s]

Debian's ParaView renders through GLX only, hence xvfb-run (see render_broken_beam.py).
"""
import sys

from paraview.simple import (ColorBy, CreateView, GetColorTransferFunction, Glyph, Render,
                             SaveScreenshot, Show, Text, XDMFReader)

WIDTH, HEIGHT = 1600, 700
# Colour-blind-safe hues, repeated for labels past the palette.
COLOURS = [(0.0, 0.45, 0.70), (0.90, 0.62, 0.0), (0.0, 0.62, 0.45), (0.80, 0.40, 0.0),
           (0.80, 0.47, 0.65), (0.34, 0.71, 0.91), (0.94, 0.89, 0.26), (0.35, 0.35, 0.35)]


def main(xmf, field, png, when=None):
    reader = XDMFReader(FileNames=[xmf])
    names = reader.GetProperty("GridInfo")[::2]
    reader.GridStatus = [n for n in names if n.split("[")[0] == "particles"]
    if field not in reader.PointArrayStatus:
        sys.exit(f"error: {xmf} has no '{field}' field")
    times = reader.TimestepValues
    last = times[-1] if when is None else min(times, key=lambda t: abs(t - float(when)))
    view = CreateView("RenderView")
    view.ViewSize = [WIDTH, HEIGHT]
    view.ViewTime = last
    view.Background = [1.0, 1.0, 1.0]
    view.UseColorPaletteForBackground = 0
    spheres = Glyph(Input=reader, GlyphType="Sphere")
    spheres.ScaleArray = ["POINTS", "radius"]
    spheres.ScaleFactor = 2.0  # the glyph sphere has radius 0.5: drawn at the particle's radius
    spheres.GlyphMode = "All Points"
    spheres.GlyphType.ThetaResolution = 16
    spheres.GlyphType.PhiResolution = 12
    shown = Show(spheres, view)
    ColorBy(shown, ("POINTS", field))
    lut = GetColorTransferFunction(field)
    lut.InterpretValuesAsCategories = 1
    reader.UpdatePipeline(last)
    count = int(reader.PointData[field].GetRange()[1]) + 1
    lut.Annotations = sum(([str(k), ""] for k in range(count)), [])
    lut.IndexedColors = [c for k in range(count) for c in COLOURS[k % len(COLOURS)]]
    shown.SetScalarBarVisibility(view, False)
    what = f"{count} bodies" if field == "body" else f"{count} fragments (colours repeat)"
    caption = Show(Text(Text=f"t = {last:.3f} s, coloured by {field}: {what}"), view)
    caption.Color = [0.1, 0.1, 0.1]
    caption.FontSize = 20
    caption.WindowLocation = "Upper Center"
    Render(view)
    x0, x1, y0, y1, z0, z1 = reader.GetDataInformation().GetBounds()
    centre = [(x0 + x1) / 2, (y0 + y1) / 2, (z0 + z1) / 2]
    view.CameraFocalPoint = centre
    view.CameraPosition = [centre[0], centre[1] - 3.0, centre[2] + 0.8]
    view.CameraViewUp = [0.0, 0.0, 1.0]
    view.CameraParallelProjection = 1
    view.CameraParallelScale = 0.55 * (x1 - x0) * HEIGHT / WIDTH  # the x extent with a 10 % margin
    Render(view)
    SaveScreenshot(png, view, ImageResolution=[WIDTH, HEIGHT])
    print(f"wrote {png}: {xmf} at t = {last} s, {count} values of {field}")


if __name__ == "__main__":
    if len(sys.argv) not in (4, 5):
        sys.exit(__doc__)
    main(*sys.argv[1:])
