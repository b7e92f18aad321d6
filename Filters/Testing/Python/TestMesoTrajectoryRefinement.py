#!/usr/bin/python3
# SPDX-License-Identifier: GPL-3.0-or-later
"""Trajectory refinement from Python: reader -> vtkMesoTrajectoryRefinement, refined time steps,
key frames passed through exactly, in-between frames as 4-point combinations of key frames."""
import os
import sys
import unittest

from vtkmodules.vtkCommonDataModel import vtkPolyData
from vtkmodules.vtkCommonExecutionModel import vtkStreamingDemandDrivenPipeline
from vtkmodules.util.numpy_support import vtk_to_numpy

import mesolens
from mesolens import array_names

DATA = os.environ["MESOLENS_DATA_DIR"]


def make_reader():
    reader = mesolens.vtkMesoTrajectoryReader()
    reader.SetTopologyFileName(os.path.join(DATA, "membranes", "yiip_popepopg.gro"))
    reader.SetTrajectoryFileName(os.path.join(DATA, "membranes", "yiip_popepopg.xtc"))
    return reader


def points_at(algorithm, time):
    algorithm.UpdateTimeStep(time)
    out = algorithm.GetOutput()
    return out, vtk_to_numpy(out.GetPoints().GetData()).astype("float64")


class TrajectoryRefinement(unittest.TestCase):
    def test_refined_time_steps_and_frames(self):
        reader = make_reader()
        refinement = mesolens.vtkMesoTrajectoryRefinement()
        refinement.SetInputConnection(reader.GetOutputPort())
        refinement.SetRefinementLevels(1)
        refinement.UpdateInformation()
        info = refinement.GetOutputInformation(0)
        times = info.Get(vtkStreamingDemandDrivenPipeline.TIME_STEPS())
        self.assertEqual(len(times), 9)
        self.assertEqual(refinement.GetNumberOfRefinedFrames(), 9)
        self.assertAlmostEqual(times[1], 10000.0)

        keys = make_reader()
        _, key1 = points_at(keys, 20000.0)
        _, key2 = points_at(keys, 40000.0)

        out, key_points = points_at(refinement, 20000.0)
        self.assertIsInstance(out, vtkPolyData)
        self.assertEqual((key_points == key1).all(), True)  # key frames exactly

        # Frame 3 lies midway between key frames 1 and 2; with one level it is
        # (-x0 + 9 x1 + 9 x2 - x3) / 16.
        _, key0 = points_at(keys, 0.0)
        _, key3 = points_at(keys, 60000.0)
        out, middle = points_at(refinement, times[3])
        self.assertEqual(out.GetFieldData().GetArray(array_names.RefinedFrameIndex).GetValue(0), 3)
        expected = (-key0 + 9 * key1 + 9 * key2 - key3) / 16
        self.assertLess(abs(middle - expected).max(), 1e-3)
        self.assertEqual(out.GetNumberOfPoints(), 43480)


if __name__ == "__main__":
    sys.exit(0 if unittest.main(exit=False).result.wasSuccessful() else 1)
