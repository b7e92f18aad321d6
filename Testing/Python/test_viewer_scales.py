#!/usr/bin/python3
# SPDX-License-Identifier: GPL-3.0-or-later
"""The magnifier between the cell's scale and the atoms', driven through the interactor: a click
flies to the patch until its atoms fill the window; f flies to the whole cell and back to the same
view; 30 wheel steps over the patch reach the atoms from the whole cell without passing through
the surface; the inset shows the atoms while the window shows the cell (x swaps them, [ and ]
resize the inset); a flight moves by equal factors of distance, stops at a press and, in VTK's
event loop, runs to its end frame by frame; the scale bar and the status line say which scale is
shown."""
import math
import unittest

from vtkmodules.util.misc import calldata_type
from vtkmodules.util.vtkConstants import VTK_INT
from vtkmodules.vtkFiltersCore import vtkImplicitPolyDataDistance

from mesolens.camera import (CameraPose, interpolate, distance, pose_of, poses_match)
from mesolens.lens import MembraneLens
from mesolens.scale_bar import length_label, round_length
from mesolens.viewer import FLIGHT_SECONDS, INSET_SIZES, LensViewer
from test_viewer import (COARSE_CELL, MESH, PATCH, YIIP, YIIP_XTC, display_point,
                         look_at_vertex_1000, press_and_release, press_key)

SIZE = (400, 300)


def wheel(viewer, x, y, steps, forward=True):
    for _ in range(steps):
        viewer.interactor.SetEventInformation(x, y, 0, 0)
        viewer.interactor.InvokeEvent("MouseWheelForwardEvent" if forward else
                                      "MouseWheelBackwardEvent")


def shows_whole(renderer, bounds):
    """Whether every corner of `bounds` projects inside the renderer's viewport."""
    width, height = renderer.GetRenderWindow().GetSize()
    x0, y0, x1, y1 = renderer.GetViewport()
    for i in range(8):
        corner = (bounds[i & 1], bounds[2 + ((i >> 1) & 1)], bounds[4 + ((i >> 2) & 1)])
        x, y = display_point(renderer, corner)
        if not (x0 * width <= x <= x1 * width and y0 * height <= y <= y1 * height):
            return False
    return True


class Scales(unittest.TestCase):
    def setUp(self):
        self.lens = MembraneLens(MESH, PATCH)
        self.lens.set_tiles(2)
        self.viewer = LensViewer(self.lens, SIZE, offscreen=True)
        self.target = look_at_vertex_1000(self.viewer)

    def click_target(self):
        x, y = display_point(self.lens.renderer, self.target)
        press_and_release(self.viewer, x, y)
        self.assertIsNotNone(self.lens.centre, self.viewer.message)

    def atom_share(self, renderer=None):
        """The share of the renderer's viewport that the mapped atoms cover."""
        renderer = renderer or self.lens.renderer
        width, height = SIZE
        x0, y0, x1, y1 = renderer.GetViewport()
        pixels = int(width * (x1 - x0)) * int(height * (y1 - y0))
        return self.lens.patch_pixels(self.viewer.window, renderer) / pixels

    def test_a_click_flies_to_the_patch_and_its_atoms_fill_the_window(self):
        self.assertLess(self.atom_share(), 0.01)
        self.click_target()
        self.assertGreaterEqual(self.atom_share(), 0.4)
        self.assertTrue(self.viewer.at_patch)
        self.viewer.window.Render()
        self.assertIn("shown: atoms", self.viewer.status.GetInput())
        # From outside, at a slant: the camera is on the surface's outer side, not on its normal.
        camera = self.lens.renderer.GetActiveCamera()
        _, outward, _ = self.lens.patch_geometry()
        eye = [camera.GetPosition()[d] - camera.GetFocalPoint()[d] for d in range(3)]
        cosine = sum(eye[d] * outward[d] for d in range(3)) / math.sqrt(sum(v * v for v in eye))
        self.assertAlmostEqual(math.degrees(math.acos(cosine)), 35.0, delta=1.0)

    def test_f_flies_to_the_whole_cell_and_back_to_the_same_view(self):
        press_key(self.viewer, "f")
        self.assertIn("no patch yet", self.viewer.status.GetInput())
        self.click_target()
        at_patch = pose_of(self.lens.renderer.GetActiveCamera())
        press_key(self.viewer, "f")
        self.assertFalse(self.viewer.at_patch)
        self.assertTrue(shows_whole(self.lens.renderer, self.lens.surface.GetOutput().GetBounds()))
        self.assertIn("shown: whole cell", self.viewer.status.GetInput())
        self.assertGreaterEqual(self.viewer.scale_bar.angstrom, 1000.0)  # 100 nm or more
        press_key(self.viewer, "f")
        self.assertTrue(poses_match(pose_of(self.lens.renderer.GetActiveCamera()), at_patch))
        self.assertIn("shown: atoms", self.viewer.status.GetInput())
        self.assertLessEqual(self.viewer.scale_bar.angstrom, 50.0)

    def test_more_tiles_are_framed_by_the_next_flight(self):
        self.click_target()
        two_tiles = distance(self.viewer.patch_pose)
        press_key(self.viewer, "plus")
        self.assertEqual(self.lens.tiles, 3)
        self.assertGreater(distance(self.viewer.patch_pose), 1.3 * two_tiles)

    def test_thirty_wheel_steps_over_the_patch_reach_the_atoms_from_the_cell(self):
        self.click_target()
        press_key(self.viewer, "f")
        self.assertLess(self.atom_share(), 0.05)
        x, y = display_point(self.lens.renderer, self.lens.centre)
        wheel(self.viewer, x, y, 30)
        self.assertGreaterEqual(self.atom_share(), 0.95)
        # Outside the surface.
        outside = vtkImplicitPolyDataDistance()
        outside.SetInput(self.lens.surface.GetOutput())
        camera = self.lens.renderer.GetActiveCamera().GetPosition()
        self.assertGreater(outside.EvaluateFunction(camera), 0.0)
        self.assertIn("shown: atoms", self.viewer.status.GetInput())
        # Where it zoomed in, the wheel draws back: 30 steps back show the organelle's scale again.
        wheel(self.viewer, x, y, 30, forward=False)
        self.assertLess(self.atom_share(), 0.05)

    def test_atoms_a_few_angstrom_away_are_drawn_in_a_cell_tens_of_micrometres_across(self):
        # The stem cell's membrane: VTK would put the near plane 20 Å out at this scale.
        lens = MembraneLens(COARSE_CELL, PATCH)
        lens.set_tiles(1)
        viewer = LensViewer(lens, SIZE, offscreen=True)
        lens.place(lens.surface.GetOutput().GetPoint(0))
        viewer.place_camera_at_patch()
        x, y = display_point(lens.renderer, lens.centre)
        wheel(viewer, x, y, 12)
        camera = lens.renderer.GetActiveCamera()
        self.assertGreater(camera.GetClippingRange()[1] * 1e-4, 20 * lens.scale)
        self.assertLess(camera.GetClippingRange()[0], 5 * lens.scale)
        self.lens, self.viewer = lens, viewer
        self.assertGreaterEqual(self.atom_share(), 0.95)

    def test_the_inset_shows_the_atoms_while_the_window_shows_the_cell(self):
        self.click_target()
        press_key(self.viewer, "f")
        press_key(self.viewer, "b")
        inset = self.viewer.inset
        self.assertIsNotNone(inset)
        self.assertGreaterEqual(self.atom_share(inset), 0.4)
        self.assertTrue(shows_whole(self.lens.renderer, self.lens.surface.GetOutput().GetBounds()))
        self.assertTrue(self.lens.outline_actor.GetVisibility())
        # x: the window shows the atoms and the inset the whole cell.
        press_key(self.viewer, "x")
        self.assertTrue(self.viewer.at_patch)
        self.assertGreaterEqual(self.atom_share(), 0.4)
        self.assertTrue(shows_whole(inset, self.lens.surface.GetOutput().GetBounds()))
        # [ and ] resize it, within its limits.
        width = inset.GetViewport()[2]
        press_key(self.viewer, "bracketright")
        self.assertGreater(inset.GetViewport()[2], width)
        for _ in range(20):
            press_key(self.viewer, "bracketleft")
        self.assertAlmostEqual(inset.GetViewport()[2], INSET_SIZES[0])
        press_key(self.viewer, "b")
        self.assertIsNone(self.viewer.inset)
        self.assertEqual(self.viewer.window.GetRenderers().GetNumberOfItems(), 1)

    def test_the_wheel_over_the_background_and_keys_out_of_turn_say_or_do_what_vtk_does(self):
        camera = self.lens.renderer.GetActiveCamera()
        before = distance(pose_of(camera))
        wheel(self.viewer, 2, 2, 1)  # the background: toward the focal point, as VTK does
        self.assertAlmostEqual(distance(pose_of(camera)), before * 0.78, delta=1e-6 * before)
        press_key(self.viewer, "x")
        self.assertIn("the inset is off", self.viewer.status.GetInput())
        press_key(self.viewer, "b")
        press_key(self.viewer, "x")
        self.assertIn("no patch yet", self.viewer.status.GetInput())
        self.viewer.resize_inset(float("nan"))
        self.assertTrue(INSET_SIZES[0] <= self.viewer.inset.GetViewport()[2] <= INSET_SIZES[1])

    def test_a_click_with_the_inset_on_keeps_the_window_at_the_cell(self):
        press_key(self.viewer, "b")
        before = pose_of(self.lens.renderer.GetActiveCamera())
        self.click_target()
        self.assertTrue(poses_match(pose_of(self.lens.renderer.GetActiveCamera()), before))
        self.assertGreaterEqual(self.atom_share(self.viewer.inset), 0.4)

    def test_a_flight_moves_by_equal_factors_and_a_press_stops_it(self):
        self.click_target()
        at_patch = pose_of(self.lens.renderer.GetActiveCamera())
        self.assertTrue(self.viewer.fly_to_cell(animate=True))
        self.assertTrue(self.viewer.flying())
        started = self.viewer._flight[3]
        self.assertTrue(self.viewer.advance_flight(started + FLIGHT_SECONDS / 2))
        halfway = distance(pose_of(self.lens.renderer.GetActiveCamera()))
        self.assertAlmostEqual(math.log(halfway),
                               (math.log(distance(at_patch)) +
                                math.log(distance(self.viewer.cell_pose))) / 2, places=6)
        self.assertFalse(self.viewer.advance_flight(started + FLIGHT_SECONDS + 0.01))
        self.assertTrue(poses_match(pose_of(self.lens.renderer.GetActiveCamera()),
                                    self.viewer.cell_pose))
        # A press stops a flight where it is: a later tick moves the camera no more.
        self.viewer.fly_to_patch(animate=True)
        started = self.viewer._flight[3]
        self.viewer.advance_flight(started + FLIGHT_SECONDS / 4)
        stopped = pose_of(self.lens.renderer.GetActiveCamera())
        self.assertFalse(poses_match(stopped, at_patch))
        press_and_release(self.viewer, 5, SIZE[1] - 5, drag=20)
        self.assertFalse(self.viewer.flying())
        self.assertFalse(self.viewer.advance_flight(started + FLIGHT_SECONDS))
        self.assertTrue(poses_match(pose_of(self.lens.renderer.GetActiveCamera()), stopped))


def run_event_loop(viewer, on_tick, period_ms, most_ticks):
    """Runs the viewer through start(), in a window on the (virtual) display and VTK's own event
    loop, calling on_tick(n) (n = 1, 2, ...) every `period_ms` from a timer of its own until it
    returns True or `most_ticks` have passed; returns the number of ticks."""
    ticks = []

    @calldata_type(VTK_INT)
    def watch(_caller, _event, timer):
        if timer != watcher:
            return
        ticks.append(1)
        if on_tick(len(ticks)) or len(ticks) >= most_ticks:
            viewer.interactor.TerminateApp()

    viewer.interactor.AddObserver("TimerEvent", watch)
    watcher = viewer.interactor.CreateRepeatingTimer(period_ms)
    viewer.start()
    return len(ticks)


class EventLoop(unittest.TestCase):
    def test_f_flies_in_the_event_loop_and_ends_at_the_cell(self):
        # The flight's timers, one per frame, run it to its end.
        lens = MembraneLens(MESH, PATCH)
        lens.set_tiles(1)
        lens.place(lens.surface.GetOutput().GetPoint(1000))
        viewer = LensViewer(lens, (200, 150))
        viewer.place_camera_at_patch()
        frames = []
        lens.renderer.AddObserver("EndEvent", lambda *_: frames.append(1))

        def on_tick(tick):
            if tick == 1:
                viewer.key("f")
                frames.clear()
                return False
            return not viewer.flying()

        self.assertLess(run_event_loop(viewer, on_tick, 100, 100), 100)
        self.assertFalse(viewer.flying())
        self.assertGreater(len(frames), 2)  # drawn on the way, not in one jump
        self.assertTrue(poses_match(pose_of(lens.renderer.GetActiveCamera()), viewer.cell_pose))

    def test_space_plays_the_trajectory_in_the_event_loop(self):
        lens = MembraneLens(MESH, YIIP, YIIP_XTC)
        lens.set_tiles(1)
        lens.place(lens.surface.GetOutput().GetPoint(1000))
        viewer = LensViewer(lens, (200, 150))

        def on_tick(tick):
            if tick == 1 or viewer.time_index >= 2:
                viewer.key("space")  # play, then pause
            return viewer.time_index >= 2

        run_event_loop(viewer, on_tick, 150, 50)
        self.assertGreaterEqual(viewer.time_index, 2)
        self.assertFalse(viewer.playing)


class CameraMoves(unittest.TestCase):
    def test_a_flight_starts_and_ends_at_its_poses_and_keeps_the_target_in_view(self):
        start = CameraPose((0.0, 0.0, 1000.0), (0.0, 0.0, 0.0), (0.0, 1.0, 0.0), 30.0)
        end = CameraPose((100.0, 0.0, 1.0), (100.0, 0.0, 0.0), (1.0, 0.0, 0.0), 30.0)
        self.assertTrue(poses_match(interpolate(start, end, 0.0), start))
        self.assertTrue(poses_match(interpolate(start, end, 1.0), end))
        previous = distance(start)
        for step in range(1, 20):
            pose = interpolate(start, end, step / 20)
            self.assertLess(distance(pose), previous)
            previous = distance(pose)
            # The target stays within the 30 degree view all the way in.
            to_target = [end.focal_point[d] - pose.position[d] for d in range(3)]
            view = [pose.focal_point[d] - pose.position[d] for d in range(3)]
            cosine = (sum(a * b for a, b in zip(to_target, view)) /
                      math.sqrt(sum(v * v for v in to_target) * sum(v * v for v in view)))
            self.assertLess(math.degrees(math.acos(min(1.0, cosine))), 15.0)

    def test_scale_bar_lengths_are_round_and_named_in_their_unit(self):
        self.assertEqual(round_length(7.3), 5.0)
        self.assertEqual(round_length(0.0199), 0.01)
        self.assertEqual(round_length(250.0), 200.0)
        self.assertEqual(length_label(5.0), "5 Å")
        self.assertEqual(length_label(200.0), "20 nm")
        self.assertEqual(length_label(2e4), "2 µm")


if __name__ == "__main__":
    unittest.main()
