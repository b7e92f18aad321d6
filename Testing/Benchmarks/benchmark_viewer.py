#!/usr/bin/python3
# SPDX-License-Identifier: GPL-3.0-or-later
"""Frame times of the magnifier with its inset off and on (both views drawn), on the culled GPU
warp: the patch mapped by the polynomial, occlusion culling on (vtkMesoAtomMapper's default).

The window shows the patch close up after a click, as a user sees it; each frame turns the
camera by one degree, so that culling works on every frame. With the inset on, the inset shows
the whole organelle with the same atoms; then, swapped (x), the window shows the organelle and
the inset the atoms. Prints one BENCH line per arrangement with the ratio to the inset off,
measured in the same run (medians over --frames frames, after one frame to warm up).

    benchmark_viewer.py [--membrane yiip|dppc] [--tiles 5] [--size 1024x768] [--frames 20]
    benchmark_viewer.py --smoke     (CI: the DPPC patch, 2 x 2 tiles, 320 x 240, 3 frames)
"""
import argparse
import os
import statistics
import time

from mesolens.lens import MembraneLens
from mesolens.viewer import LensViewer

DATA = os.environ.get("MESOLENS_DATA_DIR", "Data")
MEMBRANES = {"yiip": "yiip_popepopg.gro", "dppc": "dppc128_slipids_323K.gro"}


def frame_times(viewer, frames):
    """Median seconds per frame over `frames` frames, each turning the camera by one degree."""
    camera = viewer.lens.renderer.GetActiveCamera()
    viewer.window.Render()  # warm-up
    times = []
    for _ in range(frames):
        camera.Azimuth(1.0)
        viewer.lens.renderer.ResetCameraClippingRange()
        start = time.perf_counter()
        viewer.window.Render()
        times.append(time.perf_counter() - start)
    return statistics.median(times)


def main():
    parser = argparse.ArgumentParser(description=__doc__,
                                     formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--membrane", choices=sorted(MEMBRANES), default="yiip")
    parser.add_argument("--tiles", type=int, default=5)
    parser.add_argument("--size", default="1024x768")
    parser.add_argument("--frames", type=int, default=20)
    parser.add_argument("--smoke", action="store_true")
    args = parser.parse_args()
    if args.smoke:
        args.membrane, args.tiles, args.size, args.frames = "dppc", 2, "320x240", 3
    width, height = (int(v) for v in args.size.split("x"))

    lens = MembraneLens(os.path.join(DATA, "meshes", "mito5_outer_membrane.obj"),
                        os.path.join(DATA, "membranes", MEMBRANES[args.membrane]))
    lens.set_tiles(args.tiles)
    viewer = LensViewer(lens, (width, height), offscreen=True)
    viewer.status.VisibilityOff()  # its text changes with every frame time
    lens.place(lens.surface.GetOutput().GetPoint(1000))
    viewer.place_camera_at_patch()
    label = (f"input={args.membrane} {args.tiles}x{args.tiles} tiles "
             f"({lens.atom_count():,} atoms, GPU warp, culled) {width}x{height}")

    alone = frame_times(viewer, args.frames)
    viewer.show_inset(True)
    with_inset = frame_times(viewer, args.frames)
    viewer.swap_views()
    swapped = frame_times(viewer, args.frames)
    print(f"BENCH viewer-inset {label} | inset off {1e3 * alone:.1f} ms/frame | inset on, "
          f"organelle inset {1e3 * with_inset:.1f} ms/frame | ratio on/off "
          f"{with_inset / alone:.2f}")
    print(f"BENCH viewer-inset-swapped {label} | inset off {1e3 * alone:.1f} ms/frame | atoms in "
          f"the inset, organelle in the window {1e3 * swapped:.1f} ms/frame | ratio on/off "
          f"{swapped / alone:.2f}")


if __name__ == "__main__":
    main()
