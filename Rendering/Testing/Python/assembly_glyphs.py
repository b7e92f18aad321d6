#!/usr/bin/python3
# SPDX-License-Identifier: GPL-3.0-or-later
"""Draws an assembly's ribbons and surface two ways, for the image tests: expanded (the ribbons
and surface of all the copies' atoms, vtkPolyDataMapper) or instanced (one copy's ribbons and
surface, drawn at every copy by vtkGlyph3DMapper from the structure reader's output 1,
orientation AssemblyOrientation as quaternions). The assembly is crambin (Data/proteins/1crn.pdb)
in a ring of three copies, 0, 120 and 240 degrees about z and 40 Å out, so that the copies do
not touch (their surfaces are then the surfaces of the copies).

    assembly_glyphs.py --mode expanded|instanced|wrong-orientation --what ribbons|surface
                       --output IMAGE [--size 240]

The ribbons of a rotated copy are the rotated ribbons: instanced and expanded pictures agree
pixel for pixel. A surface's lattice is not rotated with the copy, so its triangles differ
slightly: about 3 % of the pixels, at silhouettes (a wrong orientation: about 11 %).

wrong-orientation draws the instanced copies with conjugated quaternions (each rotation
reversed): the comparison must fail.
"""
import argparse
import math
import os

import numpy as np
from vtkmodules.util.numpy_support import numpy_to_vtk, vtk_to_numpy
from vtkmodules.vtkRenderingCore import (vtkActor, vtkGlyph3DMapper, vtkPolyDataMapper,
                                         vtkRenderer, vtkRenderWindow)
import vtkmodules.vtkRenderingOpenGL2  # noqa: F401 (the OpenGL factory)

import mesolens
from mesolens.lens import write_png

DATA = os.environ["MESOLENS_DATA_DIR"]
OUTPUT = os.environ.get("MESOLENS_TEST_OUTPUT_DIR", ".")


def ring_file():
    """Crambin with a three-copy REMARK 350 ring instead of its own monomer."""
    remarks = ["REMARK 350 BIOMOLECULE: 1", "REMARK 350 APPLY THE FOLLOWING TO CHAINS: A"]
    for k in range(3):
        angle = math.radians(120.0 * k)
        c, s = math.cos(angle), math.sin(angle)
        rows = [(c, -s, 0.0), (s, c, 0.0), (0.0, 0.0, 1.0)]
        shift = np.array(rows) @ np.array([40.0, 0.0, 0.0])
        for i, row in enumerate(rows):
            remarks.append("REMARK 350   BIOMT%d %3d %9.6f %9.6f %9.6f %14.5f"
                           % (i + 1, k + 1, row[0], row[1], row[2], shift[i]))
    with open(os.path.join(DATA, "proteins", "1crn.pdb")) as crambin:
        records = [line.rstrip("\n") for line in crambin if not line.startswith("REMARK 350")]
    path = os.path.join(OUTPUT, "assembly_glyphs_ring.pdb")
    with open(path, "w") as ring:
        ring.write("\n".join(remarks + records) + "\n")
    return path


def geometry(reader):
    """The ribbons and the solvent-excluded surface of the reader's atoms."""
    ribbons = mesolens.vtkMesoRibbons()
    ribbons.SetInputConnection(reader.GetOutputPort(0))
    surface = mesolens.vtkMesoMolecularSurface()
    surface.SetInputConnection(reader.GetOutputPort(0))
    surface.SetTolerance(0.5)
    return ribbons, surface


def copies_of(reader, mode):
    """The reader's copies; for wrong-orientation, with each rotation reversed."""
    reader.Update()
    copies = reader.GetOutput(1)
    if mode == "wrong-orientation":
        quaternions = vtk_to_numpy(copies.GetPointData().GetArray("AssemblyOrientation"))
        array = numpy_to_vtk(quaternions * np.array([1.0, -1.0, -1.0, -1.0]), deep=True)
        array.SetName("AssemblyOrientation")
        copies.GetPointData().AddArray(array)
    return copies


def actor_of(mode, what, path):
    """The ribbons' or the surface's actor."""
    reader = mesolens.vtkMesoStructureReader()
    reader.SetFileName(path)
    reader.SetAssembly("1")
    reader.SetExpandAssembly(mode == "expanded")
    copies = None if mode == "expanded" else copies_of(reader, mode)
    ribbons, surface = geometry(reader)
    if what == "ribbons":
        source, colour = ribbons, (0.9, 0.5, 0.2)
    else:
        source, colour = surface, (0.6, 0.7, 0.9)
    if copies is None:
        mapper = vtkPolyDataMapper()
        mapper.SetInputConnection(source.GetOutputPort())
    else:
        mapper = vtkGlyph3DMapper()
        mapper.SetInputData(copies)
        mapper.SetSourceConnection(source.GetOutputPort())
        mapper.SetScaling(False)
        mapper.SetOrientationModeToQuaternion()
        mapper.SetOrientationArray("AssemblyOrientation")
    mapper.ScalarVisibilityOff()
    actor = vtkActor()
    actor.SetMapper(mapper)
    actor.GetProperty().SetColor(*colour)
    return actor


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--mode", choices=["expanded", "instanced", "wrong-orientation"],
                        required=True)
    parser.add_argument("--what", choices=["ribbons", "surface"], required=True)
    parser.add_argument("--output", required=True)
    parser.add_argument("--size", type=int, default=240)
    args = parser.parse_args()
    renderer = vtkRenderer()
    renderer.AddActor(actor_of(args.mode, args.what, ring_file()))
    renderer.SetBackground(1, 1, 1)
    camera = renderer.GetActiveCamera()
    camera.SetPosition(0, 0, 260)
    camera.SetFocalPoint(0, 0, 0)
    camera.SetViewUp(0, 1, 0)
    camera.SetViewAngle(30)
    renderer.ResetCameraClippingRange(-90, 90, -90, 90, -60, 60)
    window = vtkRenderWindow()
    window.SetOffScreenRendering(True)
    window.SetMultiSamples(0)
    window.SetSize(args.size, args.size)
    window.AddRenderer(renderer)
    window.Render()
    write_png(window, args.output)


if __name__ == "__main__":
    main()
