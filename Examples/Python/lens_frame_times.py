#!/usr/bin/python3
# SPDX-License-Identifier: GPL-3.0-or-later
"""Frame times of the magnifier for 1 x 1 ... 15 x 15 tiles, in the shape of Table 1 of the
membrane-mapping paper: static and animated, space-filling and ball-and-stick, without and with
ambient occlusion, on this machine.

The patch is the YiiP transporter in its POPE/POPG bilayer (43 480 atoms, 5 frames; the paper's
patch had ~46 k), mapped by the polynomial onto the mitochondrion's outer membrane and warped on
the GPU (vtkMesoAtomMapper); "animated" shows the next trajectory frame before every frame.
Times are medians over --frames frames in an offscreen window, after one frame to warm up.

    lens_frame_times.py [--tiles 1,3,5,7,9,11,13,15] [--frames 3] [--size 1024x768]
"""
import argparse
import os
import statistics
import time

from vtkmodules.vtkRenderingCore import vtkRenderWindow
import vtkmodules.vtkRenderingOpenGL2  # noqa: F401

from mesolens import vtkMesoRenderPasses
from mesolens.lens import MembraneLens

DATA = os.environ.get("MESOLENS_DATA_DIR",
                      os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "Data"))


def main():
    parser = argparse.ArgumentParser(description=__doc__,
                                     formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--tiles", default="1,3,5,7,9,11,13,15")
    parser.add_argument("--frames", type=int, default=3)
    parser.add_argument("--size", default="1024x768")
    args = parser.parse_args()
    tiles = [int(k) for k in args.tiles.split(",")]
    width, height = (int(v) for v in args.size.split("x"))

    lens = MembraneLens(os.path.join(DATA, "meshes", "mito5_outer_membrane.obj"),
                        os.path.join(DATA, "membranes", "yiip_popepopg.gro"),
                        os.path.join(DATA, "membranes", "yiip_popepopg.xtc"))
    centre = lens.surface.GetOutput().GetPoint(1000)
    steps = lens.time_steps()
    window = vtkRenderWindow()
    window.SetOffScreenRendering(1)
    window.SetMultiSamples(0)
    window.SetSize(width, height)
    window.AddRenderer(lens.renderer)
    # Ambient occlusion sized to one tile, whatever the number of tiles.
    effects = vtkMesoRenderPasses()
    effects.SetSSAOKernelSize(32)
    effects.SSAOBlurOn()

    def frame_time(animated):
        times = []
        step = 0
        for _ in range(args.frames + 1):
            if animated:
                step = (step + 1) % len(steps)
                lens.set_time(steps[step])
            start = time.perf_counter()
            window.Render()
            window.WaitForCompletion()
            times.append(time.perf_counter() - start)
        lens.set_time(steps[0])
        return statistics.median(times[1:])

    columns = [(style, ao, animated) for style in ("space-filling", "ball-and-stick")
               for ao in (False, True) for animated in (False, True)]
    print(f"Frame time (ms), {width}x{height}, Mesa llvmpipe, medians of {args.frames} frames")
    print("| tiles | atoms | " + " | ".join(
        f"{'SF' if s == 'space-filling' else 'BS'}{' +AO' if ao else ''} "
        f"{'animated' if a else 'static'}" for s, ao, a in columns) + " |")
    print("|---" * (2 + len(columns)) + "|")
    for k in tiles:
        lens.set_tiles(k)
        lens.place(centre)
        lens.look_at_patch()
        extent = max(lens.atoms.GetBounds()[2 * d + 1] - lens.atoms.GetBounds()[2 * d]
                     for d in range(3))
        effects.SetSSAORadius(0.05 * extent / k)
        effects.SetSSAOBias(0.005 * extent / k)
        row = []
        for style, ao, animated in columns:
            lens.set_style(style)
            effects.SetSSAO(ao)
            effects.Apply(lens.renderer)
            row.append(f"{1000 * frame_time(animated):.0f}")
        print(f"| {k}x{k} | {lens.atom_count():,} | " + " | ".join(row) + " |", flush=True)
    effects.SSAOOff()
    effects.Apply(lens.renderer)


if __name__ == "__main__":
    main()
