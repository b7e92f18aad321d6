#!/usr/bin/python3
# SPDX-License-Identifier: GPL-3.0-or-later
"""The same membrane patch mapped by molecule instancing and by the polynomial onto several cell
membranes, side by side, in the manner of Figure 4 of the membrane-mapping paper.

Rows: the mitochondrion's outer membrane (electron tomography), a hiPS cell's plasma membrane
(cellPACK) and a C. elegans embryo cell (pycurv); columns: instancing, polynomial. The patch is
the all-atom DPPC bilayer of Data/ in 3 x 3 tiles, space-filling. The hiPSC and C. elegans
meshes give no unit, so every mesh is scaled for display: the tiles span a tenth of the mesh's
diagonal.

    lens_figure4.py [--output lens_figure4.png] [--size 300]
"""
import argparse
import os

from vtkmodules.vtkRenderingCore import vtkRenderWindow
import vtkmodules.vtkRenderingOpenGL2  # noqa: F401

from mesolens.lens import MembraneLens, write_png

DATA = os.environ.get("MESOLENS_DATA_DIR",
                      os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "Data"))
MESHES = ["mito5_outer_membrane.obj", "hipsc_cell_membrane_1.obj", "celegans_embryo_cell10_T10.ply"]
METHODS = ["instancing", "polynomial"]
PATCH_WIDTH_ANGSTROM = 3 * 63.0  # 3 tiles of the DPPC patch's 63 Å cell


def main():
    parser = argparse.ArgumentParser(description=__doc__,
                                     formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--output", default="lens_figure4.png")
    parser.add_argument("--size", type=int, default=300, help="pixels per picture")
    args = parser.parse_args()

    window = vtkRenderWindow()
    window.SetOffScreenRendering(1)
    window.SetMultiSamples(0)
    window.SetSize(len(METHODS) * args.size, len(MESHES) * args.size)
    lenses = []
    patch = os.path.join(DATA, "membranes", "dppc128_slipids_323K.gro")
    for row, mesh in enumerate(MESHES):
        for column, method in enumerate(METHODS):
            path = os.path.join(DATA, "meshes", mesh)
            probe = MembraneLens(path, patch)
            bounds = probe.surface.GetOutput().GetBounds()
            diagonal = sum((bounds[2 * d + 1] - bounds[2 * d]) ** 2 for d in range(3)) ** 0.5
            lens = MembraneLens(path, patch, mesh_unit_angstrom=PATCH_WIDTH_ANGSTROM * 10 / diagonal)
            lens.set_method(method)
            lens.set_style("space-filling")
            surface = lens.surface.GetOutput()
            lens.place(surface.GetPoint(surface.GetNumberOfPoints() // 3))
            top = len(MESHES) - 1 - row
            lens.renderer.SetViewport(column / len(METHODS), top / len(MESHES),
                                      (column + 1) / len(METHODS), (top + 1) / len(MESHES))
            window.AddRenderer(lens.renderer)
            lens.look_at_patch(distance_factor=4.0)
            lenses.append(lens)
            print(f"{mesh}: {method}, {lens.atom_count()} atoms")
    window.Render()
    write_png(window, args.output)
    print(f"wrote {args.output}")


if __name__ == "__main__":
    main()
