#!/usr/bin/python3
# SPDX-License-Identifier: GPL-3.0-or-later
"""Styles mixed in one frame: HIV-1 protease as a cartoon coloured by secondary structure, its
inhibitor in balls and sticks, and a translucent surface of the whole protein, composited by
depth peeling.

The secondary structure comes from vtkMesoSecondaryStructure (DSSP: the file, 1hpv, is one
mkdssp refuses); vtkMesoRibbons draws the cartoon; vtkMesoAtomMapper draws the inhibitor
(residue 478) as ray-cast impostors, whose exact depth composites with the translucent
surface: the protein's solvent-excluded surface from vtkMesoMolecularSurface.

    protein_styles.py [--output protein_styles.png] [--size 600] [--cylinders]
"""
import argparse
import os

import numpy as np
from vtkmodules.util.numpy_support import numpy_to_vtk, vtk_to_numpy
from vtkmodules.vtkCommonCore import vtkIdList, vtkLookupTable, vtkPoints
from vtkmodules.vtkCommonDataModel import vtkCellArray, vtkPolyData
from vtkmodules.vtkRenderingCore import (vtkActor, vtkPolyDataMapper, vtkRenderer,
                                         vtkRenderWindow)
import vtkmodules.vtkRenderingOpenGL2  # noqa: F401

import mesolens
from mesolens import array_names
from mesolens.lens import write_png

DATA = os.environ.get("MESOLENS_DATA_DIR",
                      os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "Data"))


def secondary_structure_colours():
    """Colours of the SecondaryStructure codes: helices red (3-10 pink, pi purple), strands and
    bridges yellow, the rest grey."""
    colours = [(0.75, 0.75, 0.75), (0.90, 0.20, 0.25), (0.95, 0.50, 0.65), (0.60, 0.30, 0.80),
               (0.98, 0.80, 0.15), (0.75, 0.75, 0.75), (0.75, 0.75, 0.75), (0.98, 0.80, 0.15),
               (0.90, 0.20, 0.25), (0.75, 0.75, 0.75)]
    table = vtkLookupTable()
    table.SetNumberOfTableValues(len(colours))
    for index, (r, g, b) in enumerate(colours):
        table.SetTableValue(index, r, g, b, 1.0)
    table.SetRange(0, len(colours) - 1)
    return table


def residue_atoms(atoms, residue_name):
    """The atoms of one residue name, with their point data and the bonds among them."""
    names = atoms.GetPointData().GetAbstractArray(array_names.ResidueName)
    rows = [a for a in range(atoms.GetNumberOfPoints()) if names.GetValue(a) == residue_name]
    kept = vtkIdList()
    for row in rows:
        kept.InsertNextId(row)
    subset = vtkPolyData()
    points = vtkPoints()
    atoms.GetPoints().GetPoints(kept, points)
    subset.SetPoints(points)
    order = vtkIdList()
    for index in range(len(rows)):
        order.InsertNextId(index)
    subset.GetPointData().CopyAllocate(atoms.GetPointData(), len(rows))
    subset.GetPointData().CopyData(atoms.GetPointData(), kept, order)
    renumber = {row: index for index, row in enumerate(rows)}
    bonds = vtkCellArray()
    lines = vtk_to_numpy(atoms.GetLines().GetConnectivityArray()).reshape(-1, 2)
    for first, second in lines:
        if first in renumber and second in renumber:
            bonds.InsertNextCell(2)
            bonds.InsertCellPoint(renumber[first])
            bonds.InsertCellPoint(renumber[second])
    subset.SetLines(bonds)
    vertices = vtkCellArray()
    for index in range(len(rows)):
        vertices.InsertNextCell(1)
        vertices.InsertCellPoint(index)
    subset.SetVerts(vertices)
    return subset


def main():
    parser = argparse.ArgumentParser(description=__doc__,
                                     formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--output", default="protein_styles.png")
    parser.add_argument("--size", type=int, default=600)
    parser.add_argument("--cylinders", action="store_true", help="helices as cylinders")
    args = parser.parse_args()

    reader = mesolens.vtkMesoStructureReader()
    reader.SetFileName(os.path.join(DATA, "proteins", "1hpv.pdb"))
    reader.Update()
    atoms = reader.GetOutput()

    assignment = mesolens.vtkMesoSecondaryStructure()
    assignment.SetInputConnection(reader.GetOutputPort())
    ribbons = mesolens.vtkMesoRibbons()
    ribbons.SetInputConnection(assignment.GetOutputPort())
    ribbons.SetHelixAsCylinder(args.cylinders)
    ribbons.SetSubdivisions(8)
    ribbon_mapper = vtkPolyDataMapper()
    ribbon_mapper.SetInputConnection(ribbons.GetOutputPort())
    ribbon_mapper.SetScalarModeToUsePointFieldData()
    ribbon_mapper.SelectColorArray(array_names.SecondaryStructure)
    ribbon_mapper.SetColorModeToMapScalars()  # unsigned char codes, not colours
    ribbon_mapper.SetLookupTable(secondary_structure_colours())
    ribbon_mapper.UseLookupTableScalarRangeOn()
    ribbon_actor = vtkActor()
    ribbon_actor.SetMapper(ribbon_mapper)
    ribbon_actor.GetProperty().SetSpecular(0.3)
    ribbon_actor.GetProperty().SetSpecularPower(30)

    ligand = residue_atoms(atoms, "478")
    ligand_mapper = mesolens.vtkMesoAtomMapper()
    ligand_mapper.SetInputData(ligand)
    ligand_mapper.SetStyle(mesolens.vtkMesoAtomMapper.BALL_AND_STICK)
    ligand_mapper.SetBallScale(0.45)
    ligand_mapper.SetBondRadius(0.3)
    ligand_actor = vtkActor()
    ligand_actor.SetMapper(ligand_mapper)

    hetero = vtk_to_numpy(atoms.GetPointData().GetArray(array_names.IsHetAtm)) != 0
    protein = vtkPolyData()
    protein_points = vtkPoints()
    protein_points.SetData(numpy_to_vtk(np.ascontiguousarray(
        vtk_to_numpy(atoms.GetPoints().GetData())[~hetero], dtype=np.float32), deep=1))
    protein.SetPoints(protein_points)
    elements = numpy_to_vtk(np.ascontiguousarray(
        vtk_to_numpy(atoms.GetPointData().GetArray(array_names.AtomicNumber))[~hetero]), deep=1)
    elements.SetName(array_names.AtomicNumber)
    protein.GetPointData().AddArray(elements)
    surface = mesolens.vtkMesoMolecularSurface()
    surface.SetInputData(protein)
    surface.SetTolerance(0.2)
    surface_mapper = vtkPolyDataMapper()
    surface_mapper.SetInputConnection(surface.GetOutputPort())
    surface_mapper.ScalarVisibilityOff()
    surface_actor = vtkActor()
    surface_actor.SetMapper(surface_mapper)
    surface_actor.GetProperty().SetColor(0.55, 0.7, 0.95)
    surface_actor.GetProperty().SetOpacity(0.25)

    renderer = vtkRenderer()
    for actor in (ribbon_actor, ligand_actor, surface_actor):
        renderer.AddActor(actor)
    renderer.SetBackground(1, 1, 1)
    passes = mesolens.vtkMesoRenderPasses()
    passes.DepthPeelingOn()
    passes.SetMaximumNumberOfPeels(8)
    passes.Apply(renderer)
    renderer.ResetCamera()
    renderer.GetActiveCamera().Elevation(-60)
    renderer.GetActiveCamera().OrthogonalizeViewUp()
    renderer.ResetCamera()
    renderer.GetActiveCamera().Zoom(1.3)
    window = vtkRenderWindow()
    window.SetOffScreenRendering(1)
    window.SetMultiSamples(0)
    window.SetAlphaBitPlanes(1)
    window.SetSize(args.size, args.size)
    window.AddRenderer(renderer)
    window.Render()
    write_png(window, args.output)
    chains = assignment.GetOutput().GetFieldData().GetAbstractArray(array_names.DSSP)
    for chain in range(chains.GetNumberOfValues()):
        print(f"chain {chain}: {chains.GetValue(chain)}")
    print(f"{ligand.GetNumberOfPoints()} inhibitor atoms, "
          f"{ribbons.GetOutput().GetNumberOfPolys()} ribbon triangles; wrote {args.output}")


if __name__ == "__main__":
    main()
