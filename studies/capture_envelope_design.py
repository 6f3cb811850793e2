"""Writes the list-design sweep files of the wide capture envelope (studies/README.md, "Capture
envelope"): root offset dx along x, tilt theta and its lean direction beta (knob towards azimuth
beta), friction mu. Candidate starts that are impossible (studies/capture_geometry.py: shaft
outside a ring bore, a rope inside the pole) are not written; they are listed with the reason.

Usage: /usr/bin/python3 studies/capture_envelope_design.py STAGE   (STAGE: wide | far)
writes studies/sweeps/capture_envelope_STAGE.toml and prints the skipped starts."""
import sys

from capture_geometry import lean_axis, start_problem

MUS = (0.05, 0.2)


def wide():
    """Coarse design: offsets at tilt 0, tilts and directions at dx = 0, and both combined."""
    geo = [(dx, 0.0, 0.0) for dx in (-80, -70, -60, -50, 50, 60, 70, 80)]
    geo += [(0, 20.0, b) for b in (0, 90, 180, 270)]
    geo += [(dx, 10.0, b) for dx in (-60, 60) for b in (0, 90, 180, 270)]
    geo += [(-60, 25.0, 0), (60, 25.0, 180)]
    return geo


def far():
    """Second pass: every case of the wide pass captured, so the boundary lies at the possible
    starts' edge or beyond. Root offsets of 90-120 mm are possible only with the pole leaning
    back across the ring axis (towards beta = 0 for dx < 0, 180 for dx > 0): those, most
    informative first, both signs (the rope phases make them different)."""
    geo = []
    for dx, th in ((-100, 25), (-120, 35), (-120, 25), (-100, 35), (-100, 15), (-110, 25),
                   (-90, 15)):
        geo += [(dx, float(th), 0), (-dx, float(th), 180)]
    return geo


STAGES = {"wide": wide, "far": far}

HEADER = """# The capture envelope, {stage} pass (studies/README.md, "Capture envelope"), written by
#   /usr/bin/python3 studies/capture_envelope_design.py {stage}
# Run from the repository root (one worker, below other users' jobs, as on the shared machine):
#   nice -n 10 build-release/src/app/ancf sweep studies/sweeps/capture_envelope_{stage}.toml -j 1
# The same command resumes a stopped sweep.
#
# Cases (design "list"): friction mu on all nine contact laws; the pole's spherical root at
# (offset_mm, 0, -0.0753); tilt tilt_deg about tilt_axis = (-sin b, cos b, 0), so the knob leans
# towards azimuth b (b = 0: +x, the side a positive offset moves the root to). Starts with the shaft
# outside a ring bore or a rope inside the pole are not in the list (capture_geometry.py).
# Integrator: the error-controlled generalized-alpha settings of docs/time_step_control.md ("Second
# pass") that met every locked-state check on the nominal scene, t_end 16 s (a lock after a longer
# drive travel must still last >= 0.5 s before the end).
[sweep]
scene = "../scenes/capture.toml"
out = "out/capture_envelope_{stage}"
design = "list"
time_limit = 900.0
run_args = ["--capture-events", "--error-control", "--rtol", "1e-4"]
set = ["integrator.t_end=16.0", "integrator.cable_tangent=\\"tension_only\\"",
       "integrator.genalpha.rho_infinity=0.5", "integrator.genalpha.ceiling_rate=0.3"]
results = ["t_reached", "events.first_contact_rope_1", "events.first_contact_rope_2",
           "events.first_contact_rope_3", "events.all_three", "events.stall", "events.lock",
           "events.ring_angle_at_stall_deg", "events.final_tilt_deg", "events.final_lateral_offset_m",
           "events.peak_contact_force", "events.tension_at_lock_1", "events.tension_at_lock_2",
           "events.tension_at_lock_3", "counters.steps", "counters.Newton iterations",
           "counters.rejected steps"]
"""


def main():
    stage = sys.argv[1] if len(sys.argv) > 1 else "wide"
    cases, skipped = [], []
    for dx, th, b in STAGES[stage]():
        why = start_problem(dx, th, b)
        if why:
            skipped.append((dx, th, b, why))
            continue
        for mu in MUS:
            cases.append((mu, th, lean_axis(b), dx))
    path = f"studies/sweeps/capture_envelope_{stage}.toml"
    with open(path, "w") as f:
        f.write(HEADER.format(stage=stage))
        f.write(f"# {len(cases)} cases; impossible starts not written:\n")
        for dx, th, b, why in skipped:
            f.write(f"#   offset {dx} mm, tilt {th} deg towards {b} deg: {why}\n")
        mu_keys = ", ".join(f'"contact[{i}].law.friction"' for i in range(9))
        f.write(f'\n[[parameter]]\nname = "mu"\nkeys = [{mu_keys}]\n')
        f.write(f"values = [{', '.join(str(c[0]) for c in cases)}]\n")
        f.write('\n[[parameter]]\nname = "tilt_deg"\nkeys = ["body[1].rotation.angle"]\n'
                "scale = 0.017453292519943295  # deg -> rad\n")
        f.write(f"values = [{', '.join(str(c[1]) for c in cases)}]\n")
        axes = ", ".join(f'"[{a[0]:.6f}, {a[1]:.6f}, 0.0]"' for a in (c[2] for c in cases))
        f.write('\n[[parameter]]\nname = "tilt_axis"\nkeys = ["body[1].rotation.axis"]\n'
                f"values = [{axes}]\n")
        f.write('\n[[parameter]]\nname = "offset_mm"\nkeys = ["body[1].position", "joint[1].point"]\n'
                'value = "[{}, 0.0, -0.0753]"\nscale = 1e-3  # mm -> m\n')
        f.write(f"values = [{', '.join(str(float(c[3])) for c in cases)}]\n")
    print(f"wrote {path}: {len(cases)} cases")
    for s in skipped:
        print("skipped: offset {} mm, tilt {} deg towards {} deg: {}".format(*s))


if __name__ == "__main__":
    main()
