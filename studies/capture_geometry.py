"""Start geometry of the capture scene (studies/scenes/capture.toml, shared/CAPTURE.md) for the
capture envelope: where the pole is at t = 0 for a root offset dx along x, a tilt theta and a lean
direction beta, and whether that start is possible at all.

The pole pivots on its spherical root joint at (dx, 0, Z_ROOT); it is tilted by theta about the
horizontal axis (-sin beta, cos beta, 0), so the knob leans towards azimuth beta (beta = 0: +x,
the side a positive dx moves the root to). A start is *impossible* when
  * the shaft does not pass through the ring bores: its axis at z = 0 (fixed ring) or at z = h
    (rotating ring) is farther than R - r_shaft from the ring axis. The rings carry no contact
    shape in the scene, so the model would run such a case with the pole through a ring; it is
    not run;
  * or a rope's centreline (the stress-free helices, sampled) lies within r_rope of the shaft or
    the knob (the pole would start inside a rope).
Used by studies/capture_envelope_design.py (which cases to run) and studies/capture_envelope.py
(the possible region drawn on the maps)."""
import math

R, H = 0.10, 0.15  # ring radius, rotating ring height [m]
Z_ROOT = -0.0753  # pole root height [m]
LENGTH = 0.273  # root to knob centre [m]
R_SHAFT, R_KNOB, R_ROPE = 0.015, 0.025, 0.001
PSI0 = 2.2256  # rope twist [rad]
PHI = [math.radians(a) for a in (90.0, 210.0, 330.0)]  # rope anchors on the fixed ring


def lean_axis(beta_deg):
    """Rotation axis that tilts the pole's +z towards azimuth beta."""
    b = math.radians(beta_deg)
    return (round(-math.sin(b), 6) + 0.0, round(math.cos(b), 6) + 0.0, 0.0)


def axis_point(dx, theta, beta, z):
    """(x, y) of the pole axis at height z [m]; theta, beta in radians."""
    s = (z - Z_ROOT) * math.tan(theta)
    return dx + s * math.cos(beta), s * math.sin(beta)


def start_problem(dx_mm, theta_deg, beta_deg, samples=2000):
    """None if the start is possible, else the reason (text)."""
    dx, th, b = dx_mm * 1e-3, math.radians(theta_deg), math.radians(beta_deg)
    for z, ring in ((0.0, "fixed"), (H, "rotating")):
        r = math.hypot(*axis_point(dx, th, b, z))
        if r > R - R_SHAFT:
            return f"shaft outside the {ring} ring bore: axis {1e3 * r:.1f} mm from the ring axis > {1e3 * (R - R_SHAFT):.0f} mm"
    a = (math.sin(th) * math.cos(b), math.sin(th) * math.sin(b), math.cos(th))
    root = (dx, 0.0, Z_ROOT)
    knob = tuple(root[i] + LENGTH * a[i] for i in range(3))
    gap = math.inf
    for phi in PHI:
        for k in range(samples + 1):
            u = k / samples
            p = (R * math.cos(phi + PSI0 * u), R * math.sin(phi + PSI0 * u), H * u)
            d = [p[i] - root[i] for i in range(3)]
            s = min(LENGTH, max(0.0, sum(d[i] * a[i] for i in range(3))))
            gap = min(gap,
                      math.dist(p, [root[i] + s * a[i] for i in range(3)]) - R_SHAFT - R_ROPE,
                      math.dist(p, knob) - R_KNOB - R_ROPE)
    if gap <= 0.0:
        return f"a rope starts inside the pole (centreline gap {1e3 * gap:.2f} mm)"
    return None
