# SPDX-License-Identifier: GPL-3.0-or-later
"""The interactive magnifier: click a cell surface, see the membrane's atoms mapped there.

``LensViewer`` puts a ``MembraneLens`` in a VTK window. A left click on the surface (a press and a
release without dragging; dragging turns the camera as usual) maps the patch around the clicked
point, and the camera flies to it: the patch then fills the window, seen from outside at a slant
that shows the bilayer's thickness. Any press, wheel step or key stops a flight where it is.
The mouse wheel moves toward what is under the cursor (an atom, the surface), keeping it under
the cursor, by a constant share of the distance per step: from the whole cell to the atoms in
about 30 steps, never through the surface. A scale bar at the lower right follows the zoom.
Keys:

    f       fly between the whole cell and the patch
    b       inset on / off: a second view in the upper left that shows the other scale (the
            patch close up while the window shows the cell, the cell while it shows the patch;
            the lens is outlined on the cell)
    x       swap the window's and the inset's views    [ / ]   smaller / larger inset
    + / -   more / fewer tiles (k x k, 1..15)     m   next mapping method
    s       space-filling / ball-and-stick        a   ambient occlusion (SSAO) on / off
    h       shadows on / off
    space   play / pause the trajectory           l   refinement level (frames in between)
    c       screenshot (mesolens-NNNN.png)        v   save the camera (mesolens-camera.txt, for
                                                      mesolens render --camera)
    o       structured cutaway on / off           i   cutaway: patches / wireframe (inverted)
    n       cutaway: random / structured removal
    q       quit

With the inset on, a click maps the new patch and the inset shows it; the window's view stays.

The structured cutaway (o, once the membrane is placed) cuts the mapped membrane open with a plane
through the lens point facing the camera: of the molecules on the camera's side of it (where its
arrow points) the slider at the top right hides 0 to 100 % (50 % at first), those at the centres
of a triangle mesh on the surface first, so that a wireframe remains (i: the edges first, so that
patches remain; n: at random, for comparison). Drag its arrow (at first seen end on, at the
plane's centre) to tilt the plane; Up / Down with the mouse over the plane push it along the
arrow or back (Ctrl: half steps). Clicks and camera drags that start on the plane go to the
plane: start them beside it.

Three lines at the bottom show the atom count, the last frame time and the settings, the
cutaway's (off, or its mode and "hidden X of Y in cut", counted in molecules), and the scale in
view (whole cell, membrane or atoms, with the length of a pixel); messages (a click off the
surface, a mapping that fails, with its reason) replace them until the next action.
"""
import math
import os
import time

from vtkmodules.util.misc import calldata_type
from vtkmodules.util.vtkConstants import VTK_INT
from vtkmodules.vtkInteractionWidgets import (vtkImplicitPlaneRepresentation,
                                              vtkImplicitPlaneWidget2,
                                              vtkSliderRepresentation2D, vtkSliderWidget)
from vtkmodules.vtkRenderingCore import (vtkCellPicker, vtkRenderer, vtkRenderWindow,
                                         vtkRenderWindowInteractor, vtkTextActor)
from vtkmodules.vtkInteractionStyle import vtkInteractorStyleTrackballCamera
import vtkmodules.vtkRenderingFreeType  # noqa: F401 (text)
import vtkmodules.vtkRenderingOpenGL2  # noqa: F401 (the OpenGL factory)

from .camera import (WHEEL_FACTOR, apply_pose, dolly_toward, interpolate, keep_near_things,
                     point_under, pose_of)
from .lens import METHODS, LensError, write_camera_file, write_png
from .scale_bar import ScaleBar, length_label

CLICK_TOLERANCE = 3  # pixels a click may move and still be a click
CUT_SLIDER_ENDS = ((0.62, 0.93), (0.95, 0.93))  # the fraction slider, normalized display
FLIGHT_SECONDS = 1.2  # a flight between the cell and the patch
FLIGHT_TICK_MS = 15  # how often a flight asks for a frame (it renders as fast as it can)
# The wheel stops this far from what is under the cursor, Å: about an atom's radius.
NEAREST_APPROACH = 2.0
INSET_WIDTH = 0.35  # the inset's width and height as shares of the window's, at first
INSET_SIZES = (0.2, 0.6)  # the inset's width as a share of the window's, smallest and largest
INSET_STEP = 0.05  # [ and ] change the inset's width by this share of the window's


class LensViewer:
    """A window onto `lens`; see the module's description. `offscreen`: no window on screen
    (for tests and batch use; events are then given through `interactor`)."""

    def __init__(self, lens, size=(1024, 768), offscreen=False):
        self.lens = lens
        self.window = vtkRenderWindow()
        self.window.SetSize(*size)
        self.window.SetMultiSamples(0)
        self.window.SetWindowName("MesoLens")
        if offscreen:
            self.window.SetOffScreenRendering(1)
        self.window.AddRenderer(lens.renderer)
        self.interactor = vtkRenderWindowInteractor()
        self.interactor.SetRenderWindow(self.window)
        self.style = vtkInteractorStyleTrackballCamera()
        self.interactor.SetInteractorStyle(self.style)
        self.picker = vtkCellPicker()
        self.picker.SetTolerance(0.0005)
        self.picker.PickFromListOn()
        self.picker.AddPickList(lens.surface_actor)
        self.status = vtkTextActor()
        self.status.GetTextProperty().SetFontSize(16)
        self.status.GetTextProperty().SetColor(0.9, 0.9, 0.9)
        self.status.SetPosition(8, 8)
        lens.renderer.AddActor2D(self.status)
        self.message = ""
        self.playing = False
        self.time_index = 0
        self.screenshots = 0
        self._press = None
        self._timer = None
        # Above the three status lines.
        self.scale_bar = ScaleBar(lens.renderer, lens.scale, bottom=80)
        # Camera poses of the two scales: the patch close up (set when a patch is placed) and
        # the whole cell; which of them the window shows, or flies to.
        self.patch_pose = None
        self.cell_pose = None
        self.at_patch = False
        self._flight = None  # (renderer, start pose, end pose, start time, seconds)
        self._flight_timer = None
        self._running = False  # the interactor's event loop runs (start())
        self.inset = None  # the inset's renderer while it is on
        self.inset_bar = None
        self.inset_width = INSET_WIDTH
        # Observers on the style replace its own handling of these events (the style holds the
        # mouse focus between press and release): each calls the style's default itself.
        self.style.AddObserver("LeftButtonPressEvent", self._on_press)
        self.style.AddObserver("LeftButtonReleaseEvent", self._on_release)
        self.style.AddObserver("MiddleButtonPressEvent", self._on_other_press)
        self.style.AddObserver("RightButtonPressEvent", self._on_other_press)
        self.style.AddObserver("MouseWheelForwardEvent", self._on_wheel)
        self.style.AddObserver("MouseWheelBackwardEvent", self._on_wheel)
        self.style.AddObserver("CharEvent", self._on_char)
        self.interactor.AddObserver("TimerEvent", self._on_timer)
        self._make_cut_widgets()
        lens.renderer.AddObserver("StartEvent", lambda *_: self._before_frame())
        lens.renderer.ResetCamera()
        self._show_status()

    # Actions -------------------------------------------------------------------------------

    def click(self, x, y):
        """What a click at display pixel (x, y) does: maps the patch there and flies to it (with
        the inset on and the window at the cell, the inset shows it instead), or says why not.
        Returns True when the patch was placed."""
        renderer = self._renderer_at(x, y)
        if not self.picker.Pick(x, y, 0, renderer):
            self.message = "that click is off the surface: click on the cell"
            self.window.Render()
            return False
        if not self._place(self.picker.GetPickPosition()):
            return False
        self._frame_patch()
        if self.inset is not None and not self.at_patch:
            self._show_other_scale_in_inset()
            self.window.Render()
        else:
            self.fly_to_patch()
        return True

    def _place(self, point):
        moved = self.lens.centre is None or tuple(point) != self.lens.centre
        try:
            self.lens.place(point)
            self.message = ""
            ok = True
        except LensError as error:
            self.message = str(error)
            ok = False
        self._fit_cut_widgets(face_camera=moved)
        self.window.Render()
        return ok

    def key(self, name):
        """What a key does (the names VTK gives: 'plus', 'minus', 'm', 's', 'a', 'space', 'c',
        'o', ...)."""
        lens = self.lens
        if name != "f":
            self._stop_flight()
        if name == "f":
            self.toggle_scale()
        elif name == "b":
            self.show_inset(self.inset is None)
        elif name == "x":
            self.swap_views()
        elif name in ("bracketleft", "bracketright"):
            step = INSET_STEP if name == "bracketright" else -INSET_STEP
            self.resize_inset(self.inset_width + step)
        elif name in ("plus", "equal", "KP_Add", "minus", "KP_Subtract"):
            step = 1 if name in ("plus", "equal", "KP_Add") else -1
            lens.set_tiles(min(15, max(1, lens.tiles + step)))
            self._replace()
        elif name == "m":
            names = list(METHODS)
            lens.set_method(names[(names.index(lens.method) + 1) % len(names)])
            self._replace()
        elif name == "s":
            lens.set_style("ball-and-stick" if lens.style == "space-filling" else "space-filling")
            self.window.Render()
        elif name == "a":
            lens.set_effects(ssao=not lens.ssao, shadows=lens.shadows)
            self.window.Render()
        elif name == "h":
            lens.set_effects(ssao=lens.ssao, shadows=not lens.shadows)
            self.window.Render()
        elif name == "space":
            self._toggle_play()
        elif name == "l":
            lens.set_refinement((lens.refinement_level + 1) % 4)
            self.time_index = 0
            self._replace()
        elif name == "c":
            self.screenshot()
        elif name == "v":
            self.save_camera()
        elif name == "o":
            self.toggle_cutaway()
        elif name == "i":
            lens.set_cut_inverted(not lens.cut_inverted)
            self._cut_setting_changed()
        elif name == "n":
            lens.set_cut_random(not lens.cut_random)
            self._cut_setting_changed()

    # The two scales ------------------------------------------------------------------------

    def _aspect(self, renderer):
        width, height = renderer.GetSize()
        return width / height if width > 0 and height > 0 else 1.0

    def _frame_patch(self):
        """Works out the poses of the two scales for the placed patch: the patch close up (with
        the window's present up) and the whole cell seen from the patch's side."""
        renderer = self.lens.renderer
        self.patch_pose, self.cell_pose = self.lens.scale_poses(pose_of(renderer.GetActiveCamera()),
                                                                self._aspect(renderer))

    def place_camera_at_patch(self):
        """For a lens placed before the viewer opened: the poses of the two scales, and the
        window at the patch."""
        self._frame_patch()
        self.fly_to_patch(animate=False)

    def fly_to_patch(self, animate=None):
        """Flies the window's camera to the patch close up (key f); says why not before a patch
        is placed. `animate`: a flight of FLIGHT_SECONDS (default: while the event loop runs),
        or a jump. Returns whether there is a patch to fly to."""
        return self._fly(True, animate)

    def fly_to_cell(self, animate=None):
        """Flies the window's camera back to the whole cell (key f); see fly_to_patch."""
        return self._fly(False, animate)

    def toggle_scale(self, animate=None):
        """Key f: to the whole cell from the patch, to the patch from anywhere else."""
        return self._fly(not self.at_patch, animate)

    def _fly(self, to_patch, animate):
        self._stop_flight()
        if self.patch_pose is None:
            self.message = "no patch yet: click on the surface to map one"
            self.window.Render()
            return False
        self.message = ""
        self.at_patch = to_patch
        target = self.patch_pose if to_patch else self.cell_pose
        self._show_other_scale_in_inset()
        renderer = self.lens.renderer
        if animate is None:
            animate = self._running
        if not animate:
            apply_pose(renderer, target)
            self.window.Render()
            return True
        start = pose_of(renderer.GetActiveCamera())
        self._flight = (renderer, start, target, time.monotonic(), FLIGHT_SECONDS)
        self._next_flight_tick()
        return True

    def _next_flight_tick(self):
        # One one-shot timer per frame: VTK 9.2's X interactor crashes when a timer is destroyed
        # from its own event, so a flight never destroys its timer; it just asks for no more.
        self._flight_timer = self.interactor.CreateOneShotTimer(FLIGHT_TICK_MS)

    def advance_flight(self, now=None):
        """Moves a flight on to time `now` (time.monotonic(); the timer calls this) and draws
        the frame. Returns whether a flight is still under way."""
        if self._flight is None:
            return False
        renderer, start, end, started, seconds = self._flight
        fraction = min(1.0, ((time.monotonic() if now is None else now) - started) / seconds)
        apply_pose(renderer, end if fraction >= 1.0 else interpolate(start, end, fraction))
        if fraction >= 1.0:
            self._stop_flight()
        self.window.Render()
        return self._flight is not None

    def _on_flight_tick(self):
        if self.advance_flight():
            self._next_flight_tick()

    def _stop_flight(self):
        """Ends a flight where it is (a press, a wheel step or a key interrupts it); its last
        timer then fires to no effect."""
        self._flight = None
        self._flight_timer = None

    def flying(self):
        return self._flight is not None

    def zoom_at(self, x, y, factor=WHEEL_FACTOR):
        """One wheel step at display pixel (x, y): moves the camera of the view there toward
        what is drawn under (x, y), keeping `factor` of the distance to it (> 1 moves away);
        never nearer than NEAREST_APPROACH Å. Over the background, toward the focal point."""
        self._stop_flight()
        renderer = self._renderer_at(x, y)
        camera = renderer.GetActiveCamera()
        point = point_under(renderer, x, y)
        if point is None:
            camera.Dolly(1.0 / factor)
        else:
            dolly_toward(camera, point, factor, NEAREST_APPROACH * self.lens.scale)
        renderer.ResetCameraClippingRange()
        if renderer is self.lens.renderer:
            self.at_patch = False  # f now flies to the patch
        self.window.Render()

    def show_inset(self, on=True):
        """The inset (key b): a second view in the upper left of the window that shows the scale
        the window does not (the patch close up, or the whole cell with the lens outlined).
        Returns whether it is on."""
        if on and self.inset is None:
            inset = vtkRenderer()
            inset.SetLayer(1)
            inset.SetPreserveColorBuffer(False)  # its own background, over the window's view
            inset.SetBackground(0.16, 0.17, 0.21)
            inset.SetNearClippingPlaneTolerance(1e-4)
            for actor in (self.lens.surface_actor, self.lens.atom_actor, self.lens.outline_actor):
                inset.AddActor(actor)
            self.window.SetNumberOfLayers(2)
            self.window.AddRenderer(inset)
            self.inset = inset
            self.inset_bar = ScaleBar(inset, self.lens.scale)
            inset.AddObserver("StartEvent", lambda *_: self._before_inset_frame())
            self._place_inset()
            self._show_other_scale_in_inset()
        elif not on and self.inset is not None:
            self.window.RemoveRenderer(self.inset)
            self.window.SetNumberOfLayers(1)
            self.inset = None
            self.inset_bar = None
        self.window.Render()
        return self.inset is not None

    def resize_inset(self, width):
        """Sets the inset's width as a share of the window's (clamped to INSET_SIZES; its height
        keeps the window's aspect); a width that is no number is ignored."""
        if math.isfinite(width):
            self.inset_width = min(INSET_SIZES[1], max(INSET_SIZES[0], width))
        if self.inset is not None:
            self._place_inset()
        self.window.Render()

    def swap_views(self):
        """Key x: the window takes the inset's scale and the inset the window's."""
        if self.inset is None or self.patch_pose is None:
            self.message = ("the inset is off: b shows it" if self.inset is None else
                            "no patch yet: click on the surface to map one")
            self.window.Render()
            return
        self._fly(not self.at_patch, False)

    def _before_inset_frame(self):
        keep_near_things(self.inset.GetActiveCamera())
        self.inset_bar.update()

    def _place_inset(self):
        self.inset.SetViewport(0.0, 1.0 - self.inset_width, self.inset_width, 1.0)

    def _show_other_scale_in_inset(self):
        if self.inset is None or self.patch_pose is None:
            return
        other = self.cell_pose if self.at_patch else self.patch_pose
        apply_pose(self.inset, other)

    def _renderer_at(self, x, y):
        """The renderer whose viewport holds display pixel (x, y): the inset over the window."""
        if self.inset is not None:
            width, height = self.window.GetSize()
            x0, y0, x1, y1 = self.inset.GetViewport()
            if x0 * width <= x < x1 * width and y0 * height <= y < y1 * height:
                return self.inset
        return self.lens.renderer

    def scale_shown(self):
        """What the window shows: 'atoms' (a pixel of 2 Å or less), 'whole cell' (a view at
        least half the cell's size across) or 'membrane' between them, with the length of a
        pixel (Å)."""
        per_pixel = self.scale_bar.angstrom_per_pixel()
        if per_pixel <= 2.0:
            return "atoms", per_pixel
        bounds = self.lens.surface.GetOutput().GetBounds()
        cell = math.sqrt(sum((bounds[2 * d + 1] - bounds[2 * d]) ** 2 for d in range(3)))
        view = per_pixel * self.lens.scale * min(self.lens.renderer.GetSize())
        return ("whole cell" if view >= 0.5 * cell else "membrane"), per_pixel

    # The structured cutaway ----------------------------------------------------------------

    def _make_cut_widgets(self):
        """The cut plane (vtkImplicitPlaneWidget2, no outline, a faint plane) and the slider of
        the fraction hidden (0-100 %), both off until the cutaway is on."""
        self.plane_representation = vtkImplicitPlaneRepresentation()
        self.plane_representation.SetPlaceFactor(1.1)
        self.plane_representation.DrawOutlineOff()
        self.plane_representation.OutlineTranslationOff()
        self.plane_representation.ScaleEnabledOff()
        self.plane_representation.SetBumpDistance(0.025)  # of the patch's diagonal per Up / Down
        self.plane_representation.GetPlaneProperty().SetOpacity(0.12)
        self.plane_representation.GetSelectedPlaneProperty().SetOpacity(0.25)
        self.plane_widget = vtkImplicitPlaneWidget2()
        self.plane_widget.SetInteractor(self.interactor)
        self.plane_widget.SetRepresentation(self.plane_representation)
        self.plane_widget.SetCurrentRenderer(self.lens.renderer)
        self.plane_widget.KeyPressActivationOff()  # 'i' is ours (inversion)
        self.plane_widget.AddObserver("InteractionEvent", self._on_plane_moved)

        self.slider_representation = vtkSliderRepresentation2D()
        slider = self.slider_representation
        slider.SetMinimumValue(0.0)
        slider.SetMaximumValue(100.0)
        slider.SetValue(100.0 * self.lens.cut_fraction)
        slider.SetTitleText("hidden in the cut")
        slider.SetLabelFormat("%.0f %%")
        for coordinate, (x, y) in zip((slider.GetPoint1Coordinate(), slider.GetPoint2Coordinate()),
                                      CUT_SLIDER_ENDS):
            coordinate.SetCoordinateSystemToNormalizedDisplay()
            coordinate.SetValue(x, y)
        slider.SetSliderLength(0.02)
        slider.SetSliderWidth(0.03)
        slider.SetTubeWidth(0.008)
        slider.SetEndCapLength(0.01)
        slider.SetTitleHeight(0.025)
        slider.SetLabelHeight(0.025)
        for text in (slider.GetTitleProperty(), slider.GetLabelProperty()):
            text.SetColor(0.9, 0.9, 0.9)
            text.ShadowOff()
            text.BoldOff()
        self.slider_widget = vtkSliderWidget()
        self.slider_widget.SetInteractor(self.interactor)
        self.slider_widget.SetRepresentation(slider)
        self.slider_widget.SetCurrentRenderer(self.lens.renderer)
        self.slider_widget.KeyPressActivationOff()
        self.slider_widget.SetAnimationModeToJump()  # a click on the tube sets the value there
        self.slider_widget.AddObserver("InteractionEvent", self._on_slider_moved)

    def _fit_cut_widgets(self, face_camera):
        """Shows the widgets while the cutaway is on, around the mapped patch; with face_camera
        the plane goes through the lens point, facing the camera (its arrow towards the eye)."""
        mapped = self.lens.mapping.GetOutput()
        # Nothing to cut around where the last mapping failed (the atoms are hidden then).
        on = self.lens.cutaway_on and mapped.GetNumberOfPoints() > 0
        if on:
            self.plane_representation.PlaceWidget(mapped.GetBounds())
            if face_camera or self.lens.cut_normal is None:
                camera = self.lens.renderer.GetActiveCamera()
                towards_eye = [-v for v in camera.GetDirectionOfProjection()]
                self.lens.set_cut_plane(self.lens.centre, towards_eye)
            self.plane_representation.SetOrigin(*self.lens.cut_origin)
            self.plane_representation.SetNormal(*self.lens.cut_normal)
            self.slider_representation.SetValue(100.0 * self.lens.cut_fraction)
        if bool(self.plane_widget.GetEnabled()) != on:
            self.plane_widget.SetEnabled(on)
            self.slider_widget.SetEnabled(on)

    def toggle_cutaway(self):
        """Cuts the membrane open or shows it whole again (key o); says why not before the
        membrane is placed. Returns whether the cutaway is on."""
        try:
            self.lens.set_cutaway(not self.lens.cutaway_on)
            self.message = ""
        except LensError as error:
            self.message = str(error)
        self._fit_cut_widgets(face_camera=True)
        self.window.Render()
        return self.lens.cutaway_on

    def set_cut_fraction(self, fraction):
        """Hides this share of the molecules in the cut, [0, 1] (the slider shows it in %).
        Raises LensError outside [0, 1]."""
        self.lens.set_cut_fraction(fraction)
        self.slider_representation.SetValue(100.0 * self.lens.cut_fraction)
        self.window.Render()

    def set_cut_plane(self, origin, normal):
        """Moves the cut plane (the widget with it): through `origin` (mesh units), the cut on
        the side `normal` points to. Raises LensError for a zero or non-finite normal."""
        self.lens.set_cut_plane(origin, normal)
        if self.lens.cutaway_on:
            self.plane_representation.SetOrigin(*self.lens.cut_origin)
            self.plane_representation.SetNormal(*self.lens.cut_normal)
        self.window.Render()

    def _cut_setting_changed(self):
        on = self.lens.cutaway_on
        self.message = "" if on else "the cutaway is off: o cuts the membrane open"
        self.window.Render()

    def _on_plane_moved(self, _caller, _event):
        # The widget renders after this event: the cut follows in the same frame.
        self.lens.set_cut_plane(self.plane_representation.GetOrigin(),
                                self.plane_representation.GetNormal())

    def _on_slider_moved(self, _caller, _event):
        value = min(100.0, max(0.0, self.slider_representation.GetValue()))
        self.lens.set_cut_fraction(value / 100.0)

    def _replace(self):
        if self.lens.centre is not None:
            # Other tiles or another method: f frames the patch as it is now.
            if self._place(self.lens.centre):
                self._frame_patch()
        else:
            self.window.Render()

    def _toggle_play(self):
        steps = self.lens.time_steps()
        if len(steps) < 2:
            self.message = "no trajectory to play (start with --trajectory)"
            self.window.Render()
            return
        self.playing = not self.playing
        if self.playing and self._timer is None:
            self._timer = self.interactor.CreateRepeatingTimer(100)
        elif not self.playing and self._timer is not None:
            self.interactor.DestroyTimer(self._timer)
            self._timer = None
        self.window.Render()

    def step(self):
        """Shows the next time step of the trajectory (wrapping around)."""
        steps = self.lens.time_steps()
        if steps:
            self.time_index = (self.time_index + 1) % len(steps)
            self.lens.set_time(steps[self.time_index])
            self.window.Render()

    def screenshot(self, path=None):
        """Writes the window to `path` (default mesolens-NNNN.png in the working folder)."""
        if path is None:
            path = f"mesolens-{self.screenshots:04d}.png"
            self.screenshots += 1
        try:
            write_png(self.window, path)
        except LensError as error:
            self.message = str(error)
            self.window.Render()
            return None
        self.message = f"wrote {os.path.abspath(path)}"
        self.window.Render()
        return path

    def save_camera(self, path="mesolens-camera.txt"):
        """Writes the camera as the lines `mesolens render --camera` reads."""
        camera = self.lens.renderer.GetActiveCamera()
        try:
            write_camera_file(path, camera)
            self.message = f"wrote {os.path.abspath(path)}"
        except OSError as error:
            self.message = f"cannot write {path}: {error}"
        self.window.Render()
        return path

    # Events --------------------------------------------------------------------------------

    def _on_press(self, _caller, _event):
        self._stop_flight()
        self._press = self.interactor.GetEventPosition()
        self.style.OnLeftButtonDown()

    def _on_other_press(self, _caller, event):
        self._stop_flight()
        if event == "MiddleButtonPressEvent":
            self.style.OnMiddleButtonDown()
        else:
            self.style.OnRightButtonDown()

    def _on_wheel(self, _caller, event):
        x, y = self.interactor.GetEventPosition()
        forward = event == "MouseWheelForwardEvent"
        self.zoom_at(x, y, WHEEL_FACTOR if forward else 1.0 / WHEEL_FACTOR)

    def _on_release(self, _caller, _event):
        self.style.OnLeftButtonUp()
        if self._press is None:
            return
        x, y = self.interactor.GetEventPosition()
        moved = abs(x - self._press[0]) + abs(y - self._press[1])
        self._press = None
        if moved <= CLICK_TOLERANCE:
            self.click(x, y)

    KEYS = ("plus", "equal", "KP_Add", "minus", "KP_Subtract", "m", "s", "a", "h", "space", "c",
            "l", "v", "o", "i", "n", "f", "b", "x", "bracketleft", "bracketright")

    def _on_char(self, _caller, _event):
        # Ours replace VTK's defaults for these keys (s: surface, a: actor mode, c: camera
        # mode); the others ('q' to quit, 'r' to reset the camera, ...) keep theirs.
        name = self.interactor.GetKeySym()
        if name in self.KEYS:
            self.key(name)
        else:
            self.style.OnChar()

    @calldata_type(VTK_INT)
    def _on_timer(self, _caller, _event, timer):
        # The timer's id comes as the event's data (the X interactor's GetTimerEventId is 0).
        if timer == self._flight_timer:
            self._on_flight_tick()
        elif self.playing and timer == self._timer:
            self.step()

    def _before_frame(self):
        keep_near_things(self.lens.renderer.GetActiveCamera())
        self.scale_bar.update()
        self._show_status()

    def _show_status(self):
        lens = self.lens
        if self.message:
            text = self.message
        elif lens.centre is None:
            text = "click on the surface to place the membrane"
        else:
            frame = lens.renderer.GetLastRenderTimeInSeconds()
            steps = lens.time_steps()
            when = (f", t = {steps[self.time_index]:.0f} ps, refinement {lens.refinement_level} (l)"
                    if steps else "")
            mapped = lens.tiles_mapped()
            tiles = (f"one tile cut to the disk (of {lens.tiles} x {lens.tiles}, +/-)"
                     if lens.cut_to_disk() else
                     f"{mapped} x {mapped} tiles" + (f" of {lens.tiles} x {lens.tiles}"
                                                       if mapped != lens.tiles else "") + " (+/-)")
            text = (f"{lens.atom_count():,} atoms, {frame * 1000:.0f} ms | {tiles}, "
                    f"{lens.method} (m), {lens.style} (s), SSAO "
                    f"{'on' if lens.ssao else 'off'} (a), shadows {'on' if lens.shadows else 'off'} (h){when}"
                    f"{' playing' if self.playing else ''} (space) | c: screenshot")
            counts = lens.cut_counts()
            if counts is None:
                text += "\ncutaway off (o)"
            else:
                mode = ("random removal (n)" if lens.cut_random else
                        f"structured (n), {'patches' if lens.cut_inverted else 'wireframe'} (i)")
                text += (f"\ncutaway (o): {mode}, hidden {counts[0]:,} of {counts[1]:,} in cut "
                         f"({lens.cut_fraction:.0%}, slider)")
            scale, per_pixel = self.scale_shown()
            text += (f"\nshown: {scale}, 1 pixel = {length_label(per_pixel)} | f: "
                     f"{'whole cell' if self.at_patch else 'the patch'} | b: inset "
                     f"{'on' if self.inset is not None else 'off'}")
        if self.status.GetInput() != text:
            self.status.SetInput(text)

    def start(self):
        """Shows the window and runs the interaction until it is closed."""
        self.window.Render()
        self.interactor.Initialize()
        self._running = True
        try:
            self.interactor.Start()
        finally:
            self._running = False
