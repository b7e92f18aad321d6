#!/usr/bin/python3
# SPDX-License-Identifier: GPL-3.0-or-later
"""Colour a membrane by leaflet, chosen with atom selections (vtkMesoSelectAtoms).

The YiiP transporter in its POPE/POPG bilayer (Data/membranes/yiip_popepopg.gro). The upper
leaflet is `same residue as (lipid and name P and z > MID)`, MID the mean height of the
phosphorus atoms; the protein is `protein`. Each selection adds a 0/1 array; they are combined
into `Leaflet` (0 lower, 1 upper, 2 protein) and drawn by the impostor mapper through a lookup
table, with ambient occlusion.

    leaflets_by_selection.py [--output leaflets.png] [--size 600] [--one-colour]

--one-colour draws every lipid as the lower leaflet (the image test's proof that a wrong
colouring fails the comparison).
"""
import argparse
import os

import numpy as np
from vtkmodules.util.numpy_support import numpy_to_vtk, vtk_to_numpy
from vtkmodules.vtkCommonCore import vtkLookupTable
from vtkmodules.vtkRenderingCore import vtkActor, vtkRenderer, vtkRenderWindow
import vtkmodules.vtkRenderingOpenGL2  # noqa: F401 (the OpenGL factory)

import mesolens
from mesolens.lens import write_png

DATA = os.environ.get("MESOLENS_DATA_DIR",
                      os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "Data"))
COLOURS = [(0.25, 0.45, 0.85), (0.95, 0.6, 0.2), (0.85, 0.85, 0.85)]  # lower, upper, protein


def leaflets(one_colour):
    """The membrane's atoms with the `Leaflet` array, and the counts of lipids per leaflet."""
    membrane = mesolens.vtkMesoTrajectoryReader()
    membrane.SetTopologyFileName(os.path.join(DATA, "membranes", "yiip_popepopg.gro"))
    phosphates = mesolens.vtkMesoSelectAtoms()
    phosphates.SetInputConnection(membrane.GetOutputPort())
    phosphates.SetSelection("lipid and name P")
    phosphates.SetOutputModeToExtract()
    phosphates.Update()
    middle = vtk_to_numpy(phosphates.GetOutput().GetPoints().GetData())[:, 2].mean()

    upper = mesolens.vtkMesoSelectAtoms()
    upper.SetInputConnection(membrane.GetOutputPort())
    upper.SetSelection("same residue as (lipid and name P and z > %.3f)" % middle)
    upper.SetMaskArrayName("Upper")
    protein = mesolens.vtkMesoSelectAtoms()
    protein.SetInputConnection(upper.GetOutputPort())
    protein.SetSelection("protein")
    protein.SetMaskArrayName("Protein")
    protein.Update()
    atoms = protein.GetOutput()
    data = atoms.GetPointData()
    in_upper = vtk_to_numpy(data.GetArray("Upper")).astype(np.int32)
    in_protein = vtk_to_numpy(data.GetArray("Protein")).astype(np.int32)
    if one_colour:
        in_upper[:] = 0
    leaflet = np.where(in_protein == 1, 2, in_upper).astype(np.float32)
    array = numpy_to_vtk(leaflet, deep=True)
    array.SetName("Leaflet")
    data.AddArray(array)
    phosphorus = vtk_to_numpy(phosphates.GetOutput().GetPoints().GetData())[:, 2]
    return atoms, int((phosphorus > middle).sum()), int((phosphorus <= middle).sum())


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--output", default="leaflets.png")
    parser.add_argument("--size", type=int, default=600)
    parser.add_argument("--one-colour", action="store_true")
    args = parser.parse_args()

    atoms, upper, lower = leaflets(args.one_colour)
    print("yiip_popepopg: %d atoms; upper leaflet %d lipids, lower leaflet %d lipids"
          % (atoms.GetNumberOfPoints(), upper, lower))
    table = vtkLookupTable()
    table.SetNumberOfTableValues(3)
    for index, colour in enumerate(COLOURS):
        table.SetTableValue(index, *colour, 1.0)
    table.SetTableRange(0, 2)
    mapper = mesolens.vtkMesoAtomMapper()
    mapper.SetInputData(atoms)
    mapper.SetScalarModeToUsePointFieldData()
    mapper.SelectColorArray("Leaflet")
    mapper.ScalarVisibilityOn()
    mapper.SetLookupTable(table)
    mapper.SetScalarRange(0, 2)
    actor = vtkActor()
    actor.SetMapper(mapper)
    renderer = vtkRenderer()
    renderer.AddActor(actor)
    renderer.SetBackground(1, 1, 1)
    camera = renderer.GetActiveCamera()
    camera.SetPosition(0, -1, 0.15)
    camera.SetFocalPoint(0, 0, 0)
    camera.SetViewUp(0, 0, 1)
    renderer.ResetCamera()
    camera.Zoom(1.4)
    passes = mesolens.vtkMesoRenderPasses()
    passes.SSAOOn()
    passes.SetSSAORadius(4.0)                          # Å
    passes.SetSSAOBias(0.5)
    passes.SSAOBlurOn()
    passes.Apply(renderer)
    window = vtkRenderWindow()
    window.SetOffScreenRendering(True)
    window.SetMultiSamples(0)
    window.SetSize(args.size, args.size)
    window.AddRenderer(renderer)
    window.Render()
    write_png(window, args.output)
    print("wrote", args.output)


if __name__ == "__main__":
    main()
