#!/usr/bin/python3
# SPDX-License-Identifier: GPL-3.0-or-later
"""MesoLens from Python next to vtkmodules: readers into VTK filters, VTK data into MesoLens
filters, numpy views of the arrays, errors reported without exceptions or crashes."""
import os
import sys
import unittest

from vtkmodules.vtkCommonCore import VTK_STRING, vtkCommand
from vtkmodules.vtkCommonDataModel import vtkPolyData
from vtkmodules.vtkFiltersCore import vtkTubeFilter
from vtkmodules.vtkFiltersSources import vtkSphereSource
from vtkmodules.util.misc import calldata_type
from vtkmodules.util.numpy_support import vtk_to_numpy

import mesolens
from mesolens import array_names

DATA = os.environ["MESOLENS_DATA_DIR"]


def error_recorder(messages):
    @calldata_type(VTK_STRING)
    def record(caller, event, calldata):
        messages.append(calldata)
    return record


class PythonPipeline(unittest.TestCase):
    def test_reader_into_vtk_filter(self):
        reader = mesolens.vtkMesoStructureReader()
        reader.SetFileName(os.path.join(DATA, "proteins", "1ubq.pdb"))
        tubes = vtkTubeFilter()
        tubes.SetInputConnection(reader.GetOutputPort())
        tubes.SetRadius(0.2)
        tubes.Update()
        self.assertGreater(tubes.GetOutput().GetNumberOfPoints(), 608 * 2)
        atoms = reader.GetOutput()
        self.assertIsInstance(atoms, vtkPolyData)
        numbers = vtk_to_numpy(atoms.GetPointData().GetArray(array_names.AtomicNumber))
        self.assertEqual(len(numbers), 660)
        self.assertEqual(int((numbers == 8).sum()), 118 + 58)  # protein O + water O

    def test_vtk_data_into_mesolens_filter(self):
        sphere = vtkSphereSource()
        sphere.SetThetaResolution(24)
        sphere.SetPhiResolution(24)
        sphere.Update()
        data = vtkPolyData()
        data.DeepCopy(sphere.GetOutput())
        report = mesolens.vtkMesoMeshReport()
        report.SetInputData(data)
        report.Update()
        self.assertTrue(report.GetIsClosedManifold())
        self.assertEqual(report.GetEulerCharacteristic(), 2)
        out = report.GetOutput()
        self.assertIsInstance(out, vtkPolyData)
        self.assertEqual(out.GetFieldData().GetArray(array_names.NumberOfComponents).GetValue(0), 1)

    def test_trajectory_time_steps(self):
        reader = mesolens.vtkMesoTrajectoryReader()
        reader.SetTopologyFileName(os.path.join(DATA, "membranes", "yiip_popepopg.gro"))
        reader.SetTrajectoryFileName(os.path.join(DATA, "membranes", "yiip_popepopg.xtc"))
        reader.UpdateInformation()
        self.assertEqual(reader.GetNumberOfFrames(), 5)
        reader.UpdateTimeStep(60000.0)
        out = reader.GetOutput()
        self.assertEqual(out.GetNumberOfPoints(), 43480)
        self.assertEqual(out.GetFieldData().GetArray(array_names.FrameIndex).GetValue(0), 3)

    def test_cartoon_pipeline_with_level_of_detail(self):
        # Reader -> DSSP -> ribbons -> a VTK mapper, steered by the level-of-detail helper.
        from vtkmodules.vtkRenderingCore import vtkActor, vtkPolyDataMapper, vtkRenderer
        reader = mesolens.vtkMesoStructureReader()
        reader.SetFileName(os.path.join(DATA, "proteins", "1ubq.pdb"))
        dssp = mesolens.vtkMesoSecondaryStructure()
        dssp.SetInputConnection(reader.GetOutputPort())
        ribbons = mesolens.vtkMesoRibbons()
        ribbons.SetInputConnection(dssp.GetOutputPort())
        ribbons.Update()
        chains = dssp.GetOutput().GetFieldData().GetAbstractArray(array_names.DSSP)
        self.assertEqual(chains.GetValue(0),  # mkdssp 4.2.2
                         "-EEEEEETTS-EEEEE--TTSBHHHHHHHHHHHH---GGGEEEEETTEEPPTTSBTGGGTPPTT-EEEEEE--S--")
        self.assertGreater(ribbons.GetOutput().GetNumberOfPolys(), 5000)
        colours = vtk_to_numpy(ribbons.GetOutput().GetPointData().GetArray(array_names.BFactor))
        self.assertGreater(colours.max(), colours.min())
        mapper = vtkPolyDataMapper()
        mapper.SetInputConnection(ribbons.GetOutputPort())
        actor = vtkActor()
        actor.SetMapper(mapper)
        renderer = vtkRenderer()
        renderer.AddActor(actor)
        renderer.ResetCamera()
        detail = mesolens.vtkMesoRibbonLevelOfDetail()
        detail.SetRibbons(ribbons)
        detail.SetRenderer(renderer)
        self.assertGreater(detail.Update(), 0)
        self.assertIsNotNone(ribbons.GetSegmentSubdivisions())

    def test_error_is_reported_not_raised(self):
        reader = mesolens.vtkMesoStructureReader()
        messages = []
        record = error_recorder(messages)
        reader.AddObserver(vtkCommand.ErrorEvent, record)
        reader.GetExecutive().AddObserver(vtkCommand.ErrorEvent, record)
        reader.SetFileName(os.path.join(DATA, "no_such_file.pdb"))
        self.assertEqual(reader.GetExecutive().Update(), 0)
        self.assertEqual(reader.GetOutput().GetNumberOfPoints(), 0)
        self.assertTrue(any("no such file" in m for m in messages), messages)

    def test_element_colours(self):
        table = mesolens.vtkMesoElementLookupTable()
        self.assertEqual(table.GetNumberOfTableValues(), 119)
        oxygen = table.GetTableValue(8)
        self.assertGreater(oxygen[0], 0.9)  # red
        self.assertLess(oxygen[1], 0.2)


if __name__ == "__main__":
    sys.exit(0 if unittest.main(exit=False).result.wasSuccessful() else 1)
