#!/usr/bin/python3
# SPDX-License-Identifier: GPL-3.0-or-later
"""The interactive magnifier driven without a person: a scripted click through the interactor
places the membrane where the click was; keys change the tiles, method, style and play the
trajectory; a click off the surface and a failing mapping say why in the status line."""
import math
import os
import tempfile
import unittest

from mesolens.lens import MembraneLens
from mesolens.viewer import LensViewer

DATA = os.environ.get("MESOLENS_DATA_DIR", "Data")
MESH = os.path.join(DATA, "meshes", "mito5_outer_membrane.obj")
PATCH = os.path.join(DATA, "membranes", "dppc128_slipids_323K.gro")
YIIP = os.path.join(DATA, "membranes", "yiip_popepopg.gro")
YIIP_XTC = os.path.join(DATA, "membranes", "yiip_popepopg.xtc")


def display_point(renderer, point):
    renderer.SetWorldPoint(*point, 1.0)
    renderer.WorldToDisplay()
    x, y, _ = renderer.GetDisplayPoint()
    return int(round(x)), int(round(y))


def press_and_release(viewer, x, y, drag=0):
    interactor = viewer.interactor
    interactor.SetEventInformation(x, y, 0, 0)
    interactor.InvokeEvent("LeftButtonPressEvent")
    interactor.SetEventInformation(x + drag, y, 0, 0)
    interactor.InvokeEvent("LeftButtonReleaseEvent")


def press_key(viewer, name):
    codes = {"plus": "+", "minus": "-", "space": " "}
    viewer.interactor.SetKeySym(name)
    viewer.interactor.SetKeyCode(codes.get(name, name))
    viewer.interactor.InvokeEvent("CharEvent")


class Viewer(unittest.TestCase):
    def setUp(self):
        self.lens = MembraneLens(MESH, PATCH)
        self.lens.set_tiles(2)
        self.viewer = LensViewer(self.lens, (400, 300), offscreen=True)
        # Look at the vertex 1000 side of the organelle, from outside.
        surface = self.lens.surface.GetOutput()
        self.target = surface.GetPoint(1000)
        centre = surface.GetCenter()
        outward = [self.target[d] - centre[d] for d in range(3)]
        length = math.sqrt(sum(v * v for v in outward))
        camera = self.lens.renderer.GetActiveCamera()
        camera.SetFocalPoint(self.target)
        camera.SetPosition([self.target[d] + 2.0 * outward[d] / length for d in range(3)])
        camera.SetViewUp(0, 0, 1)
        self.lens.renderer.ResetCameraClippingRange()
        self.viewer.window.Render()

    def test_click_places_the_membrane_where_the_click_was(self):
        x, y = display_point(self.lens.renderer, self.target)
        press_and_release(self.viewer, x, y)
        self.assertIsNotNone(self.lens.centre, self.viewer.message)
        distance = math.dist(self.lens.centre, self.target)
        self.assertLess(distance, 0.02)  # µm: the picked point is the clicked surface point
        bounds = self.lens.atoms.GetBounds()
        for d in range(3):
            self.assertLessEqual(bounds[2 * d], self.lens.centre[d])
            self.assertGreaterEqual(bounds[2 * d + 1], self.lens.centre[d])
        self.assertIn("atoms", self.viewer.status.GetInput())

    def test_a_drag_turns_the_camera_and_places_nothing(self):
        x, y = display_point(self.lens.renderer, self.target)
        press_and_release(self.viewer, x, y, drag=20)
        self.assertIsNone(self.lens.centre)

    def test_a_click_off_the_surface_says_so(self):
        press_and_release(self.viewer, 2, 2)
        self.assertIsNone(self.lens.centre)
        self.assertIn("off the surface", self.viewer.status.GetInput())

    def test_keys_change_tiles_method_style_and_keep_the_place(self):
        x, y = display_point(self.lens.renderer, self.target)
        press_and_release(self.viewer, x, y)
        placed = self.lens.centre
        self.assertIsNotNone(placed)
        press_key(self.viewer, "plus")
        self.assertEqual(self.lens.tiles, 3)
        press_key(self.viewer, "minus")
        press_key(self.viewer, "minus")
        self.assertEqual(self.lens.tiles, 1)
        press_key(self.viewer, "minus")
        self.assertEqual(self.lens.tiles, 1)
        method = self.lens.method
        press_key(self.viewer, "m")
        self.assertNotEqual(self.lens.method, method)
        self.assertEqual(self.lens.centre, placed)
        press_key(self.viewer, "s")
        self.assertEqual(self.lens.style, "ball-and-stick")
        press_key(self.viewer, "a")
        self.assertTrue(self.lens.ssao)
        press_key(self.viewer, "h")
        self.assertTrue(self.lens.shadows)
        self.assertIn("shadows on", self.viewer.status.GetInput())
        press_key(self.viewer, "a")
        press_key(self.viewer, "h")
        self.assertFalse(self.lens.ssao or self.lens.shadows)
        with tempfile.TemporaryDirectory() as folder:
            path = self.viewer.screenshot(os.path.join(folder, "shot.png"))
            self.assertGreater(os.path.getsize(path), 1000)
            # The saved camera is one the render command reads back.
            saved = self.viewer.save_camera(os.path.join(folder, "camera.txt"))
            from mesolens.lens import read_camera_file
            from vtkmodules.vtkRenderingCore import vtkCamera
            camera = vtkCamera()
            read_camera_file(saved, camera)
            original = self.lens.renderer.GetActiveCamera()
            for got, want in zip(camera.GetPosition(), original.GetPosition()):
                self.assertAlmostEqual(got, want, places=9)
            self.assertAlmostEqual(camera.GetViewAngle(), original.GetViewAngle())

    def test_space_without_a_trajectory_says_so(self):
        press_key(self.viewer, "space")
        self.assertFalse(self.viewer.playing)
        self.assertIn("no trajectory", self.viewer.status.GetInput())


class Trajectory(unittest.TestCase):
    def test_space_plays_and_steps_the_trajectory(self):
        lens = MembraneLens(MESH, YIIP, YIIP_XTC)
        lens.set_tiles(1)
        lens.place(lens.surface.GetOutput().GetPoint(1000))
        viewer = LensViewer(lens, (200, 150), offscreen=True)
        press_key(viewer, "space")
        self.assertTrue(viewer.playing)
        viewer.step()
        self.assertEqual(viewer.time_index, 1)
        self.assertIn("t = ", viewer.status.GetInput())
        # Refinement level 1: a frame between each two, 9 in all.
        self.assertEqual(len(lens.time_steps()), 5)
        press_key(viewer, "l")
        self.assertEqual(lens.refinement_level, 1)
        self.assertEqual(len(lens.time_steps()), 9)
        viewer.step()
        self.assertIn("t = 10000 ps", viewer.status.GetInput())
        press_key(viewer, "space")
        self.assertFalse(viewer.playing)


if __name__ == "__main__":
    unittest.main()
