"""Renders a frame of a many-body scene (scenes/plates_drop.toml, scenes/belt_to_chute.toml) as
ParaView opens its run.xmf: particles as spheres coloured by a per-particle field, `body` (which
body a sphere came from) or `fragment` (canonical fragment label). The frame is the last one unless
--time picks the nearest to a time. --view above (default) looks obliquely down on a floor, for
plates_drop; --view side looks from -y, slightly above, so belt_to_chute's belt, flight and chute
read left to right.

    xvfb-run -a -s "-screen 0 1600x900x24" pvpython docs/images/render_bodies.py \
        out/plates_drop/run.xmf body docs/images/plates_drop_body.png
    xvfb-run -a -s "-screen 0 1600x900x24" pvpython docs/images/render_bodies.py \
        out/belt_to_chute/run.xmf fragment docs/images/belt_to_chute_fragment.png --view side --time 0.4

Debian's ParaView renders through GLX only, hence xvfb-run (see render_broken_beam.py).
"""
import argparse
import sys

from paraview.simple import (ColorBy, CreateView, GetColorTransferFunction, Glyph, Render,
                             SaveScreenshot, Show, Text, XDMFReader)

WIDTH = 1600
# Per view: picture height (px) and the camera's offset from the centre along -y and +z (the
# projection is parallel, so only the direction matters).
VIEWS = {"above": (560, 0.6, 0.35), "side": (700, 3.0, 0.8)}
# Colour-blind-safe hues, repeated for labels past the palette.
COLOURS = [(0.0, 0.45, 0.70), (0.90, 0.62, 0.0), (0.0, 0.62, 0.45), (0.80, 0.40, 0.0),
           (0.80, 0.47, 0.65), (0.34, 0.71, 0.91), (0.94, 0.89, 0.26), (0.35, 0.35, 0.35)]


def main(xmf, field, png, when=None, view_name="above"):
    height, back, up = VIEWS[view_name]
    reader = XDMFReader(FileNames=[xmf])
    names = reader.GetProperty("GridInfo")[::2]
    reader.GridStatus = [n for n in names if n.split("[")[0] == "particles"]
    if field not in reader.PointArrayStatus:
        sys.exit(f"error: {xmf} has no '{field}' field")
    times = reader.TimestepValues
    last = times[-1] if when is None else min(times, key=lambda t: abs(t - when))
    view = CreateView("RenderView")
    view.ViewSize = [WIDTH, height]
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
    view.CameraPosition = [centre[0], centre[1] - back, centre[2] + up]
    view.CameraViewUp = [0.0, 0.0, 1.0]
    view.CameraParallelProjection = 1
    view.CameraParallelScale = 0.55 * (x1 - x0) * height / WIDTH  # the x extent with a 10 % margin
    Render(view)
    SaveScreenshot(png, view, ImageResolution=[WIDTH, height])
    print(f"wrote {png}: {xmf} at t = {last} s, {count} values of {field}")


if __name__ == "__main__":
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("xmf")
    parser.add_argument("field", choices=["body", "fragment"])
    parser.add_argument("png")
    parser.add_argument("--time", type=float, help="s; the nearest frame is drawn (default: the last)")
    parser.add_argument("--view", choices=sorted(VIEWS), default="above")
    args = parser.parse_args()
    main(args.xmf, args.field, args.png, args.time, args.view)
