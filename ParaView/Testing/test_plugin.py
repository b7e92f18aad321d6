# SPDX-License-Identifier: GPL-3.0-or-later
"""The ParaView plugin under pvbatch: it loads, its readers open every file type they claim
(chosen by ParaView's reader factory), report their time steps, and every filter runs from
paraview.simple with its defaults, giving what the same VTK class gives without ParaView. The
"MesoLens Atoms" representation is offered, starts at the mapper's defaults, and picking a pixel
selects the atom a ray through it meets first, with its arrays.

Run by ctest as: pvbatch test_plugin.py PLUGIN_LIBRARY (environment from mesolens_add_python_test).
"""
import os
import sys

from paraview import servermanager
from paraview import simple

import mesolens

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from plugin_checks import check, data, finish, vtk_output  # noqa: E402



def points_of(proxy, port=0):
    proxy.UpdatePipeline()
    return proxy.GetDataInformation(port).GetNumberOfPoints()


def cells_of(proxy, port=0):
    proxy.UpdatePipeline()
    return proxy.GetDataInformation(port).GetNumberOfCells()


# paraview.simple names a proxy's function after its label.
simple.LoadPlugin(sys.argv[1], remote=False)
for name in ("MesoLensStructureReader", "MesoLensGROReader", "MesoLensTrajectoryReader",
             "MesoLensMeshReader", "SecondaryStructureDSSP", "Ribbons", "MolecularSurface",
             "SolventAccessibleArea", "AtomProperties", "MembraneMapping", "GeodesicDisk",
             "DiskParameterization", "StructuredCutaway", "TrajectoryRefinement", "MeshReport"):
    check(hasattr(simple, name), f"the plugin defines {name}")

# The reader factory offers our readers for their file types.
factory = servermanager.vtkSMProxyManager.GetProxyManager().GetReaderFactory()
session = servermanager.ActiveConnection.Session
for path, reader in ((data("proteins/1crn.pdb"), "MesoLensStructureReader"),
                     (data("proteins/1crn.cif"), "MesoLensStructureReader"),
                     (data("membranes/yiip_popepopg.gro"), "MesoLensGroReader"),
                     (data("membranes/yiip_popepopg.xtc"), "MesoLensTrajectoryReader"),
                     (data("meshes/cgal_mesh_with_border.off"), "MesoLensMeshReader")):
    offered = factory.GetReaders(path, session)
    names = [offered.GetString(i) for i in range(1, offered.GetNumberOfStrings(), 3)]
    check(reader in names, f"{reader} is offered for {os.path.basename(path)} (offered {names})")

# Readers: the same atoms as the VTK classes, time steps in ParaView's animation.
crambin = simple.MesoLensStructureReader(FileName=data("proteins/1crn.pdb"))
plain = mesolens.vtkMesoStructureReader()
plain.SetFileName(data("proteins/1crn.pdb"))
expected = vtk_output(plain)
check(points_of(crambin) == expected.GetNumberOfPoints() > 0, "1crn.pdb atoms")
check(cells_of(crambin) == expected.GetNumberOfCells(), "1crn.pdb bonds")

trajectory = simple.MesoLensTrajectoryReader(FileName=data("membranes/yiip_popepopg.xtc"))
trajectory.UpdatePipelineInformation()
plain = mesolens.vtkMesoTrajectoryReader()
plain.SetTrajectoryFileName(data("membranes/yiip_popepopg.xtc"))
plain.UpdateInformation()
times = list(trajectory.TimestepValues)
check(len(times) == plain.GetNumberOfFrames() > 1, f"trajectory time steps {times}")
check(points_of(trajectory) == 43480, "the xtc's topology was found beside it")
scene = simple.GetAnimationScene()
scene.UpdateAnimationUsingDataTimeSteps()
check(list(scene.TimeKeeper.TimestepValues) == times, "the animation has the trajectory's times")

gro = simple.MesoLensGROReader(FileName=data("membranes/dppc128_slipids_323K.gro"))
check(points_of(gro) == 28160, "gro atoms")
mesh = simple.MesoLensMeshReader(FileName=data("meshes/cgal_mesh_with_border.off"))
check(cells_of(mesh) > 0, "off mesh triangles")

# Filters with their defaults: the same output as the VTK classes.
structure = simple.SecondaryStructureDSSP(Input=crambin)
ribbons = simple.Ribbons(Input=structure)
reader = mesolens.vtkMesoStructureReader()
reader.SetFileName(data("proteins/1crn.pdb"))
dssp = mesolens.vtkMesoSecondaryStructure()
dssp.SetInputConnection(reader.GetOutputPort())
plain_ribbons = mesolens.vtkMesoRibbons()
plain_ribbons.SetInputConnection(dssp.GetOutputPort())
check(cells_of(ribbons) == vtk_output(plain_ribbons).GetNumberOfCells() > 0, "ribbons")

surface = simple.MolecularSurface(Input=crambin)
plain_surface = mesolens.vtkMesoMolecularSurface()
plain_surface.SetInputConnection(reader.GetOutputPort())
check(cells_of(surface) == vtk_output(plain_surface).GetNumberOfCells() > 0, "molecular surface")

area = simple.SolventAccessibleArea(Input=crambin)
check(points_of(area) == expected.GetNumberOfPoints(), "surface area keeps the atoms")
properties = simple.AtomProperties(Input=crambin)
check(points_of(properties) == expected.GetNumberOfPoints(), "atom properties")

organelle = simple.MesoLensMeshReader(FileName=data("meshes/mito5_outer_membrane.obj"))
report = simple.MeshReport(Input=organelle)
check(cells_of(report) > 0, "mesh report")
membrane = simple.MesoLensGROReader(FileName=data("membranes/dppc128_slipids_323K.gro"))
mapping = simple.MembraneMapping(Surface=organelle, Membrane=membrane)
mapping.SeedPoint = list(simple.servermanager.Fetch(organelle).GetPoint(1000))
mapping.Tiles = 2
mapping.MembraneToMeshScale = 1e-4
check(points_of(mapping) == 4 * 28160, f"membrane mapping of 2 x 2 tiles ({points_of(mapping)})")
disk = simple.GeodesicDisk(Input=organelle)
disk.SeedPoint = mapping.SeedPoint
disk.Radius = 0.2
check(cells_of(disk) > 0, "geodesic disk")
chart = simple.DiskParameterization(Input=disk)
check(points_of(chart) == points_of(disk), "disk parameterization")

cutaway = simple.StructuredCutaway(Input=membrane)
check(points_of(cutaway) == 28160, "structured cutaway keeps the atoms")
refinement = simple.TrajectoryRefinement(Input=trajectory)
refinement.UpdatePipelineInformation()
check(len(refinement.TimestepValues) > len(times), "trajectory refinement adds time steps")

# Every property starts where the VTK class starts (its default comes from the class itself).
def same(proxy_value, class_value):
    if isinstance(class_value, (tuple, list)):
        return all(same(p, c) for p, c in zip(proxy_value, class_value))
    if isinstance(class_value, bool) or isinstance(proxy_value, bool):
        return bool(proxy_value) == bool(class_value)
    if isinstance(class_value, (int, float)) and isinstance(proxy_value, (int, float)):
        return abs(proxy_value - class_value) <= 1e-12 * max(1.0, abs(class_value))
    return (proxy_value or "") == (class_value or "")


checked = 0
for proxy in (crambin, trajectory, gro, mesh, structure, ribbons, surface, area, properties,
              report, cutaway):
    instance = getattr(mesolens, proxy.SMProxy.GetVTKClassName())()
    for name in proxy.ListProperties():
        prop = proxy.GetProperty(name)
        getter = getattr(instance, "Get" + name, None)
        if (getter is None or prop.SMProperty.GetInformationOnly() or name == "FileName" or
                prop.SMProperty.IsA("vtkSMProxyProperty")):
            continue  # inputs and cut functions are proxies, not values
        value = proxy.GetPropertyValue(name)
        if prop.SMProperty.FindDomain("vtkSMEnumerationDomain"):
            value = prop.SMProperty.GetElement(0)  # the value, not the entry's text
        check(same(value, getter()), f"{proxy.SMProxy.GetXMLName()}.{name} starts at the class's "
              f"default ({value!r} against {getter()!r})")
        checked += 1

# The representation: offered for atoms, its own properties at the mapper's defaults.
view = simple.CreateRenderView()
view.ViewSize = [300, 300]
view.OrientationAxesVisibility = 0
display = simple.Show(crambin, view)
check("MesoLens Atoms" in display.GetProperty("Representation").Available,
      "MesoLens Atoms is a representation type")
display.SetRepresentationType("MesoLens Atoms")
simple.ColorBy(display, None)
mapper = mesolens.vtkMesoAtomMapper()
for name in ("Style", "RadiusScale", "BallScale", "BondRadius", "OcclusionCulling",
             "VisibilityArrayName"):
    prop = display.GetProperty(name)
    value = prop.SMProperty.GetElement(0) if name == "Style" else display.GetPropertyValue(name)
    check(same(value, getattr(mapper, "Get" + name)()),
          f"MesoLens Atoms.{name} starts at the mapper's default ({value!r})")
    checked += 1
check(checked > 40, f"defaults compared for {checked} properties")
print(f"defaults compared for {checked} properties")

# Picking: the pixel at the view's centre selects the atom the central ray meets first, and the
# selection extracts that atom with its arrays (what the spreadsheet shows).
simple.ResetCamera(view)
simple.Render(view)
camera = view.GetActiveCamera()
eye, focus = camera.GetPosition(), camera.GetFocalPoint()
direction = [f - e for f, e in zip(focus, eye)]
length = sum(d * d for d in direction) ** 0.5
direction = [d / length for d in direction]
radii_filter = mesolens.vtkMesoAtomProperties()
radii_filter.SetInputConnection(reader.GetOutputPort())
atoms = vtk_output(radii_filter)
radii = atoms.GetPointData().GetArray("VanDerWaalsRadius")
nearest, nearest_depth = -1, float("inf")
for atom in range(atoms.GetNumberOfPoints()):
    offset = [p - e for p, e in zip(atoms.GetPoint(atom), eye)]
    along = sum(o * d for o, d in zip(offset, direction))
    across2 = sum(o * o for o in offset) - along * along
    radius = radii.GetValue(atom)
    if across2 < radius * radius:
        depth = along - (radius * radius - across2) ** 0.5
        if depth < nearest_depth:
            nearest, nearest_depth = atom, depth
check(nearest >= 0, "the central ray meets an atom")
centre = [view.ViewSize[0] // 2, view.ViewSize[1] // 2]
simple.SetActiveSource(crambin)
simple.SelectSurfacePoints(Rectangle=centre + centre, View=view)
picked = servermanager.Fetch(simple.ExtractSelection(Input=crambin))
picked_ids = picked.GetPointData().GetArray("vtkOriginalPointIds") if picked else None
ids = [int(picked_ids.GetValue(i)) for i in range(picked_ids.GetNumberOfTuples())] \
    if picked_ids else []
check(ids == [nearest], f"picking selects atom {nearest} (selected {ids})")
if ids == [nearest]:
    names = expected.GetPointData().GetAbstractArray("AtomName")
    check(picked.GetPointData().GetAbstractArray("AtomName").GetValue(0) ==
          names.GetValue(nearest), "the picked atom's arrays come with it")
simple.ClearSelection(crambin)

finish("all plugin checks passed")
