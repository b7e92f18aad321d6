# SPDX-License-Identifier: GPL-3.0-or-later
"""The interactive magnifier: click a cell surface, see the membrane's atoms mapped there.

``LensViewer`` puts a ``MembraneLens`` in a VTK window. A left click on the surface (a press and a
release without dragging; dragging turns the camera as usual) maps the patch around the clicked
point. Keys:

    + / -   more / fewer tiles (k x k, 1..15)     m   next mapping method
    s       space-filling / ball-and-stick        a   ambient occlusion (SSAO) on / off
    h       shadows on / off
    space   play / pause the trajectory           l   refinement level (frames in between)
    c       screenshot (mesolens-NNNN.png)        v   save the camera (mesolens-camera.txt, for
                                                      mesolens render --camera)
    o       structured cutaway on / off           i   cutaway: patches / wireframe (inverted)
    n       cutaway: random / structured removal
    q       quit

The structured cutaway (o, once the membrane is placed) cuts the mapped membrane open with a plane
through the lens point facing the camera: of the molecules on the camera's side of it (where its
arrow points) the slider at the top right hides 0 to 100 % (50 % at first), those at the centres
of a triangle mesh on the surface first, so that a wireframe remains (i: the edges first, so that
patches remain; n: at random, for comparison). Drag its arrow (at first seen end on, at the
plane's centre) to tilt the plane; Up / Down with the mouse over the plane push it along the
arrow or back (Ctrl: half steps). Clicks and camera drags that start on the plane go to the
plane: start them beside it.

Two lines at the bottom show the atom count, the last frame time and the settings, then the
cutaway's (off, or its mode and "hidden X of Y in cut", counted in molecules); messages (a click
off the surface, a mapping that fails, with its reason) replace them until the next action.
"""
import os

from vtkmodules.vtkInteractionWidgets import (vtkImplicitPlaneRepresentation,
                                              vtkImplicitPlaneWidget2,
                                              vtkSliderRepresentation2D, vtkSliderWidget)
from vtkmodules.vtkRenderingCore import vtkCellPicker, vtkRenderWindow, vtkRenderWindowInteractor
from vtkmodules.vtkRenderingCore import vtkTextActor
from vtkmodules.vtkInteractionStyle import vtkInteractorStyleTrackballCamera
import vtkmodules.vtkRenderingFreeType  # noqa: F401 (text)
import vtkmodules.vtkRenderingOpenGL2  # noqa: F401 (the OpenGL factory)

from .lens import METHODS, LensError, write_camera_file, write_png

CLICK_TOLERANCE = 3  # pixels a click may move and still be a click
CUT_SLIDER_ENDS = ((0.62, 0.93), (0.95, 0.93))  # the fraction slider, normalized display


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
        # Observers on the style replace its own handling of these events (the style holds the
        # mouse focus between press and release): each calls the style's default itself.
        self.style.AddObserver("LeftButtonPressEvent", self._on_press)
        self.style.AddObserver("LeftButtonReleaseEvent", self._on_release)
        self.style.AddObserver("CharEvent", self._on_char)
        self.interactor.AddObserver("TimerEvent", self._on_timer)
        self._make_cut_widgets()
        lens.renderer.AddObserver("StartEvent", lambda *_: self._show_status())
        lens.renderer.ResetCamera()
        self._show_status()

    # Actions -------------------------------------------------------------------------------

    def click(self, x, y):
        """What a click at display pixel (x, y) does: maps the patch there, or says why not.
        Returns True when the patch was placed."""
        if not self.picker.Pick(x, y, 0, self.lens.renderer):
            self.message = "that click is off the surface: click on the cell"
            self.window.Render()
            return False
        return self._place(self.picker.GetPickPosition())

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
        if name in ("plus", "equal", "KP_Add", "minus", "KP_Subtract"):
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
            self._place(self.lens.centre)
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
        self._press = self.interactor.GetEventPosition()
        self.style.OnLeftButtonDown()

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
            "l", "v", "o", "i", "n")

    def _on_char(self, _caller, _event):
        # Ours replace VTK's defaults for these keys (s: surface, a: actor mode, c: camera
        # mode); the others ('q' to quit, 'r' to reset the camera, ...) keep theirs.
        name = self.interactor.GetKeySym()
        if name in self.KEYS:
            self.key(name)
        else:
            self.style.OnChar()

    def _on_timer(self, _caller, _event):
        if self.playing:
            self.step()

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
        if self.status.GetInput() != text:
            self.status.SetInput(text)

    def start(self):
        """Shows the window and runs the interaction until it is closed."""
        self.window.Render()
        self.interactor.Initialize()
        self.interactor.Start()
