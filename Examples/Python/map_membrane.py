#!/usr/bin/python3
# SPDX-License-Identifier: GPL-3.0-or-later
"""Map a lipid bilayer onto a cell surface with each membrane-mapping method, one PNG each.

The all-atom DPPC patch of Data/ (128 lipids, waters removed, Å) is tiled k x k and placed around
a point of the mitochondrion's outer membrane (electron tomography, µm, converted to nm here:
VTK's sphere impostors lose precision when atoms are 1e-4 of the scene's coordinates) by
displacement, molecule instancing and the quadratic polynomial per tile. The surface is grey,
the atoms are coloured by element.

    map_membrane.py [--tiles K] [--output-prefix mapped] [--size 600]
"""
import argparse
import os

import numpy as np
from vtkmodules.util.numpy_support import vtk_to_numpy
from vtkmodules.vtkCommonTransforms import vtkTransform
from vtkmodules.vtkFiltersGeneral import vtkTransformPolyDataFilter
from vtkmodules.vtkIOImage import vtkPNGWriter
from vtkmodules.vtkRenderingCore import (vtkActor, vtkPolyDataMapper, vtkRenderer, vtkRenderWindow,
                                         vtkWindowToImageFilter)
from vtkmodules.vtkRenderingOpenGL2 import vtkOpenGLSphereMapper

import mesolens
from mesolens import array_names

DATA = os.environ.get("MESOLENS_DATA_DIR",
                      os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "Data"))
ANGSTROM_TO_NANOMETRE = 0.1
METHODS = {"displacement": mesolens.vtkMesoMembraneMapping.DISPLACEMENT,
           "instancing": mesolens.vtkMesoMembraneMapping.MOLECULE_INSTANCING,
           "polynomial": mesolens.vtkMesoMembraneMapping.POLYNOMIAL}


def main():
    parser = argparse.ArgumentParser(description=__doc__)
    parser.add_argument("--tiles", type=int, default=3)
    parser.add_argument("--output-prefix", default="mapped")
    parser.add_argument("--size", type=int, default=600)
    args = parser.parse_args()

    reader = mesolens.vtkMesoMeshReader()
    reader.SetFileName(os.path.join(DATA, "meshes", "mito5_outer_membrane.obj"))
    micrometre_to_nanometre = vtkTransform()
    micrometre_to_nanometre.Scale(1000, 1000, 1000)
    surface = vtkTransformPolyDataFilter()
    surface.SetInputConnection(reader.GetOutputPort())
    surface.SetTransform(micrometre_to_nanometre)
    surface.Update()
    seed = surface.GetOutput().GetPoint(1000)
    membrane = mesolens.vtkMesoTrajectoryReader()
    membrane.SetTopologyFileName(os.path.join(DATA, "membranes", "dppc128_slipids_323K.gro"))
    membrane.RemoveWatersOn()

    mapping = mesolens.vtkMesoMembraneMapping()
    mapping.SetSurfaceConnection(surface.GetOutputPort())
    mapping.SetMembraneConnection(membrane.GetOutputPort())
    mapping.SetSeedPoint(seed)
    mapping.SetTiles(args.tiles)
    mapping.SetMembraneToMeshScale(ANGSTROM_TO_NANOMETRE)
    radii = mesolens.vtkMesoAtomProperties()
    radii.SetInputConnection(mapping.GetOutputPort())
    radii.SetLengthScale(ANGSTROM_TO_NANOMETRE)

    atoms_mapper = vtkOpenGLSphereMapper()
    atoms_mapper.SetInputConnection(radii.GetOutputPort())
    atoms_mapper.SetScaleArray(array_names.VanDerWaalsRadius)
    atoms_mapper.SetLookupTable(mesolens.vtkMesoElementLookupTable())
    atoms_mapper.UseLookupTableScalarRangeOn()
    atoms_mapper.SetScalarModeToUsePointFieldData()
    atoms_mapper.SelectColorArray(array_names.AtomicNumber)
    atoms_mapper.SetColorModeToMapScalars()
    atoms = vtkActor()
    atoms.SetMapper(atoms_mapper)
    surface_mapper = vtkPolyDataMapper()
    surface_mapper.SetInputConnection(surface.GetOutputPort())
    surface_mapper.ScalarVisibilityOff()
    cell = vtkActor()
    cell.SetMapper(surface_mapper)
    cell.GetProperty().SetColor(0.75, 0.72, 0.68)

    renderer = vtkRenderer()
    renderer.AddActor(cell)
    renderer.AddActor(atoms)
    renderer.SetBackground(0.1, 0.11, 0.14)
    window = vtkRenderWindow()
    window.SetOffScreenRendering(True)
    window.SetMultiSamples(0)
    window.SetSize(args.size, args.size)
    window.AddRenderer(renderer)

    for name, method in METHODS.items():
        mapping.SetMappingMethod(method)
        if not mapping.GetExecutive().Update():
            raise SystemExit(f"mapping with {name} failed")
        mapped = mapping.GetOutput()
        change = vtk_to_numpy(mapped.GetCellData().GetArray(array_names.BondLengthChange))[mapped.GetNumberOfVerts():]
        print(f"{name}: {mapped.GetNumberOfPoints()} atoms in {args.tiles}x{args.tiles} tiles, "
              f"bond length change median {np.median(np.abs(change)):.2e}, "
              f"95th percentile {np.percentile(np.abs(change), 95):.2e}")
        # Look at the mapped region along the surface normal at the seed.
        centre = np.array(mapped.GetCenter())
        normal = centre - np.array(surface.GetOutput().GetCenter())
        normal /= np.linalg.norm(normal)
        camera = renderer.GetActiveCamera()
        camera.SetFocalPoint(*centre)
        camera.SetPosition(*(centre + 80 * normal))
        renderer.ResetCameraClippingRange()
        window.Render()
        capture = vtkWindowToImageFilter()
        capture.SetInput(window)
        writer = vtkPNGWriter()
        writer.SetFileName(f"{args.output_prefix}_{name}.png")
        writer.SetInputConnection(capture.GetOutputPort())
        writer.Write()
        print("wrote", f"{args.output_prefix}_{name}.png")


if __name__ == "__main__":
    main()
