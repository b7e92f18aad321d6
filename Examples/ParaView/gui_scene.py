# SPDX-License-Identifier: GPL-3.0-or-later
"""The magnifier's scene in the ParaView GUI: the mitochondrion of Data/, a DPPC bilayer mapped
onto it at its vertex 1000, cut open along a plane whose widget stays in the view (drag it, or
the Fraction Hidden slider, and press Apply). The README's screenshot shows this."""
import os
from paraview.simple import *
from paraview import servermanager
from vtkmodules.vtkCommonCore import vtkMath
from vtkmodules.vtkFiltersCore import vtkPolyDataNormals
# Run from the repository root: paraview --script=Examples/ParaView/gui_scene.py
root = os.environ.get("MESOLENS_ROOT", os.getcwd())
LoadPlugin(root + "/build/lib/paraview-5.11/plugins/MesoLens/MesoLens.so", remote=False, ns=globals())
organelle = MesoLensMeshReader(registrationName="mito5_outer_membrane.obj",
                               FileName=root + "/Data/meshes/mito5_outer_membrane.obj")
membrane = MesoLensGROReader(registrationName="dppc128_slipids_323K.gro",
                             FileName=root + "/Data/membranes/dppc128_slipids_323K.gro")
membrane.RemoveWaters = 1
mesh = servermanager.Fetch(organelle)
normals = vtkPolyDataNormals(); normals.SetInputData(mesh); normals.SplittingOff(); normals.Update()
seed = list(mesh.GetPoint(1000))
normal = normals.GetOutput().GetPointData().GetNormals().GetTuple3(1000)
side = [0.0, 0.0, 0.0]
vtkMath.Cross(normal, [0.0, 0.0, 1.0], side); vtkMath.Normalize(side)
lens = MembraneMapping(registrationName="MembraneMapping", Surface=organelle, Membrane=membrane)
lens.SeedPoint = seed; lens.Tiles = 3; lens.MembraneToMeshScale = 1e-4; lens.MappingMethod = "Polynomial"
cut = StructuredCutaway(registrationName="StructuredCutaway", Input=lens)
cut.CutFunction = "Plane"; cut.CutFunction.Origin = seed; cut.CutFunction.Normal = side
cut.FractionHidden = 0.5; cut.ExtractVisibleAtoms = 1
view = GetActiveViewOrCreate("RenderView")
surface = Show(organelle, view); surface.SetRepresentationType("Wireframe")
Hide(lens, view)
# MesoLens' impostors in element colours; radii in Å times RadiusScale (the scene is in µm).
atoms = Show(cut, view); atoms.SetRepresentationType("MesoLens Atoms"); atoms.RadiusScale = 1e-4
atoms.ColorArrayName = ["POINTS", ""]
SetActiveSource(cut)
Render(view)
cut.UpdatePipeline()
b = lens.GetDataInformation().GetBounds()
centre = [0.5 * (b[2 * k] + b[2 * k + 1]) for k in range(3)]
view.CameraFocalPoint = centre
view.CameraPosition = [centre[k] + 0.045 * normal[k] - 0.012 * side[k] for k in range(3)]
view.CameraViewUp = side
Render(view)
