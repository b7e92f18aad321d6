#!/usr/bin/python3
# SPDX-License-Identifier: GPL-3.0-or-later
"""A whole virus capsid built from its asymmetric unit, with one protein picked out by a selection.

The phiX174 virion (1RB8: 5112 atoms in the file, 60 copies in its biological assembly, 306,720
atoms) read with vtkMesoStructureReader's Assembly "1", drawn space-filling by the impostor mapper
with ambient occlusion. The spike protein G of every copy (`chain G G-*`: copy c > 0 of chain G
is named G-(c + 1)) is coloured by a vtkMesoSelectAtoms mask; everything else is grey.

    virus_capsid.py [--file ../shared/data/proteins/1rb8.pdb] [--assembly 1]
                    [--selection "chain G G-*"] [--output capsid.png] [--size 600]

Exits with 77 (skipped) when the file is absent.
"""
import argparse
import os
import sys
import time

from vtkmodules.vtkCommonCore import vtkLookupTable
from vtkmodules.vtkRenderingCore import vtkActor, vtkRenderer, vtkRenderWindow
import vtkmodules.vtkRenderingOpenGL2  # noqa: F401 (the OpenGL factory)

import mesolens
from mesolens.lens import write_png

HERE = os.path.dirname(os.path.abspath(__file__))
SHARED = os.environ.get("MESOLENS_SHARED_DATA_DIR",
                        os.path.join(HERE, "..", "..", "..", "shared", "data"))


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--file", default=os.path.join(SHARED, "proteins", "1rb8.pdb"))
    parser.add_argument("--assembly", default="1")
    parser.add_argument("--selection", default="chain G G-*")
    parser.add_argument("--output", default="capsid.png")
    parser.add_argument("--size", type=int, default=600)
    args = parser.parse_args()
    if not os.path.exists(args.file):
        print("skipped: no", args.file)
        sys.exit(77)

    reader = mesolens.vtkMesoStructureReader()
    reader.SetFileName(args.file)
    reader.SetAssembly(args.assembly)
    select = mesolens.vtkMesoSelectAtoms()
    select.SetInputConnection(reader.GetOutputPort())
    select.SetSelection(args.selection)
    start = time.perf_counter()
    select.Update()
    atoms = select.GetOutput()
    if atoms.GetNumberOfPoints() == 0:
        sys.exit(1)
    chosen = atoms.GetPointData().GetArray("Selected")
    picked = sum(int(chosen.GetValue(i)) for i in range(chosen.GetNumberOfTuples()))
    copies = int(atoms.GetPointData().GetArray("AssemblyCopy").GetRange()[1]) + 1
    print("%s assembly %s: %d copies, %d atoms (read, built and selected in %.2f s); "
          "'%s': %d atoms" % (os.path.basename(args.file), args.assembly, copies,
                              atoms.GetNumberOfPoints(), time.perf_counter() - start,
                              args.selection, picked))

    table = vtkLookupTable()
    table.SetNumberOfTableValues(2)
    table.SetTableValue(0, 0.78, 0.78, 0.8, 1.0)
    table.SetTableValue(1, 0.95, 0.55, 0.15, 1.0)
    table.SetTableRange(0, 1)
    mapper = mesolens.vtkMesoAtomMapper()
    mapper.SetInputConnection(select.GetOutputPort())
    mapper.SetScalarModeToUsePointFieldData()
    mapper.SelectColorArray("Selected")
    mapper.ScalarVisibilityOn()
    mapper.SetLookupTable(table)
    mapper.SetScalarRange(0, 1)
    actor = vtkActor()
    actor.SetMapper(mapper)
    renderer = vtkRenderer()
    renderer.AddActor(actor)
    renderer.SetBackground(0.08, 0.09, 0.12)
    renderer.ResetCamera()
    renderer.GetActiveCamera().Zoom(1.3)
    passes = mesolens.vtkMesoRenderPasses()
    passes.SSAOOn()
    passes.SetSSAORadius(12.0)                         # Å: a capsid is 300 Å across
    passes.SetSSAOBias(1.0)
    passes.SSAOBlurOn()
    passes.Apply(renderer)
    window = vtkRenderWindow()
    window.SetOffScreenRendering(True)
    window.SetMultiSamples(0)
    window.SetSize(args.size, args.size)
    window.AddRenderer(renderer)
    start = time.perf_counter()
    window.Render()
    print("first frame %.2f s" % (time.perf_counter() - start))
    write_png(window, args.output)
    print("wrote", args.output)


if __name__ == "__main__":
    main()
