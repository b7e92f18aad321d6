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
    q       quit

A line at the bottom shows the atom count, the last frame time and the settings; messages (a
click off the surface, a mapping that fails, with its reason) replace it until the next action.
"""
import os

from vtkmodules.vtkRenderingCore import vtkCellPicker, vtkRenderWindow, vtkRenderWindowInteractor
from vtkmodules.vtkRenderingCore import vtkTextActor
from vtkmodules.vtkInteractionStyle import vtkInteractorStyleTrackballCamera
import vtkmodules.vtkRenderingFreeType  # noqa: F401 (text)
import vtkmodules.vtkRenderingOpenGL2  # noqa: F401 (the OpenGL factory)

from .lens import METHODS, LensError, write_camera_file, write_png

CLICK_TOLERANCE = 3  # pixels a click may move and still be a click


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
        try:
            self.lens.place(point)
            self.message = ""
            ok = True
        except LensError as error:
            self.message = str(error)
            ok = False
        self.window.Render()
        return ok

    def key(self, name):
        """What a key does (the names VTK gives: 'plus', 'minus', 'm', 's', 'a', 'space', 'c')."""
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
            "l", "v")

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
            text = (f"{lens.atom_count():,} atoms, {frame * 1000:.0f} ms | {lens.tiles} x "
                    f"{lens.tiles} tiles (+/-), {lens.method} (m), {lens.style} (s), SSAO "
                    f"{'on' if lens.ssao else 'off'} (a), shadows {'on' if lens.shadows else 'off'} (h){when}"
                    f"{' playing' if self.playing else ''} (space) | c: screenshot")
        if self.status.GetInput() != text:
            self.status.SetInput(text)

    def start(self):
        """Shows the window and runs the interaction until it is closed."""
        self.window.Render()
        self.interactor.Initialize()
        self.interactor.Start()
