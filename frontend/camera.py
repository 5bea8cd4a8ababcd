"""Where the studio's camera goes: the room framed in the free part of the canvas (beside the control
panel), a top view, the VR user's view, and the orbit kept above the floor.

The framing is computed here in numpy (a pinhole projection of the room's corners), so every view is
reproducible from the room and the canvas size alone. viser has no orthographic camera: the top view is
a near-orthographic one (a 6 degree field of view from far above), which keeps sizes uniform across the
room to within a few per cent.
"""

from __future__ import annotations

import math

import numpy as np

PANEL_PX = 420  # viser's floating control panel ("large" width) and its margin, measured in chromium
DEFAULT_FOV = math.radians(50.0)  # vertical field of view of the framed views (viser's own default, 75, distorts)
TOP_FOV = math.radians(6.0)
EYE_HEIGHT = 1.6  # the VR user's eyes above the floor, metres
VR_FOV = math.radians(80.0)  # roughly a Quest's vertical field of view
MARGIN = 0.06  # share of the free area left around the framed room
MAX_POLAR = math.radians(82.0)  # the orbit stops 8 degrees above the horizon: never below the floor
DEFAULT_DIRECTION = np.array([0.0, -1.15, -1.0])  # looking down ~49 degrees, from the room's z = 0 side

ORBIT_LIMIT_JS = f"""
(function limit() {{
  const m = window.__viserMutable;
  if (!m || !m.cameraControl) {{ setTimeout(limit, 200); return; }}
  m.cameraControl.maxPolarAngle = {MAX_POLAR};
}})();
"""

# The canvas's size in CSS pixels, sent to a hidden input (its uuid replaces UUID) whenever it changes. viser's camera
# messages give the drawing buffer's size, which is the CSS size times the device pixel ratio (2 on a HiDPI screen)
# times viser's adaptive resolution factor (0.75-1, lowered while frames are slow), while the panel's width and the
# page's mouse events are in CSS pixels.
CANVAS_SIZE_JS = """
(function report() {
  const m = window.__viserMutable;
  if (!m || !m.canvas || !m.canvas.clientWidth) { setTimeout(report, 200); return; }
  let last = "";
  setInterval(() => {
    const size = [m.canvas.clientWidth, m.canvas.clientHeight];
    if (String(size) === last) return;
    last = String(size);
    m.sendMessage({type: "GuiUpdateMessage", uuid: "UUID", updates: {value: size}});
  }, 250);
})();
"""


def _unit(v) -> np.ndarray:
    v = np.asarray(v, dtype=float)
    return v / np.linalg.norm(v)


def basis(direction, up=(0.0, 1.0, 0.0)) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """(forward, right, camera up) of a camera looking along `direction`."""
    d = _unit(direction)
    r = np.cross(d, up)
    if np.linalg.norm(r) < 1e-6:  # looking straight down: screen-up is -z (the room's +z, away)
        r = np.cross(d, (0.0, 0.0, -1.0))
    r = _unit(r)
    return d, r, np.cross(r, d)


def project(points, position, direction, fov: float, width: int, height: int) -> np.ndarray:
    """Pixel coordinates (N, 2), origin top-left, of world points seen by a pinhole camera."""
    d, r, u = basis(direction)
    rel = np.asarray(points, dtype=float) - np.asarray(position, dtype=float)
    z = rel @ d
    f = (height / 2) / math.tan(fov / 2)
    return np.stack([width / 2 + f * (rel @ r) / z, height / 2 - f * (rel @ u) / z], axis=1)


def fit(points, direction, fov: float, width: int, height: int, panel_px: int = PANEL_PX,
        margin: float = MARGIN) -> tuple[np.ndarray, np.ndarray]:
    """(camera position, look-at) that shows every point inside the canvas left of the panel.

    Exact for a pinhole camera of fixed orientation: each edge of the free area is a plane through the
    camera, and a point is inside it when the camera's (lateral, depth) coordinates satisfy one linear
    inequality. The camera goes to the nearest depth where both the horizontal and the vertical pair
    can hold, then to the middle of what is allowed across the view."""
    pts = np.asarray(points, dtype=float)
    d, r, u = basis(direction)
    tan_v = math.tan(fov / 2)
    tan_h = tan_v * width / height
    free = max(width - panel_px, width * 0.4) / width
    centre, half = free - 1.0, free * (1 - margin)  # the free area in normalised x, -1 (left) .. 1 (right)
    depth = pts @ d

    def bounds(lateral: np.ndarray, lo: float, hi: float) -> tuple[float, float, float, float]:
        m_hi, m_lo = float((lateral - hi * depth).max()), float((lateral - lo * depth).min())
        return m_hi, m_lo, hi, lo

    rows = [bounds(pts @ r, (centre - half) * tan_h, (centre + half) * tan_h),
            bounds(pts @ u, -(1 - margin) * tan_v, (1 - margin) * tan_v)]
    cam_d = min((m_hi - m_lo) / (k_lo - k_hi) for m_hi, m_lo, k_hi, k_lo in rows)
    across = [((m_hi + k_hi * cam_d) + (m_lo + k_lo * cam_d)) / 2 for m_hi, m_lo, k_hi, k_lo in rows]
    position = across[0] * r + across[1] * u + cam_d * d
    return position, position + (float(depth.mean()) - cam_d) * d


def room_points(width: float, depth: float, height: float = 1.2) -> np.ndarray:
    """The corners of the floor and of a box `height` above it, in the browser's frame (z negated)."""
    return np.array([(x, y, -z) for x in (0.0, width) for y in (0.0, height) for z in (0.0, depth)])


def framing_direction(position, look_at) -> np.ndarray:
    """The current view's compass direction, tilted to the default downward angle."""
    v = np.asarray(look_at, dtype=float) - np.asarray(position, dtype=float)
    flat = np.array([v[0], 0.0, v[2]])
    if np.linalg.norm(flat) < 1e-3:
        return _unit(DEFAULT_DIRECTION)
    pitch = -DEFAULT_DIRECTION[1] / np.linalg.norm(DEFAULT_DIRECTION[[0, 2]])
    flat = _unit(flat)
    return _unit(flat + np.array([0.0, -pitch, 0.0]))


def vr_view(x: float, z: float, rotation: float) -> tuple[np.ndarray, np.ndarray]:
    """(position, look-at) of the VR user's eyes at the anchor pose (Unity x, z, yaw), in the browser frame."""
    a = math.radians(rotation)
    eye = np.array([x, EYE_HEIGHT, -z])
    ahead = np.array([math.sin(a), 0.0, -math.cos(a)])
    return eye, eye + 2.5 * ahead + np.array([0.0, -0.45, 0.0])
