#!/usr/bin/python3
# SPDX-License-Identifier: GPL-3.0-or-later
"""A Martini DPPC vesicle cut open: the structured cutaway (SirTom) against random removal (the
Visibility Equalizer), 20 %, 50 % and 80 % of the cut hidden, in the manner of Figure 4.2 of
the thesis.

The vesicle (3072 lipids, split by its periodic box and gathered whole by the filter) is cut
by the plane through its centre facing the camera; the structure mesh is made from the lipids'
centres. Top row: structured (what remains of the cut half, orange, follows the mesh's edges);
bottom row: random. The beads are drawn by vtkMesoAtomMapper, which hides those the cutaway's
`Visible` mask marks; the untouched half behind is blue.

    cutaway_vesicle.py [--output cutaway_vesicle.png] [--size 240] [--vertices 20]
                       [--both-random]
"""
import argparse
import os

import numpy as np
from vtkmodules.util.numpy_support import numpy_to_vtk, vtk_to_numpy
from vtkmodules.vtkCommonDataModel import vtkPlane, vtkPolyData
from vtkmodules.vtkCommonCore import vtkLookupTable
from vtkmodules.vtkRenderingCore import vtkActor, vtkRenderer, vtkRenderWindow
import vtkmodules.vtkRenderingOpenGL2  # noqa: F401

import mesolens
from mesolens import array_names
from mesolens.lens import write_png

DATA = os.environ.get("MESOLENS_DATA_DIR",
                      os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "Data"))
BEAD_RADIUS = 2.35  # Å, a Martini bead


def coloured_beads(cut_output, in_cut):
    """The cutaway's output (all beads, with its `Visible` mask, which vtkMesoAtomMapper reads
    and hides the zeros of) and an `InCut` array to colour by: 1 for the cut half (what the
    removal leaves of it), 0 for the untouched half behind."""
    beads = vtkPolyData()
    beads.ShallowCopy(cut_output)
    beads.GetPointData().AddArray(in_cut)
    return beads


def main():
    parser = argparse.ArgumentParser(description=__doc__,
                                     formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--output", default="cutaway_vesicle.png")
    parser.add_argument("--size", type=int, default=240, help="pixels per picture")
    parser.add_argument("--vertices", type=int, default=20,
                        help="structure mesh vertices (20: triangles about 6 nm wide, several "
                             "lipids across, on this 17 nm vesicle)")
    parser.add_argument("--both-random", action="store_true",
                        help="random removal in both rows (shows that the picture tells the "
                             "modes apart)")
    args = parser.parse_args()

    vesicle = mesolens.vtkMesoTrajectoryReader()
    vesicle.SetTopologyFileName(os.path.join(DATA, "membranes", "martini_dppc_vesicle.gro"))
    cutaway = mesolens.vtkMesoStructuredCutaway()
    cutaway.SetInputConnection(vesicle.GetOutputPort())
    cutaway.SetStructureVertices(args.vertices)
    cutaway.Update()
    points = vtk_to_numpy(cutaway.GetOutput().GetPoints().GetData())
    centre = np.median(points, axis=0)
    in_cut = numpy_to_vtk(np.ascontiguousarray(points[:, 2] >= centre[2], dtype=np.float32),
                          deep=1)
    in_cut.SetName("InCut")
    # The vesicle's extent (a few stray lipids lie far from it).
    low = np.percentile(points, 1, axis=0)
    high = np.percentile(points, 99, axis=0)
    frame = [low[0], high[0], low[1], high[1], low[2], high[2]]
    colours = vtkLookupTable()
    colours.SetNumberOfTableValues(2)
    colours.SetTableValue(0, 0.45, 0.55, 0.75, 1.0)  # the half behind
    colours.SetTableValue(1, 0.95, 0.6, 0.2, 1.0)    # what remains of the cut half
    colours.SetRange(0.0, 1.0)
    plane = vtkPlane()  # the cut: the half towards the camera (+z)
    plane.SetOrigin(*centre)
    plane.SetNormal(0, 0, -1)
    cutaway.SetCutFunction(plane)

    fractions = (0.2, 0.5, 0.8)
    window = vtkRenderWindow()
    window.SetOffScreenRendering(1)
    window.SetMultiSamples(0)
    window.SetSize(len(fractions) * args.size, 2 * args.size)
    keep = []
    for row, random_order in enumerate((False, True)):
        for column, fraction in enumerate(fractions):
            cutaway.SetRandomOrder(random_order or args.both_random)
            cutaway.SetFractionHidden(fraction)
            cutaway.Update()
            beads = coloured_beads(cutaway.GetOutput(), in_cut)
            mapper = mesolens.vtkMesoAtomMapper()
            mapper.SetInputData(beads)
            mapper.SetRadiusScale(BEAD_RADIUS)
            mapper.SetScalarModeToUsePointFieldData()
            mapper.SelectColorArray("InCut")
            mapper.SetLookupTable(colours)
            mapper.UseLookupTableScalarRangeOn()
            actor = vtkActor()
            actor.SetMapper(mapper)
            renderer = vtkRenderer()
            renderer.AddActor(actor)
            renderer.SetBackground(0.1, 0.1, 0.13)
            top = 1 - row
            renderer.SetViewport(column / len(fractions), top / 2, (column + 1) / len(fractions),
                                 (top + 1) / 2)
            camera = renderer.GetActiveCamera()
            camera.SetFocalPoint(*centre)
            camera.SetPosition(centre[0], centre[1], centre[2] + 500)
            camera.SetViewUp(0, 1, 0)
            renderer.ResetCamera(frame)
            window.AddRenderer(renderer)
            keep.append((beads, mapper, actor, renderer))
            hidden = cutaway.GetOutput().GetFieldData().GetArray(array_names.MoleculesHidden).GetValue(0)
            cut_count = cutaway.GetOutput().GetFieldData().GetArray(array_names.MoleculesInCut).GetValue(0)
            print(f"{'random' if random_order else 'structured'} {fraction:.0%}: {hidden} of "
                  f"{cut_count} lipids in the cut hidden")
    window.Render()
    write_png(window, args.output)
    print(f"wrote {args.output}")


if __name__ == "__main__":
    main()
