#!/usr/bin/env python3
"""A minimal external engine for rockbench, in Python with the standard library only.

Housner's rocking block (Housner 1963): one rigid block on a rigid ground, rocking about one
base corner at a time, integrated by semi-implicit (symplectic) Euler at the input's step.
Impacts are Housner's: when the angle crosses zero the block lands on its other corner and
keeps the fraction e = 1 - (2 m R^2 / I_O) sin^2(alpha) of its angular velocity (conservation
of angular momentum about the new corner). It reads rockbench's input file (protocol version 1,
docs/external-engines.md) and writes the block's pose at every output row.

    python3 housner_engine.py INPUT.json
"""
import json
import math
import sys


def main(argv):
    if len(argv) != 2:
        sys.exit("usage: housner_engine.py INPUT.json")
    with open(argv[1]) as f:
        run = json.load(f)
    if run["protocol_version"] != 1:
        sys.exit("housner_engine.py speaks protocol 1, the input is %s" % run["protocol_version"])
    if len(run["blocks"]) != 1:
        sys.exit("housner_engine.py simulates one block, the input has %d" % len(run["blocks"]))
    drive = run["drive"]
    if drive["kind"] != "inertial":
        sys.exit("housner_engine.py takes the inertial drive only")

    block = run["blocks"][0]
    b, h, m = block["width_m"] / 2, block["height_m"] / 2, block["mass_kg"]
    R = math.hypot(b, h)
    alpha = math.atan2(b, h)
    I_O = block["inertia_kgm2"] + m * R * R  # about a base corner (parallel axes)
    e = 1.0 - 2.0 * m * R * R / I_O * math.sin(alpha) ** 2
    g = run["gravity_mps2"]
    dt, steps, every = run["time_step_s"], run["steps"], run["output_every_steps"]
    ax, ay = drive["ax_mps2"], drive["ay_mps2"]

    # The thesis's convention: theta > 0 tilts right, about the right-hand base corner. The
    # input's pose has the counter-clockwise angle phi = -theta.
    theta = -block["angle_rad"]
    omega = -block["omega_radps"]

    def pivot_side():
        return 1 if theta > 0 or (theta == 0 and omega > 0) else (-1 if theta < 0 or omega < 0 else 0)

    def angular_acceleration(side, a_x, a_y):
        # The effective gravity (-a_x, -(g + a_y)) about the pivot corner (side * b, 0):
        # I_O theta'' = -(r_PG x m g_eff), r_PG = G - P, with phi = -theta.
        if side == 0:
            return 0.0
        c, s = math.cos(-theta), math.sin(-theta)
        rx, ry = -side * b * c - h * s, -side * b * s + h * c
        torque_ccw = m * (rx * -(g + a_y) - ry * -a_x)
        return -torque_ccw / I_O

    def pose():
        side = pivot_side()
        c, s = math.cos(-theta), math.sin(-theta)
        px = side * b
        x = px + (-side * b) * c - h * s
        y = (-side * b) * s + h * c
        # The mass centre's velocity: w x (G - P), w = -omega.
        w = -omega
        vx, vy = -w * (y - 0.0), w * (x - px)
        return x, y, -theta, vx, vy, w

    def row(n):
        x, y, phi, vx, vy, w = pose()
        return "%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g\n" % (n * dt, x, y, phi, vx, vy, w)

    fallen = False
    with open(run["poses_file"], "w") as out:
        out.write("# Housner's block, semi-implicit Euler (examples/python_housner)\n")
        out.write("t_s,x1_m,y1_m,angle1_rad,vx1_mps,vy1_mps,omega1_radps\n")
        out.write(row(0))
        for n in range(steps):
            a_x = ax[n] if ax else 0.0
            a_y = ay[n] if ay else 0.0
            side = pivot_side()
            if side == 0:
                # At rest on its face: it tips when the base overcomes the restoring moment.
                if abs(a_x) > (g + a_y) * math.tan(alpha):
                    side = -1 if a_x > 0 else 1
            if not fallen and side != 0:
                omega += angular_acceleration(side, a_x, a_y) * dt
                before = theta
                theta += omega * dt
                if before != 0 and theta * before < 0:
                    # Landing on the other corner: Housner's impact.
                    theta, omega = 0.0, e * omega
                    if abs(omega) < 1e-9:
                        omega = 0.0
                if abs(theta) >= math.pi / 2:
                    # Lying on its side: the run is an overturn; the block stays down.
                    theta, omega, fallen = math.copysign(math.pi / 2, theta), 0.0, True
            if (n + 1) % every == 0 or n + 1 == steps:
                out.write(row(n + 1))


if __name__ == "__main__":
    main(sys.argv)
