#!/usr/bin/python3
# SPDX-License-Identifier: GPL-3.0-or-later
"""Render a protein as space-filling atoms coloured by element, off screen, to a PNG.

    render_protein.py [FILE] [--output protein.png]
"""
import argparse
import os

from vtkmodules.vtkFiltersSources import vtkSphereSource
from vtkmodules.vtkIOImage import vtkPNGWriter
from vtkmodules.vtkRenderingCore import (vtkActor, vtkGlyph3DMapper, vtkRenderer,
                                         vtkRenderWindow, vtkWindowToImageFilter)
import vtkmodules.vtkRenderingOpenGL2  # noqa: F401 (registers the OpenGL back end)

import mesolens
from mesolens import array_names

DATA = os.environ.get("MESOLENS_DATA_DIR",
                      os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "Data"))


def main():
    parser = argparse.ArgumentParser(description=__doc__)
    parser.add_argument("file", nargs="?", default=os.path.join(DATA, "proteins", "1crn.pdb"))
    parser.add_argument("--output", default="protein.png")
    args = parser.parse_args()

    reader = mesolens.vtkMesoStructureReader()
    reader.SetFileName(args.file)
    radii = mesolens.vtkMesoAtomProperties()
    radii.SetInputConnection(reader.GetOutputPort())
    sphere = vtkSphereSource()
    sphere.SetThetaResolution(20)
    sphere.SetPhiResolution(20)
    mapper = vtkGlyph3DMapper()
    mapper.SetInputConnection(radii.GetOutputPort())
    mapper.SetSourceConnection(sphere.GetOutputPort())
    mapper.SetScaleArray(array_names.VanDerWaalsRadius)
    mapper.SetScaleModeToScaleByMagnitude()
    mapper.SetScaleFactor(2.0)  # the source sphere has diameter 1
    mapper.SetLookupTable(mesolens.vtkMesoElementLookupTable())
    mapper.UseLookupTableScalarRangeOn()
    mapper.SetScalarModeToUsePointFieldData()
    mapper.SelectColorArray(array_names.AtomicNumber)
    actor = vtkActor()
    actor.SetMapper(mapper)
    renderer = vtkRenderer()
    renderer.AddActor(actor)
    renderer.SetBackground(1, 1, 1)
    window = vtkRenderWindow()
    window.SetOffScreenRendering(True)
    window.SetMultiSamples(0)
    window.SetSize(400, 400)
    window.AddRenderer(renderer)
    window.Render()
    capture = vtkWindowToImageFilter()
    capture.SetInput(window)
    writer = vtkPNGWriter()
    writer.SetFileName(args.output)
    writer.SetInputConnection(capture.GetOutputPort())
    writer.Write()
    print("wrote", args.output)


if __name__ == "__main__":
    main()
