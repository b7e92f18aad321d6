# SPDX-License-Identifier: GPL-3.0-or-later
"""The magnifier's scene in ParaView: an organelle, a lipid bilayer mapped onto it where you point,
and the bilayer cut open, drawn in one picture. Runs in pvpython, or on MPI ranks in pvbatch:

    pvbatch membrane_on_organelle.py PLUGIN [IMAGE]
    mpirun -np 2 pvbatch membrane_on_organelle.py PLUGIN [IMAGE]

PLUGIN is the built MesoLens.so (build/lib/paraview-5.11/plugins/MesoLens/MesoLens.so); the
picture goes to IMAGE (default membrane_on_organelle.png). Data come from the repository's Data/.
"""
import os
import sys

from paraview import servermanager
from paraview.simple import (ColorBy, GetActiveViewOrCreate, LoadPlugin, Render, SaveScreenshot,
                             Show)
from vtkmodules.vtkCommonCore import vtkMath
from vtkmodules.vtkFiltersCore import vtkPolyDataNormals

HERE = os.path.dirname(os.path.abspath(__file__))
DATA = os.environ.get("MESOLENS_DATA_DIR", os.path.join(HERE, "..", "..", "Data"))
plugin = sys.argv[1]
image = sys.argv[2] if len(sys.argv) > 2 else "membrane_on_organelle.png"

LoadPlugin(plugin, remote=False)
from paraview.simple import (MembraneMapping, MesoLensGROReader, MesoLensMeshReader,  # noqa: E402
                             StructuredCutaway)

# The mitochondrion's outer membrane (µm) and an all-atom DPPC patch (Å).
organelle = MesoLensMeshReader(FileName=os.path.join(DATA, "meshes", "mito5_outer_membrane.obj"))
membrane = MesoLensGROReader(FileName=os.path.join(DATA, "membranes", "dppc128_slipids_323K.gro"))
membrane.RemoveWaters = 1

# Point at the surface (here its vertex 1000, as a click would): the patch is mapped there,
# 3 x 3 tiles, at its true size.
mesh = servermanager.Fetch(organelle)
normals = vtkPolyDataNormals()
normals.SetInputData(mesh)
normals.SplittingOff()
normals.Update()
seed = list(mesh.GetPoint(1000))
normal = normals.GetOutput().GetPointData().GetNormals().GetTuple3(1000)
side = [0.0, 0.0, 0.0]
vtkMath.Cross(normal, [0.0, 0.0, 1.0] if abs(normal[2]) < 0.9 else [1.0, 0.0, 0.0], side)
vtkMath.Normalize(side)
lens = MembraneMapping(Surface=organelle, Membrane=membrane)
lens.SeedPoint = seed
lens.Tiles = 3
lens.MembraneToMeshScale = 1e-4
lens.MappingMethod = "Polynomial"

# Cut the mapped bilayer open along a plane through the seed: half of the lipids in front go,
# those at the structure's edges last, so the bilayer's structure stays readable.
cut = StructuredCutaway(Input=lens)
cut.CutFunction = "Plane"
cut.CutFunction.Origin = seed
cut.CutFunction.Normal = side
cut.FractionHidden = 0.5
cut.ExtractVisibleAtoms = 1

cut.UpdatePipeline()
bounds = lens.GetDataInformation().GetBounds()
centre = [0.5 * (bounds[2 * k] + bounds[2 * k + 1]) for k in range(3)]
print("mapped atoms:", lens.GetDataInformation().GetNumberOfPoints(),
      "visible after the cut:", cut.GetDataInformation().GetNumberOfPoints())
view = GetActiveViewOrCreate("RenderView")
view.ViewSize = [640, 480]
view.OrientationAxesVisibility = 0
view.Background = [1.0, 1.0, 1.0]
try:  # ParaView 5.11 paints the background from its palette unless told not to
    view.UseColorPaletteForBackground = 0
except AttributeError:
    pass
surface = Show(organelle, view)
surface.DiffuseColor = [0.75, 0.75, 0.78]
# As a wireframe: the mapped bilayer lies on the smooth surface the mapping fits, which the
# coarse mesh's flat triangles cross.
surface.SetRepresentationType("Wireframe")
surface.AmbientColor = surface.DiffuseColor
atoms = Show(cut, view)
# MesoLens' impostors: true spheres, composited with their depth on any number of ranks. Radii
# are in Å times RadiusScale: the scene is in µm.
atoms.SetRepresentationType("MesoLens Atoms")
atoms.RadiusScale = 1e-4
ColorBy(atoms, None)  # element colours

Render(view)  # the first render places the camera on everything; then ours
# Looking down at the patch, slanted towards the cut so the bilayer's thickness shows.
view.CameraFocalPoint = centre
view.CameraPosition = [centre[k] + 0.045 * normal[k] - 0.012 * side[k] for k in range(3)]
view.CameraViewUp = side
view.CameraViewAngle = 30
Render(view)
SaveScreenshot(image, view, ImageResolution=[640, 480])
print("wrote", image)
