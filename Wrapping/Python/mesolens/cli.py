# SPDX-License-Identifier: GPL-3.0-or-later
"""The ``mesolens`` command: a membrane patch mapped onto a cell surface, drawn to PNG.

    mesolens render --mesh CELL --membrane PATCH [--trajectory XTC] (--center X,Y,Z | --vertex I)
                    [--tiles K] [--method polynomial|instancing|displacement]
                    [--style space-filling|ball-and-stick] [--ssao] [--size WxH]
                    [--camera FILE] [--frames N] [--cut FRACTION [--cut-order ORDER]]
                    [--view close|both|inset] -o OUT.png
    mesolens view --mesh CELL --membrane PATCH [--trajectory XTC] [--center X,Y,Z | --vertex I]
                  [--view close|inset]
    mesolens demo [-o mesolens-demo.png] [--size WxH] [--no-window]

``view`` opens the interactive magnifier (mesolens.viewer): click the surface to map the patch
there, and the camera flies to it; f flies between the whole cell and the patch, the wheel
moves toward what is under the cursor, b shows an inset with the other scale; keys change the
tiles, the method, the style, SSAO, play the trajectory, take screenshots, and cut the membrane
open (o: a structured cutaway under a plane widget and a slider). With --view inset it starts
with the inset on. ``render`` draws offscreen (no window; under Xvfb without a display);
--view close draws the patch close up, both the whole component on the left and the close-up
on the right, inset the close-up with the whole component (the lens outlined) in its upper
left. With --frames N and a
trajectory it writes OUT_0000.png ... for N time steps. --cut F cuts the mapped membrane open
as the viewer's o key does (the plane through the centre facing outward) and hides the share F
of the molecules in the cut, in structured (a wireframe remains), inverted (patches remain) or
random order (--cut-order). --camera reads a camera saved as
"position x y z", "focal x y z", "up x y z", "angle degrees" lines; without it the camera looks
at the patch from outside the surface. ``demo`` renders the embedded data (the outer membrane of
a mitochondrion from electron tomography and the all-atom DPPC patch) the same way, the whole
organelle beside the close-up, then opens the magnifier on it where a display exists.

Where the asked tiles do not fit the surface there, the largest k x k that fits is mapped (or
one tile cut to the disk) and a progress line says so. Errors (a missing or unreadable file, a
centre off the surface, a mapping that fails, with the mapping's reason, a picture that would
not show the mapped atoms) are one line on stderr and exit status 1; wrong arguments exit with
2. The progress lines' times count from the command's start.
"""
import argparse
import os
import sys
import time

from .camera import apply_pose, pose_of
from .lens import METHODS, STYLES, LensError, MembraneLens, read_camera_file, write_png

DEFAULT_DATA = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "..", "..",
                            "share", "mesolens", "Data")


def _data_dir():
    """The embedded data: MESOLENS_DATA_DIR, or the copy installed with the package."""
    return os.environ.get("MESOLENS_DATA_DIR", DEFAULT_DATA)


def _triple(text):
    try:
        values = [float(v) for v in text.split(",")]
    except ValueError:
        values = []
    if len(values) != 3:
        raise argparse.ArgumentTypeError(f"expected X,Y,Z, not {text!r}")
    return values


def _size(text):
    try:
        width, height = (int(v) for v in text.lower().split("x"))
    except ValueError:
        width = height = 0
    if not (16 <= width <= 8192 and 16 <= height <= 8192):
        raise argparse.ArgumentTypeError(f"expected WIDTHxHEIGHT of 16 to 8192 pixels, not {text!r}")
    return width, height


def _window(lens, size, ssao, shadows, view):
    from vtkmodules.vtkRenderingCore import vtkRenderWindow
    import vtkmodules.vtkRenderingOpenGL2  # noqa: F401 (the OpenGL factory)

    window = vtkRenderWindow()
    window.SetOffScreenRendering(1)
    window.SetMultiSamples(0)
    window.SetSize(*size)
    window.AddRenderer(lens.renderer)
    if view == "both":
        # The whole component on the left, the close-up on the right (VTK 9.1's SSAO needs the
        # renderer at the window's origin: the close-up keeps it only in "close" view).
        whole = lens.whole_view()
        whole.SetViewport(0.0, 0.0, 0.4, 1.0)
        lens.renderer.SetViewport(0.4, 0.0, 1.0, 1.0)
        window.AddRenderer(whole)
        lens._whole = whole
        ssao = shadows = False
    elif view == "inset":
        # The close-up fills the window (and keeps its effects); the whole component, the lens
        # outlined on it, in the upper left, over the close-up.
        whole = lens.whole_view()
        current = pose_of(whole.GetActiveCamera())
        apply_pose(whole, lens.scale_poses(current, size[0] / size[1])[1])
        whole.SetLayer(1)
        whole.SetPreserveColorBuffer(False)  # its own background, over the close-up
        whole.SetBackground(0.16, 0.17, 0.21)
        from .viewer import INSET_WIDTH  # the magnifier's inset, as it first opens
        whole.SetViewport(0.0, 1.0 - INSET_WIDTH, INSET_WIDTH, 1.0)
        window.SetNumberOfLayers(2)
        window.AddRenderer(whole)
        lens._whole = whole
    if ssao or shadows:
        lens.set_effects(ssao=ssao, shadows=shadows)
    return window


def _progress(quiet):
    start = time.monotonic()

    def report(text):
        if not quiet:
            print(f"mesolens: [{time.monotonic() - start:6.1f} s] {text}", file=sys.stderr)
    return report


def _lens(args, report):
    """The lens of the arguments, placed at --center or --vertex when one is given."""
    lens = MembraneLens(args.mesh, args.membrane, args.trajectory,
                        mesh_unit_angstrom=args.mesh_unit, progress=report)
    lens.set_tiles(args.tiles)
    lens.set_method(args.method)
    lens.set_style(args.style)
    cut = getattr(args, "cut", None)
    if cut is not None and not 0.0 <= cut <= 1.0:
        raise LensError(f"--cut must be between 0 and 1, not {cut}")
    if args.vertex is not None:
        points = lens.surface.GetOutput().GetNumberOfPoints()
        if not 0 <= args.vertex < points:
            raise LensError(f"--vertex {args.vertex} is not a vertex of the mesh (0 to {points - 1})")
        lens.place(lens.surface.GetOutput().GetPoint(args.vertex))
    elif args.center is not None:
        lens.place(args.center)
    if cut is not None:
        lens.set_cutaway(True)
        lens.set_cut_fraction(cut)
        lens.set_cut_inverted(args.cut_order == "inverted")
        lens.set_cut_random(args.cut_order == "random")
    return lens


def view(args):
    """Opens the interactive magnifier."""
    if not os.environ.get("DISPLAY"):
        raise LensError("view needs a display (an X server): run it on a desktop, or draw "
                        "pictures with 'mesolens render'")
    _open_viewer(_lens(args, _progress(args.quiet)), args)
    return 0


def _open_viewer(lens, args):
    """The magnifier on `lens`, at its patch when one is placed, the inset on for --view inset."""
    from .viewer import LensViewer
    viewer = LensViewer(lens, args.size)
    if lens.centre is not None:
        viewer.place_camera_at_patch()
    if args.view == "inset":
        viewer.show_inset(True)
    viewer.start()


def _check_patch_visible(lens, window, camera_given):
    """Makes sure the picture shows the mapped atoms: re-frames the default camera once, and
    otherwise raises LensError (a user's camera that misses the patch, atoms hidden)."""
    if lens.patch_pixels(window) > 0:
        return
    if not camera_given:
        lens.look_at_patch(distance_factor=2.0, elevation=0.0)
        if lens.patch_pixels(window) > 0:
            return
    where = "the camera file's view" if camera_given else "the view from outside the surface"
    raise LensError(f"the mapped patch ({lens.atom_count():,} atoms) does not show in {where}: "
                    "it is out of view or hidden behind the surface")


def render(args, report=None):
    """Builds the lens from the arguments and writes the PNG(s)."""
    report = report or _progress(args.quiet)
    if args.frames and not args.trajectory:
        raise LensError("--frames needs a trajectory (--trajectory) with time steps")
    lens = _lens(args, report)
    if args.camera:
        read_camera_file(args.camera, lens.renderer.GetActiveCamera())
        lens.renderer.ResetCameraClippingRange()
    else:
        lens.look_at_patch()
        if args.view == "inset":  # the patch filling the window, as the viewer flies to it
            current = pose_of(lens.renderer.GetActiveCamera())
            apply_pose(lens.renderer, lens.scale_poses(current, args.size[0] / args.size[1])[0])
    window = _window(lens, args.size, args.ssao, args.shadows, args.view)
    if lens.atom_count() == 0:
        raise LensError("no atoms were mapped")
    _check_patch_visible(lens, window, bool(args.camera))
    if args.frames:
        steps = lens.time_steps() if args.trajectory else []
        if not steps:
            raise LensError("--frames needs a trajectory (--trajectory) with time steps")
        stem, suffix = os.path.splitext(args.output)
        for index, step in enumerate(steps[:args.frames]):
            lens.set_time(step)
            window.Render()
            write_png(window, f"{stem}_{index:04d}{suffix or '.png'}")
        report(f"wrote {min(args.frames, len(steps))} frames {stem}_0000{suffix or '.png'} ...")
    else:
        window.Render()
        write_png(window, args.output)
        mapped = lens.tiles_mapped()
        tiles = ("one tile cut to the disk" if lens.cut_to_disk() else f"{mapped} x {mapped} tiles"
                 + (f" (of {args.tiles} x {args.tiles} asked)" if mapped != args.tiles else ""))
        report(f"wrote {args.output}: {lens.atom_count()} atoms, {tiles}, {args.method}, "
               f"{args.style}")
    return 0


def _parser():
    parser = argparse.ArgumentParser(prog="mesolens", description=__doc__,
                                     formatter_class=argparse.RawDescriptionHelpFormatter)
    commands = parser.add_subparsers(dest="command", required=True)

    def common(sub, default_view, views=("close", "both", "inset")):
        sub.add_argument("--tiles", type=int, default=3, help="k x k tiles, k in 1..15 (3)")
        sub.add_argument("--method", choices=sorted(METHODS), default="polynomial")
        sub.add_argument("--style", choices=sorted(STYLES), default="space-filling")
        sub.add_argument("--ssao", action="store_true", help="screen-space ambient occlusion")
        sub.add_argument("--shadows", action="store_true", help="shadows from a light above the patch")
        sub.add_argument("--size", type=_size, default=(1024, 768), help="WIDTHxHEIGHT (1024x768)")
        sub.add_argument("--quiet", action="store_true", help="no progress lines")
        sub.add_argument("--view", choices=views, default=default_view,
                         help="the patch close up, the whole component beside it (both) or in "
                              "an inset over it (inset)")

    def inputs(sub, placed):
        sub.add_argument("--mesh", required=True, help="cell-component surface")
        sub.add_argument("--membrane", required=True, help="membrane patch (GRO/PDB/mmCIF)")
        sub.add_argument("--trajectory", help="XTC/TRR over the membrane's topology")
        sub.add_argument("--mesh-unit", type=float, default=1e4,
                         help="Å per mesh unit (1e4: µm, the default; 10: nm)")
        where = sub.add_mutually_exclusive_group(required=placed)
        where.add_argument("--center", type=_triple, help="X,Y,Z near the surface (mesh units)")
        where.add_argument("--vertex", type=int, help="a vertex of the mesh as the centre")

    view_command = commands.add_parser("view", help="the interactive magnifier")
    inputs(view_command, False)
    common(view_command, "close", ("close", "inset"))

    render_command = commands.add_parser("render", help="draw a mapped membrane to PNG")
    inputs(render_command, True)
    render_command.add_argument("--camera", help="camera file (position/focal/up/angle lines)")
    render_command.add_argument("--frames", type=int, default=0,
                                help="write this many time steps as OUT_0000.png ...")
    render_command.add_argument("--cut", type=float, metavar="FRACTION",
                                help="cut the membrane open and hide this share (0..1) of the "
                                     "molecules in the cut")
    render_command.add_argument("--cut-order", choices=("structured", "inverted", "random"),
                                default="structured", help="which molecules go first (structured)")
    render_command.add_argument("-o", "--output", required=True, help="PNG file")
    common(render_command, "close")

    demo_command = commands.add_parser("demo", help="the embedded data, to PNG and a window")
    demo_command.add_argument("-o", "--output", default="mesolens-demo.png")
    demo_command.add_argument("--no-window", action="store_true",
                              help="only the PNG, even where a display exists")
    common(demo_command, "both")
    return parser


def main(argv=None):
    args = _parser().parse_args(argv)
    report = _progress(getattr(args, "quiet", False))  # one clock for the whole command
    try:
        if args.command == "demo":
            data = _data_dir()
            args.mesh = os.path.join(data, "meshes", "mito5_outer_membrane.obj")
            args.membrane = os.path.join(data, "membranes", "dppc128_slipids_323K.gro")
            args.trajectory = None
            args.mesh_unit = 1e4
            args.vertex = 1000
            args.tiles = args.tiles if args.tiles != 3 else 5
            args.center = None
            args.camera = None
            args.frames = 0
            status = render(args, report)
            if os.environ.get("DISPLAY") and not args.no_window:
                args.view = "close"
                _open_viewer(_lens(args, _progress(True)), args)
            return status
        if args.command == "view":
            return view(args)
        return render(args, report)
    except LensError as error:
        print(f"mesolens: error: {error}", file=sys.stderr)
        return 1


if __name__ == "__main__":
    sys.exit(main())
