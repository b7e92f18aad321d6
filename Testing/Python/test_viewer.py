#!/usr/bin/python3
# SPDX-License-Identifier: GPL-3.0-or-later
"""The interactive magnifier driven without a person: a scripted click through the interactor
places the membrane where the click was; keys change the tiles, method, style and play the
trajectory; a click off the surface and a failing mapping say why in the status line, tiles
that do not fit say how many did. The
structured cutaway: its key, the fraction (API and slider), inversion and random order change
what is drawn without a new assignment of the molecules; bad fractions are refused."""
import math
import os
import tempfile
import unittest

import numpy as np
from vtkmodules.util.numpy_support import vtk_to_numpy

from mesolens import array_names
from mesolens.lens import LensError, MembraneLens
from mesolens.viewer import CUT_SLIDER_ENDS, LensViewer

DATA = os.environ.get("MESOLENS_DATA_DIR", "Data")
MESH = os.path.join(DATA, "meshes", "mito5_outer_membrane.obj")
PATCH = os.path.join(DATA, "membranes", "dppc128_slipids_323K.gro")
YIIP = os.path.join(DATA, "membranes", "yiip_popepopg.gro")
# A stem cell's membrane, about 20 µm across.
COARSE_CELL = os.path.join(DATA, "meshes", "hipsc_cell_membrane_1.obj")
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
    codes = {"plus": "+", "minus": "-", "space": " ", "bracketleft": "[", "bracketright": "]"}
    viewer.interactor.SetKeySym(name)
    viewer.interactor.SetKeyCode(codes.get(name, name))
    viewer.interactor.InvokeEvent("CharEvent")


def look_at_vertex_1000(viewer):
    """Points the viewer's camera at the vertex 1000 side of the organelle from 2 µm outside,
    the whole organelle in view; returns the vertex."""
    lens = viewer.lens
    surface = lens.surface.GetOutput()
    target = surface.GetPoint(1000)
    centre = surface.GetCenter()
    outward = [target[d] - centre[d] for d in range(3)]
    length = math.sqrt(sum(v * v for v in outward))
    camera = lens.renderer.GetActiveCamera()
    camera.SetFocalPoint(target)
    camera.SetPosition([target[d] + 2.0 * outward[d] / length for d in range(3)])
    camera.SetViewUp(0, 0, 1)
    lens.renderer.ResetCameraClippingRange()
    viewer.window.Render()
    return target


class Viewer(unittest.TestCase):
    def setUp(self):
        self.lens = MembraneLens(MESH, PATCH)
        self.lens.set_tiles(2)
        self.viewer = LensViewer(self.lens, (400, 300), offscreen=True)
        self.target = look_at_vertex_1000(self.viewer)

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

    def test_tiles_that_do_not_fit_map_fewer_and_the_status_says_so(self):
        # The organelle read in units of 0.1 µm: 5 x 5 DPPC tiles then need a disk of radius
        # 0.63 units, more than this 0.17 x 0.3 x 0.6 organelle offers.
        self.lens = MembraneLens(MESH, PATCH, mesh_unit_angstrom=1e3)
        self.lens.set_tiles(5)
        self.viewer = LensViewer(self.lens, (400, 300), offscreen=True)
        self.lens.place(self.target)
        self.assertIsNotNone(self.lens.centre, self.viewer.message)
        mapped = self.lens.tiles_mapped()
        self.assertGreaterEqual(mapped, 1)
        self.assertLess(mapped, 5)
        self.assertIn("instead of 5 x 5", self.lens.mapping_note())
        self.viewer.window.Render()
        self.assertIn(f"{mapped} x {mapped} tiles of 5 x 5", self.viewer.status.GetInput())
        atoms = self.lens.membrane.GetOutput().GetNumberOfPoints()
        self.assertEqual(self.lens.atom_count(), atoms * mapped * mapped)

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


def drawn_atoms(lens):
    """Atoms the atom mapper draws: its input's (times the tiles when it warps on the GPU) less
    those its visibility masks hide."""
    lens.renderer.GetRenderWindow().Render()
    count = lens.atoms.GetInput().GetNumberOfPoints()
    warped = lens.atoms.GetNumberOfInputConnections(1) > 0 and lens.atoms.GetInputConnection(1, 0)
    if warped:
        count *= lens.tiles * lens.tiles
    return count - lens.atoms.GetHiddenAtomCount()


def patch_molecule_sizes(lens):
    """Atoms per molecule of the patch, in order of first appearance."""
    ids = vtk_to_numpy(lens._patch_source().GetOutput().GetPointData()
                       .GetArray(array_names.MoleculeId))
    _, first, sizes = np.unique(ids, return_index=True, return_counts=True)
    return sizes[np.argsort(first)]


def cut_atoms(lens):
    """Per point of the cutaway's input (an atom, or on the GPU a molecule's centre in a tile),
    whether its molecule's centre is on the cut side of the lens' cut plane (counted here, not
    by the filter); the molecules in the cut; the largest molecule's atoms; and the atoms each
    point stands for."""
    atoms = lens.cutaway.GetInput()
    points = vtk_to_numpy(atoms.GetPoints().GetData()).astype(np.float64)
    molecule = np.unique(vtk_to_numpy(atoms.GetPointData().GetArray(array_names.MoleculeId)),
                         return_inverse=True)[1]
    sizes = np.bincount(molecule)
    centres = np.column_stack([np.bincount(molecule, points[:, d]) for d in range(3)])
    centres /= sizes[:, None]
    in_cut = (centres - lens.cut_origin) @ np.asarray(lens.cut_normal) >= 0
    if lens.on_gpu:
        patch_sizes = patch_molecule_sizes(lens)
        weights = np.tile(patch_sizes, len(points) // len(patch_sizes))
        return in_cut[molecule], int(in_cut.sum()), int(patch_sizes.max()), weights
    return in_cut[molecule], int(in_cut.sum()), int(sizes.max()), np.ones(len(points))


def visible_mask(lens):
    lens.cut_counts()  # brings the cutaway up to date
    return vtk_to_numpy(lens.cutaway.GetOutput().GetPointData().GetArray(array_names.Visible)).copy()


class Cutaway(unittest.TestCase):
    def setUp(self):
        self.lens = MembraneLens(MESH, PATCH)
        self.lens.set_tiles(2)
        self.lens.place(self.lens.surface.GetOutput().GetPoint(1000))
        self.viewer = LensViewer(self.lens, (400, 300), offscreen=True)
        self.lens.look_at_patch()
        self.viewer.window.Render()
        self.all_atoms = drawn_atoms(self.lens)

    def test_key_cuts_open_and_the_fraction_hides_half_of_the_cut(self):
        self.assertEqual(self.all_atoms, 4 * self.lens.membrane.GetOutput().GetNumberOfPoints())
        press_key(self.viewer, "o")
        self.assertTrue(self.lens.cutaway_on, self.viewer.message)
        self.assertTrue(self.viewer.plane_widget.GetEnabled())
        self.assertTrue(self.viewer.slider_widget.GetEnabled())
        # The plane goes through the lens point and faces the camera.
        camera = self.lens.renderer.GetActiveCamera()
        for got, want in zip(self.lens.cut_normal, camera.GetDirectionOfProjection()):
            self.assertAlmostEqual(got, -want, places=6)
        self.assertEqual(self.lens.cut_origin, self.lens.centre)
        for got, want in zip(self.viewer.plane_representation.GetOrigin(), self.lens.centre):
            self.assertAlmostEqual(got, want, places=9)

        self.viewer.set_cut_fraction(0.5)
        self.assertTrue(self.lens.on_gpu)  # the polynomial warp stays on the GPU
        atom_in_cut, molecules, largest, weights = cut_atoms(self.lens)
        self.assertGreater(molecules, 50)
        hidden, in_cut = self.lens.cut_counts()
        self.assertEqual(in_cut, molecules)
        self.assertEqual(hidden, math.floor(0.5 * molecules + 0.5))
        hidden_atoms = self.all_atoms - drawn_atoms(self.lens)
        self.assertLessEqual(abs(hidden_atoms - 0.5 * weights[atom_in_cut].sum()), largest)
        self.assertEqual(drawn_atoms(self.lens), self.lens.atom_count())
        status = self.viewer.status.GetInput()
        self.assertIn(f"hidden {hidden:,} of {in_cut:,} in cut", status)
        self.assertIn("structured (n), wireframe (i)", status)
        self.assertEqual(self.viewer.slider_representation.GetValue(), 50.0)

        # The slider and the plane only reorder: the molecules stay assigned once.
        for fraction in (0.2, 0.9, 0.35, 1.0, 0.65):
            self.viewer.set_cut_fraction(fraction)
            # Half-way counts round up (Python's round() would go to the even one).
            self.assertEqual(self.lens.cut_counts()[0], math.floor(fraction * in_cut + 0.5))
            # The mapper gets a new mask only, a bit per molecule and tile (in 32-bit words):
            # no positions, no warp.
            drawn_atoms(self.lens)
            bits = 4 * len(patch_molecule_sizes(self.lens))
            self.assertEqual(self.lens.atoms.GetLastUploadBytes(), 4 * ((bits + 31) // 32))
        self.viewer.set_cut_plane(self.lens.centre, [-v for v in self.lens.cut_normal])
        self.viewer.set_cut_plane(self.lens.centre, self.lens.seed_normal())
        self.assertEqual(self.lens.cutaway.GetNumberOfAssignments(), 1)

        self.viewer.set_cut_fraction(0.0)
        self.assertEqual(drawn_atoms(self.lens), self.all_atoms)
        self.assertEqual(self.lens.cut_counts()[0], 0)
        self.viewer.set_cut_fraction(0.5)
        self.assertLess(drawn_atoms(self.lens), self.all_atoms)

        press_key(self.viewer, "o")
        self.assertFalse(self.lens.cutaway_on)
        self.assertFalse(self.viewer.plane_widget.GetEnabled())
        self.assertFalse(self.viewer.slider_widget.GetEnabled())
        self.assertEqual(drawn_atoms(self.lens), self.all_atoms)
        self.assertNotIn("hidden", self.viewer.status.GetInput())
        self.assertIn("cutaway off (o)", self.viewer.status.GetInput())

    def test_inversion_and_random_order_change_the_mask_not_the_count(self):
        self.viewer.toggle_cutaway()
        self.viewer.set_cut_fraction(0.5)
        structured = visible_mask(self.lens)
        hidden = self.lens.cut_counts()[0]
        press_key(self.viewer, "i")
        self.assertTrue(self.lens.cut_inverted)
        patches = visible_mask(self.lens)
        self.assertIn("patches (i)", self.viewer.status.GetInput())
        press_key(self.viewer, "i")
        press_key(self.viewer, "n")
        self.assertTrue(self.lens.cut_random)
        random = visible_mask(self.lens)
        self.assertIn("random removal (n)", self.viewer.status.GetInput())
        for mask in (patches, random):
            self.assertFalse(np.array_equal(mask, structured))
            self.assertEqual(self.lens.cut_counts()[0], hidden)
        self.assertFalse(np.array_equal(patches, random))
        # Outside the cut nothing is hidden, whatever the order.
        atom_in_cut = cut_atoms(self.lens)[0]
        for mask in (structured, patches, random):
            self.assertTrue(mask[~atom_in_cut].all())
            self.assertFalse(mask[atom_in_cut].all())
        self.assertEqual(self.lens.cutaway.GetNumberOfAssignments(), 1)

    def test_the_plane_widget_moves_the_cut(self):
        self.viewer.toggle_cutaway()
        interactor = self.viewer.interactor
        x, y = display_point(self.lens.renderer, self.lens.centre)
        origin, normal = self.lens.cut_origin, self.lens.cut_normal
        in_cut = self.lens.cut_counts()[1]
        # Up with the mouse over the plane pushes it along its arrow: fewer molecules in the cut.
        interactor.SetEventInformation(x + 30, y + 10, 0, 0, "", 0, "Up")
        interactor.InvokeEvent("KeyPressEvent")
        step = [self.lens.cut_origin[d] - origin[d] for d in range(3)]
        self.assertGreater(sum(step[d] * normal[d] for d in range(3)), 0)
        self.assertLess(self.lens.cut_counts()[1], in_cut)
        # A drag from the arrow (seen end on, at the plane's centre) tilts the plane.
        interactor.SetEventInformation(x, y, 0, 0)
        interactor.InvokeEvent("LeftButtonPressEvent")
        interactor.SetEventInformation(x + 40, y, 0, 0)
        interactor.InvokeEvent("MouseMoveEvent")
        interactor.InvokeEvent("LeftButtonReleaseEvent")
        tilt = math.degrees(math.acos(sum(a * b for a, b in zip(self.lens.cut_normal, normal))))
        self.assertGreater(tilt, 5)
        for got, want in zip(self.viewer.plane_representation.GetNormal(), self.lens.cut_normal):
            self.assertAlmostEqual(got, want, places=9)
        self.assertEqual(self.lens.cutaway.GetNumberOfAssignments(), 1)
        self.assertEqual(drawn_atoms(self.lens), self.lens.atom_count())

    def test_a_click_on_the_slider_sets_the_fraction(self):
        self.viewer.toggle_cutaway()
        width, height = self.viewer.window.GetSize()
        (x1, y), (x2, _) = CUT_SLIDER_ENDS
        # A quarter of the way along the tube (the end caps take a little of each end).
        x = int(round((x1 + 0.25 * (x2 - x1)) * width))
        press_and_release(self.viewer, x, int(round(y * height)))
        self.assertGreater(self.lens.cut_fraction, 0.15)
        self.assertLess(self.lens.cut_fraction, 0.35)
        self.assertIsNotNone(self.lens.centre)
        self.assertEqual(self.lens.cutaway.GetNumberOfAssignments(), 1)
        self.assertIn(f"({self.lens.cut_fraction:.0%}, slider)", self.viewer.status.GetInput())

    def test_bad_fractions_and_planes_are_refused(self):
        self.viewer.toggle_cutaway()
        self.viewer.set_cut_fraction(0.3)
        for bad in (1.5, -0.1, float("nan"), "half"):
            with self.assertRaisesRegex(LensError, "between 0 and 1"):
                self.viewer.set_cut_fraction(bad)
        self.assertAlmostEqual(self.lens.cut_fraction, 0.3)
        with self.assertRaisesRegex(LensError, "must not be zero"):
            self.viewer.set_cut_plane(self.lens.centre, (0, 0, 0))
        with self.assertRaisesRegex(LensError, "finite"):
            self.viewer.set_cut_plane(self.lens.centre, (0, float("inf"), 1))

    def test_cutaway_keys_before_placing_say_why(self):
        lens = MembraneLens(MESH, PATCH)
        viewer = LensViewer(lens, (200, 150), offscreen=True)
        press_key(viewer, "o")
        self.assertFalse(lens.cutaway_on)
        self.assertIn("place the membrane first", viewer.status.GetInput())
        self.assertFalse(viewer.plane_widget.GetEnabled())
        press_key(viewer, "i")
        self.assertIn("the cutaway is off", viewer.message)

    def test_new_tiles_and_method_keep_the_cut(self):
        self.viewer.toggle_cutaway()
        self.viewer.set_cut_fraction(0.8)
        normal = self.lens.cut_normal
        press_key(self.viewer, "plus")
        self.assertEqual(self.lens.tiles, 3)
        press_key(self.viewer, "m")
        self.assertTrue(self.lens.cutaway_on)
        self.assertEqual(self.lens.cut_normal, normal)
        hidden, in_cut = self.lens.cut_counts()
        self.assertEqual(hidden, round(0.8 * in_cut))
        patch_atoms = self.lens.membrane.GetOutput().GetNumberOfPoints()
        self.assertLess(drawn_atoms(self.lens), 9 * patch_atoms)


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

    def test_the_cutaway_plays_with_the_trajectory_and_keeps_its_assignment(self):
        lens = MembraneLens(MESH, YIIP, YIIP_XTC)
        lens.set_tiles(1)
        lens.place(lens.surface.GetOutput().GetPoint(1000))
        viewer = LensViewer(lens, (200, 150), offscreen=True)
        self.assertTrue(viewer.toggle_cutaway(), viewer.message)
        frames = []
        for _ in range(3):
            viewer.step()
            cut = lens.cutaway.GetOutput()
            frames.append(vtk_to_numpy(cut.GetPoints().GetData()).copy())
            self.assertGreater(lens.cut_counts()[0], 0)
        # Every frame is cut (the atoms move), and the molecules are assigned once.
        self.assertGreater(np.abs(frames[1] - frames[0]).max(), 1e-5)
        self.assertEqual(lens.cutaway.GetNumberOfAssignments(), 1)
        self.assertEqual(viewer.time_index, 3)


if __name__ == "__main__":
    unittest.main()
