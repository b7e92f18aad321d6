# SPDX-License-Identifier: GPL-3.0-or-later
"""MesoLens on several MPI ranks (mpirun -np N pvbatch test_distributed.py PLUGIN): the readers
and the membrane mapping share their atoms among the ranks (every rank holds some), and what the
ranks give together equals what the VTK classes give in one process: the same atoms, the same
secondary structure and surface area across chains, the same molecular surface, and the same
molecules hidden by the cutaway.
"""
import os
import sys

from paraview import servermanager
from paraview import simple
from vtkmodules.vtkCommonDataModel import vtkPlane

import mesolens

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from plugin_checks import check, data, finish, vtk_output  # noqa: E402


def ranks_holding(proxy):
    """The ranks (process ids) that hold points of a proxy's output."""
    ids = simple.ProcessIdScalars(Input=proxy)
    ids.UpdatePipeline()
    info = ids.GetPointDataInformation().GetArray("ProcessId")
    return set(range(int(info.GetRange()[0]), int(info.GetRange()[1]) + 1)) if info else set()


simple.LoadPlugin(sys.argv[1], remote=False)
ranks = servermanager.vtkProcessModule.GetProcessModule().GetNumberOfLocalPartitions()
check(ranks > 1, f"runs on several ranks ({ranks})")
everyone = set(range(ranks))

# The structure reader: whole molecules per rank; together every atom once.
protease = simple.MesoLensStructureReader(FileName=data("proteins/1hpv.pdb"))
reader = mesolens.vtkMesoStructureReader()
reader.SetFileName(data("proteins/1hpv.pdb"))
whole = vtk_output(reader)
protease.UpdatePipeline()
check(protease.GetDataInformation().GetNumberOfPoints() == whole.GetNumberOfPoints(),
      "the ranks hold every atom once")
check(ranks_holding(protease) == everyone, f"every rank holds atoms ({ranks_holding(protease)})")

def same_point_array(proxy, plain_filter, name):
    """Whether the ranks' outputs of `proxy`, gathered, carry the point array `name` of the
    single process's `plain_filter` run on the whole file (to 1e-6)."""
    plain_filter.SetInputConnection(reader.GetOutputPort())
    expected = vtk_output(plain_filter).GetPointData().GetArray(name)
    gathered = servermanager.Fetch(proxy).GetPointData().GetArray(name)
    count = expected.GetNumberOfTuples()
    return (gathered is not None and gathered.GetNumberOfTuples() == count and
            all(abs(gathered.GetValue(i) - expected.GetValue(i)) <= 1e-6 for i in range(count)))


# Filters across chains: the ranks' pieces, gathered, equal the single process's result.
check(same_point_array(simple.SecondaryStructureDSSP(Input=protease),
                       mesolens.vtkMesoSecondaryStructure(), "SecondaryStructureId"),
      "secondary structure on the ranks equals one process's")
check(same_point_array(simple.SolventAccessibleArea(Input=protease), mesolens.vtkMesoSurfaceArea(),
                       "AccessibleArea"),
      "surface area per atom on the ranks equals one process's")
surface = simple.MolecularSurface(Input=protease)
plain_surface = mesolens.vtkMesoMolecularSurface()
plain_surface.SetInputConnection(reader.GetOutputPort())
surface.UpdatePipeline()
check(surface.GetDataInformation().GetNumberOfCells() == vtk_output(plain_surface).GetNumberOfCells(),
      "the molecular surface is made once, of every atom")

# The membrane mapping: the ranks share the 3 x 3 tiles; the cutaway hides the same molecules.
organelle = simple.MesoLensMeshReader(FileName=data("meshes/mito5_outer_membrane.obj"))
membrane = simple.MesoLensGROReader(FileName=data("membranes/dppc128_slipids_323K.gro"))
membrane.RemoveWaters = 1
seed = list(servermanager.Fetch(organelle).GetPoint(1000))
mapping = simple.MembraneMapping(Surface=organelle, Membrane=membrane)
mapping.SeedPoint = seed
mapping.Tiles = 3
mapping.MembraneToMeshScale = 1e-4
mapping.MappingMethod = "Polynomial"
mapping.UpdatePipeline()
check(mapping.GetDataInformation().GetNumberOfPoints() == 9 * 16640, "3 x 3 tiles mapped once")
check(ranks_holding(mapping) == everyone, f"every rank maps tiles ({ranks_holding(mapping)})")
cut = simple.StructuredCutaway(Input=mapping)
cut.CutFunction = "Plane"
cut.CutFunction.Origin = seed
cut.CutFunction.Normal = [0.0, 0.0, 1.0]
cut.FractionHidden = 0.5
cut.ExtractVisibleAtoms = 1
cut.UpdatePipeline()

mesh = mesolens.vtkMesoMeshReader()
mesh.SetFileName(data("meshes/mito5_outer_membrane.obj"))
gro = mesolens.vtkMesoTrajectoryReader()
gro.SetTopologyFileName(data("membranes/dppc128_slipids_323K.gro"))
gro.RemoveWatersOn()
plain_mapping = mesolens.vtkMesoMembraneMapping()
plain_mapping.SetInputConnection(0, mesh.GetOutputPort())
plain_mapping.SetInputConnection(1, gro.GetOutputPort())
plain_mapping.SetSeedPoint(seed)
plain_mapping.SetTiles(3)
plain_mapping.SetMembraneToMeshScale(1e-4)
plain_mapping.SetMappingMethodToPolynomial()
plane = vtkPlane()
plane.SetOrigin(seed)
plane.SetNormal(0.0, 0.0, 1.0)
plain_cut = mesolens.vtkMesoStructuredCutaway()
plain_cut.SetInputConnection(plain_mapping.GetOutputPort())
plain_cut.SetCutFunction(plane)
plain_cut.SetFractionHidden(0.5)
plain_cut.ExtractVisibleAtomsOn()
kept = vtk_output(plain_cut).GetNumberOfPoints()
check(0 < kept < 9 * 16640, f"the cutaway hides some atoms ({kept})")
check(cut.GetDataInformation().GetNumberOfPoints() == kept,
      f"the ranks keep the atoms one process keeps ({cut.GetDataInformation().GetNumberOfPoints()} "
      f"against {kept})")
visible_ids = servermanager.Fetch(cut).GetPointData().GetArray("MoleculeId")
expected_ids = plain_cut.GetOutput().GetPointData().GetArray("MoleculeId")
check(visible_ids is not None and
      sorted(visible_ids.GetValue(i) for i in range(visible_ids.GetNumberOfTuples())) ==
      sorted(expected_ids.GetValue(i) for i in range(expected_ids.GetNumberOfTuples())),
      "the same molecules stay visible")

finish(f"all distributed checks passed on {ranks} ranks")
