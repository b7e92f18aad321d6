# SPDX-License-Identifier: GPL-3.0-or-later
"""Camera moves of the magnifier between the scale of a cell and that of its atoms.

A cell is thousands of times larger than the patch of membrane mapped onto it, so the moves
here work in the logarithm of the distance: a flight from the whole cell to the patch covers
each factor of ten of zoom in the same time, and the wheel steps toward the point under the
cursor by a constant factor, which shrinks the step as the point comes near and never reaches
it. Poses are plain tuples, so that a pose can be kept, compared and flown back to.
"""
import math
from collections import namedtuple

# A camera: position, focal_point and view_up (3-tuples, world units), view_angle (degrees).
CameraPose = namedtuple("CameraPose", "position focal_point view_up view_angle")

# How far the patch view looks past the surface normal, degrees: the bilayer's edge then shows
# its thickness, which a view straight down hides.
PATCH_SLANT = 35.0
# Share of the window's smaller side that the patch's extent spans in the patch view: a little
# more than all of it, as the slant foreshortens the patch.
PATCH_FILL = 1.2
# One wheel step toward the point under the cursor keeps this share of the distance to it:
# 30 steps take a camera 2 µm away to 1 nm.
WHEEL_FACTOR = 0.78


def _sub(a, b):
    return [a[d] - b[d] for d in range(3)]


def _dot(a, b):
    return sum(a[d] * b[d] for d in range(3))


def _cross(a, b):
    return [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]]


def _norm(a):
    return math.sqrt(_dot(a, a))


def _unit(a, fallback=(0.0, 0.0, 1.0)):
    length = _norm(a)
    return [v / length for v in a] if length > 0 and math.isfinite(length) else list(fallback)


def _slerp(a, b, fraction):
    """The unit vector a fraction of the way from unit vector a to unit vector b along the great
    circle (straight through where they are opposite, then normalized)."""
    cosine = max(-1.0, min(1.0, _dot(a, b)))
    angle = math.acos(cosine)
    if angle < 1e-6 or angle > math.pi - 1e-3:
        return _unit([a[d] + fraction * (b[d] - a[d]) for d in range(3)], b)
    sine = math.sin(angle)
    wa = math.sin((1 - fraction) * angle) / sine
    wb = math.sin(fraction * angle) / sine
    return [wa * a[d] + wb * b[d] for d in range(3)]


def pose_of(camera):
    """The pose of a vtkCamera."""
    return CameraPose(tuple(camera.GetPosition()), tuple(camera.GetFocalPoint()),
                      tuple(camera.GetViewUp()), camera.GetViewAngle())


def apply_pose(renderer, pose):
    """Gives the renderer's camera the pose (its view-up made orthogonal to the view direction)
    and fits its clipping range to what the renderer shows from there."""
    camera = renderer.GetActiveCamera()
    camera.SetPosition(*pose.position)
    camera.SetFocalPoint(*pose.focal_point)
    camera.SetViewUp(*pose.view_up)
    camera.SetViewAngle(pose.view_angle)
    camera.OrthogonalizeViewUp()
    renderer.ResetCameraClippingRange()


def distance(pose):
    return _norm(_sub(pose.position, pose.focal_point))


def patch_pose(centre, normal, extent, current, aspect=1.0, slant=PATCH_SLANT, fill=PATCH_FILL):
    """The view of a patch of size `extent` (its largest side, world units) around `centre` on a
    surface whose outward normal there is `normal`: from outside, `slant` degrees past the
    normal toward the bottom of the `current` pose's picture (so the picture turns little), far
    enough that the patch spans `fill` of the window's smaller side (`aspect`: width / height)."""
    normal = _unit(normal)
    up = list(current.view_up)
    # The tangent toward the top of the current picture; any tangent where up is the normal.
    tangent = _sub(up, [_dot(up, normal) * v for v in normal])
    if _norm(tangent) < 1e-6 * max(_norm(up), 1e-30):
        helper = (1.0, 0.0, 0.0) if abs(normal[0]) < 0.9 else (0.0, 1.0, 0.0)
        tangent = _cross(normal, helper)
    tangent = _unit(tangent)
    angle = math.radians(slant)
    towards_eye = [math.cos(angle) * normal[d] - math.sin(angle) * tangent[d] for d in range(3)]
    half_angle = math.radians(current.view_angle) / 2
    # The view angle is vertical: a window wider than high shows more across.
    across = min(1.0, aspect)
    span = extent / max(fill, 1e-3)
    eye_distance = span / 2 / (math.tan(half_angle) * across)
    position = tuple(centre[d] + eye_distance * towards_eye[d] for d in range(3))
    view_up = _sub(tangent, [_dot(tangent, towards_eye) * v for v in towards_eye])
    return CameraPose(position, tuple(centre), tuple(_unit(view_up, up)), current.view_angle)


def whole_pose(bounds, centre, towards_eye, current, aspect=1.0, margin=1.15):
    """The view of a whole body (`bounds`, world units; looked at through `centre`) from the
    direction `towards_eye`, with the `current` pose's up and view angle, the bounding sphere
    filling the window's smaller side with `margin` to spare."""
    radius = 0.5 * math.sqrt(sum((bounds[2 * d + 1] - bounds[2 * d]) ** 2 for d in range(3)))
    half_angle = math.radians(current.view_angle) / 2
    eye_distance = margin * radius / math.sin(half_angle * min(1.0, aspect) or 1e-6)
    towards_eye = _unit(towards_eye)
    position = tuple(centre[d] + eye_distance * towards_eye[d] for d in range(3))
    up = list(current.view_up)
    view_up = _sub(up, [_dot(up, towards_eye) * v for v in towards_eye])
    if _norm(view_up) < 1e-6:
        view_up = _cross(towards_eye, (1.0, 0.0, 0.0) if abs(towards_eye[0]) < 0.9 else (0, 1, 0))
    return CameraPose(position, tuple(centre), tuple(_unit(view_up)), current.view_angle)


def interpolate(start, end, fraction):
    """The pose `fraction` (0..1) of the way along a flight from `start` to `end`: the view
    direction and the up turn along great circles, the distance to the focal point changes by
    equal factors, and the focal point moves in step with the distance covered: closing in, the
    target is no farther off the view's axis, relative to the distance, than it was at the start
    (so a target in view stays in view); drawing back, the start stays in view likewise."""
    s = fraction * fraction * (3 - 2 * fraction)  # eases in and out
    d0 = max(distance(start), 1e-30)
    d1 = max(distance(end), 1e-30)
    eye_distance = math.exp((1 - s) * math.log(d0) + s * math.log(d1))
    lead = (eye_distance - d0) / (d1 - d0) if abs(d1 - d0) > 1e-9 * d0 else s
    focal = [start.focal_point[d] + lead * (end.focal_point[d] - start.focal_point[d])
             for d in range(3)]
    direction = _slerp(_unit(_sub(start.position, start.focal_point)),
                       _unit(_sub(end.position, end.focal_point)), s)
    up = _slerp(_unit(start.view_up), _unit(end.view_up), s)
    angle = start.view_angle + s * (end.view_angle - start.view_angle)
    return CameraPose(tuple(focal[d] + eye_distance * direction[d] for d in range(3)),
                      tuple(focal), tuple(up), angle)


def poses_match(a, b, tolerance=1e-6):
    """Whether two poses show the same picture: positions and focal points within `tolerance`
    of the distance between them, the same up and view angle."""
    scale = max(distance(a), distance(b), 1e-30)
    return (_norm(_sub(a.position, b.position)) <= tolerance * scale and
            _norm(_sub(a.focal_point, b.focal_point)) <= tolerance * scale and
            _norm(_sub(_unit(a.view_up), _unit(b.view_up))) <= 1e-4 and
            abs(a.view_angle - b.view_angle) <= 1e-6)


def point_under(renderer, x, y):
    """The world point drawn at display pixel (x, y) of the last frame (from its depth), or
    None over the background."""
    depth = renderer.GetZ(x, y)
    if not 0.0 <= depth < 1.0:
        return None
    renderer.SetDisplayPoint(x, y, depth)
    renderer.DisplayToWorld()
    point = renderer.GetWorldPoint()
    if point[3] == 0:
        return None
    return tuple(point[d] / point[3] for d in range(3))


def dolly_toward(camera, point, factor, minimum_distance):
    """Moves the camera and its focal point toward `point` (world units), keeping `factor` of
    their distance to it (> 1 moves away), so that the point stays where it shows in the window;
    never nearer than `minimum_distance`. Returns whether the camera moved."""
    eye = camera.GetPosition()
    now = _norm(_sub(eye, point))
    wanted = max(now * factor, minimum_distance)
    if now <= 0 or (factor < 1 and wanted >= now):
        return False
    kept = wanted / now
    focal = camera.GetFocalPoint()
    camera.SetPosition(*[point[d] + kept * (eye[d] - point[d]) for d in range(3)])
    camera.SetFocalPoint(*[point[d] + kept * (focal[d] - point[d]) for d in range(3)])
    return True


def keep_near_things(camera, share=0.25, depth_range=1e7):
    """Brings the near clipping plane to `share` of the focal distance where it lies beyond
    that: VTK puts it at a fixed share of the far plane's distance when the camera is inside
    the scene's bounds, which in a cell tens of µm across is farther than atoms a few Å in front
    of the camera. The far plane stays; the near one keeps within `depth_range` of it."""
    near, far = camera.GetClippingRange()
    wanted = max(share * distance(pose_of(camera)), far / depth_range)
    if wanted < near:
        camera.SetClippingRange(wanted, far)


def pixel_size(renderer):
    """World length of one pixel at the focal point's depth, in the renderer's viewport."""
    camera = renderer.GetActiveCamera()
    height = renderer.GetSize()[1] or 1
    if camera.GetParallelProjection():
        return 2 * camera.GetParallelScale() / height
    focal_depth = distance(pose_of(camera))
    return 2 * focal_depth * math.tan(math.radians(camera.GetViewAngle()) / 2) / height
