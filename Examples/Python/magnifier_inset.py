#!/usr/bin/python3
# SPDX-License-Identifier: GPL-3.0-or-later
"""Both scales at once: the whole mitochondrion in the window, the DPPC bilayer mapped onto it
at atomic scale in an inset, the lens outlined on the organelle.

The magnifier (mesolens.viewer.LensViewer) driven from Python: a click on the organelle maps
the patch there and the camera flies to it; fly_to_cell() flies back to the whole organelle,
show_inset(True) adds the inset, which shows the scale the window does not. Without --output
the window stays open for interaction (f, b, x, the wheel: see mesolens.viewer).

    magnifier_inset.py [--output inset.png] [--size 400x300] [--tiles 2] [--swap]

--swap shows the atoms in the window and the organelle in the inset (key x).
"""
import argparse
import os

from mesolens.lens import MembraneLens, write_png
from mesolens.viewer import LensViewer

DATA = os.environ.get("MESOLENS_DATA_DIR",
                      os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "Data"))


def main():
    parser = argparse.ArgumentParser(description=__doc__,
                                     formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--output", help="write the picture here instead of opening a window")
    parser.add_argument("--size", default="400x300", help="WIDTHxHEIGHT (400x300)")
    parser.add_argument("--tiles", type=int, default=2, help="k x k tiles (2)")
    parser.add_argument("--swap", action="store_true", help="the atoms in the window")
    args = parser.parse_args()
    width, height = (int(v) for v in args.size.split("x"))

    lens = MembraneLens(os.path.join(DATA, "meshes", "mito5_outer_membrane.obj"),
                        os.path.join(DATA, "membranes", "dppc128_slipids_323K.gro"))
    lens.set_tiles(args.tiles)
    viewer = LensViewer(lens, (width, height), offscreen=bool(args.output))
    # Look at the organelle from the side of its vertex 1000, then click there.
    surface = lens.surface.GetOutput()
    target = surface.GetPoint(1000)
    centre = surface.GetCenter()
    camera = lens.renderer.GetActiveCamera()
    camera.SetFocalPoint(target)
    camera.SetPosition([target[d] + 3.0 * (target[d] - centre[d]) for d in range(3)])
    camera.SetViewUp(0, 0, 1)
    lens.renderer.ResetCameraClippingRange()
    viewer.window.Render()
    lens.renderer.SetWorldPoint(*target, 1.0)
    lens.renderer.WorldToDisplay()
    x, y, _ = lens.renderer.GetDisplayPoint()
    if not viewer.click(int(round(x)), int(round(y))):
        raise SystemExit(f"magnifier_inset: {viewer.message}")
    viewer.fly_to_cell(animate=False)
    viewer.show_inset(True)
    if args.swap:
        viewer.swap_views()
    scale, per_pixel = viewer.scale_shown()
    print(f"{lens.atom_count()} atoms mapped; the window shows the {scale} "
          f"({per_pixel:.3g} Å per pixel), the inset the other scale")
    if args.output:
        viewer.status.VisibilityOff()  # a picture without the status lines (frame times vary)
        write_png(viewer.window, args.output)
    else:
        viewer.start()


if __name__ == "__main__":
    main()
