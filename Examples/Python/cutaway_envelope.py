#!/usr/bin/python3
# SPDX-License-Identifier: GPL-3.0-or-later
"""An HIV-envelope-sized vesicle (150 nm across, about 240 000 lipids) cut open by the structured
cutaway, beside random removal: the scale of the SirTom thesis' HIV membrane.

The vesicle is built from the Martini DPPC/cholesterol bilayer of Data/, mapped tile by tile
onto a sphere of radius 750 Å with vtkMesoMembraneMapping (molecule instancing, 3 x 3 tiles
around points spread evenly over the sphere; tiles of neighbouring points overlap at their
seams, and leave gaps). vtkMesoStructuredCutaway makes the structure mesh from the lipids'
centres (about 150 vertices, as in the thesis), and hides the given share of the lipids in front of the plane
through the centre facing the camera. Left: structured (a wireframe of the mesh remains);
right: random. Cholesterol is yellow, DPPC orange; the back half, seen through the holes, blue.

    cutaway_envelope.py [--output cutaway_envelope.png] [--size 400] [--fraction 0.6]
                        [--vertices 150] [--seeds 60]
"""
import argparse
import math
import os
import time

import numpy as np
from vtkmodules.util.numpy_support import numpy_to_vtk, vtk_to_numpy
from vtkmodules.vtkCommonCore import vtkLookupTable
from vtkmodules.vtkCommonDataModel import vtkPlane, vtkPolyData
from vtkmodules.vtkFiltersCore import vtkAppendPolyData, vtkTriangleFilter
from vtkmodules.vtkFiltersSources import vtkSphereSource
from vtkmodules.vtkRenderingCore import vtkActor, vtkRenderer, vtkRenderWindow
import vtkmodules.vtkRenderingOpenGL2  # noqa: F401

import mesolens
from mesolens import array_names
from mesolens.lens import write_png

DATA = os.environ.get("MESOLENS_DATA_DIR",
                      os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "Data"))
RADIUS = 750.0       # Å: an HIV envelope is about 150 nm across
BEAD_RADIUS = 2.35   # Å, a Martini bead


def envelope(seeds):
    """The bilayer mapped around `seeds` points of a Fibonacci lattice on the sphere, with
    molecule ids made unique over all tiles and a `Colour` array (0 DPPC, 1 cholesterol)."""
    sphere = vtkSphereSource()
    sphere.SetRadius(RADIUS)
    sphere.SetThetaResolution(180)
    sphere.SetPhiResolution(180)
    triangles = vtkTriangleFilter()
    triangles.SetInputConnection(sphere.GetOutputPort())
    triangles.Update()
    bilayer = mesolens.vtkMesoTrajectoryReader()
    bilayer.SetTopologyFileName(os.path.join(DATA, "membranes", "martini_dppc_chol_bilayer.gro"))
    bilayer.Update()
    append = vtkAppendPolyData()
    golden = math.pi * (3 - math.sqrt(5))
    first_id = 0
    for s in range(seeds):
        z = 1 - 2 * (s + 0.5) / seeds
        r = math.sqrt(1 - z * z)
        mapping = mesolens.vtkMesoMembraneMapping()
        mapping.SetInputData(0, triangles.GetOutput())
        mapping.SetMembraneConnection(bilayer.GetOutputPort())
        mapping.SetMappingMethodToMoleculeInstancing()
        mapping.SetTiles(3)
        mapping.SetRadiusFactor(1.0)
        mapping.SetSeedPoint(RADIUS * r * math.cos(golden * s), RADIUS * r * math.sin(golden * s),
                             RADIUS * z)
        mapping.Update()
        mapped = vtkPolyData()
        mapped.ShallowCopy(mapping.GetOutput())
        if mapped.GetNumberOfPoints() == 0:
            continue
        data = mapped.GetPointData()
        # The mapping numbers its tiles' molecules apart; the mappings are numbered apart here.
        ids = vtk_to_numpy(data.GetArray(array_names.MoleculeId)).astype(np.int64)
        unique = numpy_to_vtk(first_id + ids, deep=1)
        unique.SetName(array_names.MoleculeId)
        data.AddArray(unique)
        first_id += int(ids.max()) + 1
        names = data.GetAbstractArray(array_names.ResidueName)
        colour = numpy_to_vtk(np.array([names.GetValue(i) == "CHOL"
                                        for i in range(names.GetNumberOfValues())],
                                       dtype=np.float32), deep=1)
        colour.SetName("Colour")
        data.AddArray(colour)
        mapped.GetFieldData().Initialize()  # no periodic box: the vesicle is whole
        append.AddInputData(mapped)
    append.Update()
    return append.GetOutput()


def main():
    parser = argparse.ArgumentParser(description=__doc__,
                                     formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--output", default="cutaway_envelope.png")
    parser.add_argument("--size", type=int, default=400, help="pixels per picture")
    parser.add_argument("--fraction", type=float, default=0.6, help="share of the cut hidden")
    parser.add_argument("--vertices", type=int, default=150, help="structure mesh vertices")
    parser.add_argument("--seeds", type=int, default=60, help="mapping sites on the sphere")
    args = parser.parse_args()

    start = time.monotonic()
    vesicle = envelope(args.seeds)
    lipids = len(np.unique(vtk_to_numpy(vesicle.GetPointData().GetArray(array_names.MoleculeId))))
    print(f"built the envelope: {lipids} lipids, {vesicle.GetNumberOfPoints()} beads in "
          f"{time.monotonic() - start:.1f} s")

    cutaway = mesolens.vtkMesoStructuredCutaway()
    cutaway.SetInputData(vesicle)
    cutaway.SetStructureVertices(args.vertices)
    plane = vtkPlane()  # the front half (towards the camera on +z) is cut
    plane.SetNormal(0, 0, -1)
    cutaway.SetCutFunction(plane)
    cutaway.SetFractionHidden(args.fraction)
    start = time.monotonic()
    cutaway.Update()
    print(f"prepared the cutaway (structure mesh, assignment, order) in "
          f"{time.monotonic() - start:.2f} s")

    colours = vtkLookupTable()
    colours.SetNumberOfTableValues(3)
    colours.SetTableValue(0, 0.95, 0.6, 0.2, 1.0)   # DPPC
    colours.SetTableValue(1, 1.0, 0.9, 0.3, 1.0)    # cholesterol
    colours.SetTableValue(2, 0.45, 0.55, 0.75, 1.0)  # the back half
    colours.SetRange(0.0, 2.0)
    window = vtkRenderWindow()
    window.SetOffScreenRendering(1)
    window.SetMultiSamples(0)
    window.SetSize(2 * args.size, args.size)
    keep = []
    for column, random_order in enumerate((False, True)):
        cutaway.SetRandomOrder(random_order)
        start = time.monotonic()
        cutaway.Update()
        seconds = time.monotonic() - start
        beads = vtkPolyData()
        beads.ShallowCopy(cutaway.GetOutput())
        points = vtk_to_numpy(beads.GetPoints().GetData())
        colour = vtk_to_numpy(beads.GetPointData().GetArray("Colour")).copy()
        colour[points[:, 2] < 0] = 2.0
        shown = numpy_to_vtk(colour, deep=1)
        shown.SetName("Shown")
        beads.GetPointData().AddArray(shown)
        mapper = mesolens.vtkMesoAtomMapper()  # hides the beads whose `Visible` is 0
        mapper.SetInputData(beads)
        mapper.SetRadiusScale(BEAD_RADIUS)
        mapper.SetScalarModeToUsePointFieldData()
        mapper.SelectColorArray("Shown")
        mapper.SetLookupTable(colours)
        mapper.UseLookupTableScalarRangeOn()
        actor = vtkActor()
        actor.SetMapper(mapper)
        renderer = vtkRenderer()
        renderer.AddActor(actor)
        renderer.SetBackground(0.1, 0.1, 0.13)
        renderer.SetViewport(column / 2, 0, (column + 1) / 2, 1)
        camera = renderer.GetActiveCamera()
        camera.SetPosition(0, 0, 4 * RADIUS)
        camera.SetFocalPoint(0, 0, 0)
        camera.SetViewUp(0, 1, 0)
        renderer.ResetCamera(-RADIUS, RADIUS, -RADIUS, RADIUS, -RADIUS, RADIUS)
        window.AddRenderer(renderer)
        keep.append((beads, mapper, actor, renderer))
        fields = beads.GetFieldData()
        print(f"{'random' if random_order else 'structured'}: "
              f"{fields.GetArray(array_names.MoleculesHidden).GetValue(0)} of "
              f"{fields.GetArray(array_names.MoleculesInCut).GetValue(0)} lipids in the cut hidden "
              f"(update {1e3 * seconds:.0f} ms)")
    window.Render()
    write_png(window, args.output)
    print(f"wrote {args.output}")


if __name__ == "__main__":
    main()
