#!/usr/bin/python3
# SPDX-License-Identifier: GPL-3.0-or-later
"""The solvent-excluded surface of E. coli heat-labile enterotoxin type IIB (1tii: one A chain,
five B chains), coloured by chain, or by the kind of analytic patch each vertex lies on.

vtkMesoMolecularSurface builds the surface from its patches (convex on the atoms, saddles
where the probe touches two atoms, concave where it touches three), tessellated to a chord
error; its exact area and volume come from the patches. Every vertex carries the atom it
belongs to, so chains, residues or elements colour it.

    surface_by_chain.py [--output surface_by_chain.png] [--size 600] [--tolerance 0.1]
                        [--colour-by chain|patch] [--drop-cavities]
"""
import argparse
import os
import time

from vtkmodules.vtkCommonCore import vtkLookupTable
from vtkmodules.vtkRenderingCore import (vtkActor, vtkPolyDataMapper, vtkRenderer,
                                         vtkRenderWindow)
import vtkmodules.vtkRenderingOpenGL2  # noqa: F401

import mesolens
from mesolens import array_names
from mesolens.lens import write_png

DATA = os.environ.get("MESOLENS_DATA_DIR",
                      os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "Data"))

# Colour-blind-safe (Okabe-Ito) colours for up to eight chains; patches: convex, saddle, concave.
CHAIN_COLOURS = [(0.90, 0.62, 0.00), (0.34, 0.71, 0.91), (0.00, 0.62, 0.45), (0.94, 0.89, 0.26),
                 (0.00, 0.45, 0.70), (0.84, 0.37, 0.00), (0.80, 0.47, 0.65), (0.60, 0.60, 0.60)]
PATCH_COLOURS = [(0.85, 0.85, 0.85), (0.35, 0.60, 0.90), (0.90, 0.35, 0.30)]


def lookup_table(colours):
    table = vtkLookupTable()
    table.SetNumberOfTableValues(len(colours))
    for index, (r, g, b) in enumerate(colours):
        table.SetTableValue(index, r, g, b, 1.0)
    table.SetRange(0, len(colours) - 1)
    return table


def field(data, name):
    return data.GetFieldData().GetArray(name).GetValue(0)


def main():
    parser = argparse.ArgumentParser(description=__doc__,
                                     formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--output", default="surface_by_chain.png")
    parser.add_argument("--size", type=int, default=600)
    parser.add_argument("--tolerance", type=float, default=0.1, help="chord error, Å")
    parser.add_argument("--colour-by", choices=("chain", "patch"), default="chain")
    parser.add_argument("--drop-cavities", action="store_true")
    args = parser.parse_args()

    reader = mesolens.vtkMesoStructureReader()
    reader.SetFileName(os.path.join(DATA, "proteins", "1tii.pdb"))
    reader.RemoveWatersOn()  # 216 crystal waters would each be a small sphere
    surface = mesolens.vtkMesoMolecularSurface()
    surface.SetInputConnection(reader.GetOutputPort())
    surface.SetTolerance(args.tolerance)
    surface.SetKeepCavities(not args.drop_cavities)
    reader.Update()
    start = time.perf_counter()
    surface.Update()
    seconds = time.perf_counter() - start
    mesh = surface.GetOutput()
    if mesh.GetNumberOfPoints() == 0:
        raise SystemExit("no surface was built")

    mapper = vtkPolyDataMapper()
    mapper.SetInputData(mesh)
    mapper.SetScalarModeToUsePointFieldData()
    array, colours = ((array_names.ChainIndex, CHAIN_COLOURS) if args.colour_by == "chain"
                      else (array_names.PatchType, PATCH_COLOURS))
    mapper.SelectColorArray(array)
    mapper.SetColorModeToMapScalars()
    mapper.SetLookupTable(lookup_table(colours))
    mapper.UseLookupTableScalarRangeOn()
    actor = vtkActor()
    actor.SetMapper(mapper)
    actor.GetProperty().SetSpecular(0.25)
    actor.GetProperty().SetSpecularPower(20)

    renderer = vtkRenderer()
    renderer.AddActor(actor)
    renderer.SetBackground(1, 1, 1)
    renderer.ResetCamera()
    renderer.GetActiveCamera().Elevation(30)
    renderer.GetActiveCamera().OrthogonalizeViewUp()
    renderer.ResetCamera()
    renderer.GetActiveCamera().Zoom(1.25)
    window = vtkRenderWindow()
    window.SetOffScreenRendering(1)
    window.SetMultiSamples(0)
    window.SetSize(args.size, args.size)
    window.AddRenderer(renderer)
    window.Render()
    write_png(window, args.output)
    print(f"1tii: {reader.GetOutput().GetNumberOfPoints()} atoms; SES {field(mesh, array_names.Area):.0f} Å2, "
          f"{field(mesh, array_names.Volume):.0f} Å3, {int(field(mesh, array_names.CavityCount))} cavities, "
          f"{mesh.GetNumberOfPolys()} triangles at {args.tolerance} Å in {seconds:.2f} s; "
          f"wrote {args.output}")


if __name__ == "__main__":
    main()
