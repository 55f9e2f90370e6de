# The static tests of MacNeal and Harder's shell obstacle course (Finite Elements in
# Analysis and Design 1, 1985) as SOL 101 decks on a sequence of meshes, each halving
# the element size: reference-data/decks/obstacle/*.bdf, read by the verification cases
# scordelis-lo, pinched-cylinder and pinched-hemisphere. Run from the project root:
#     python3 reference-data/decks/obstacle-course.py
# Coordinates are written with Python's repr (the shortest text that reads back to the
# same double).
import math
import os

OUT = "reference-data/decks/obstacle"


def deck(name, header, n, e, nu, t, rho, point, spcs, loads):
    gid = lambda i, j: 1000 * (i + 1) + j + 1
    lines = [f"$ {l}" for l in header]
    lines += [
        "$ Units: unspecified",
        "SOL 101",
        "CEND",
        "  SPC = 1",
        "  LOAD = 1",
        "BEGIN BULK",
        f"MAT1,1,{e!r},,{nu!r},{rho!r}",
        f"PSHELL,1,1,{t!r},1",
    ]
    for i in range(n + 1):
        for j in range(n + 1):
            x, y, z = point(i, j)
            lines.append(f"GRID,{gid(i, j)},,{x!r},{y!r},{z!r}")
    for i in range(n):
        for j in range(n):
            lines.append(f"CQUAD4,{gid(i, j)},1,{gid(i, j)},{gid(i + 1, j)},{gid(i + 1, j + 1)},{gid(i, j + 1)}")
    for c, ids in spcs(gid):
        for g in ids:
            lines.append(f"SPC1,1,{c},{g}")
    lines += loads(gid)
    lines.append("ENDDATA")
    with open(os.path.join(OUT, f"{name}-{n}.bdf"), "w") as f:
        f.write("\n".join(lines) + "\n")


def scordelis_lo(n):
    # A quarter of the roof: R = 25, half length 25, arc 40 deg, t = 0.25, E = 4.32e8,
    # nu = 0, weight 90 per unit area (RHO 360 = 90 / t under GRAV 1.0 down). x from the
    # diaphragm (u_y = u_z = theta_x = 0; it leaves T1 free) to mid-length
    # (symmetry: u_x = theta_y = theta_z = 0), arc from the crown (symmetry: u_y =
    # theta_x = theta_z = 0) to the free edge.
    r, half, arc = 25.0, 25.0, 40.0

    def point(i, j):
        a = math.radians(arc * j / n)
        return half * i / n, r * math.sin(a), r * math.cos(a)

    deck(
        "scordelis-lo",
        [
            "The Scordelis-Lo roof (MacNeal & Harder 1985, test 7), a quarter on an "
            f"{n}x{n} mesh;",
            "its own weight by GRAV; the deflection is read at the free edge's midside.",
        ],
        n, 4.32e8, 0.0, 0.25, 360.0, point,
        lambda g: [("234", [g(0, j) for j in range(n + 1)]),
                   ("156", [g(n, j) for j in range(n + 1)]),
                   ("246", [g(i, 0) for i in range(n + 1)])],
        lambda g: ["GRAV,1,,1.0,0.0,0.0,-1.0"],
    )


def pinched_cylinder(n):
    # R = 300, L = 600, t = 3, E = 3e6, nu = 0.3, two opposite unit loads at mid-length:
    # an eighth, x from the rigid diaphragm (u_y = u_z = theta_x = 0) to mid-length
    # (u_x = theta_y = theta_z = 0), theta from the loaded top (u_y = theta_x =
    # theta_z = 0) to the side (u_z = theta_x = theta_y = 0); a quarter of the load.
    r, half = 300.0, 300.0

    def point(i, j):
        a = 0.5 * math.pi * j / n
        return half * i / n, r * math.sin(a), r * math.cos(a)

    deck(
        "pinched-cylinder",
        [
            "The pinched cylinder with rigid diaphragms (MacNeal & Harder 1985, test 8), an "
            f"eighth on an {n}x{n} mesh;",
            "a quarter of the unit load down at the top of mid-length.",
        ],
        n, 3.0e6, 0.3, 3.0, 1.0, point,
        lambda g: [("234", [g(0, k) for k in range(n + 1)]),
                   ("156", [g(n, k) for k in range(n + 1)]),
                   ("246", [g(k, 0) for k in range(n + 1)]),
                   ("345", [g(k, n) for k in range(n + 1)])],
        lambda g: [f"FORCE,1,{g(n, 0)},,0.25,0.0,0.0,-1.0"],
    )


def pinched_hemisphere(n):
    # R = 10, t = 0.04, E = 6.825e7, nu = 0.3, an 18 deg hole at the pole, four radial
    # loads of 2 at the equator, alternately out and in: a quarter, polar angle from the
    # hole's edge to the equator, azimuth from the xz-plane (u_y = theta_x = theta_z = 0)
    # to the yz-plane (u_x = theta_y = theta_z = 0), z held at one point; the loads on
    # the symmetry planes halved.
    r, hole = 10.0, math.radians(18.0)

    def point(i, j):
        polar = hole + (0.5 * math.pi - hole) * i / n
        az = 0.5 * math.pi * j / n
        return r * math.sin(polar) * math.cos(az), r * math.sin(polar) * math.sin(az), r * math.cos(polar)

    deck(
        "pinched-hemisphere",
        [
            "The pinched hemisphere with an 18 deg hole (MacNeal & Harder 1985, test 9), a "
            f"quarter on an {n}x{n} mesh;",
            "half of each load on the symmetry planes: +1 along x at azimuth 0, -1 along y at 90 deg.",
        ],
        n, 6.825e7, 0.3, 0.04, 1.0, point,
        lambda g: [("246", [g(k, 0) for k in range(n + 1)]),
                   ("156", [g(k, n) for k in range(n + 1)]),
                   ("3", [g(n, 0)])],
        lambda g: [f"FORCE,1,{g(n, 0)},,1.0,1.0,0.0,0.0", f"FORCE,1,{g(n, n)},,1.0,0.0,-1.0,0.0"],
    )


os.makedirs(OUT, exist_ok=True)
for n in (4, 8, 16, 32):
    scordelis_lo(n)
for n in (8, 16, 32):
    pinched_cylinder(n)
    pinched_hemisphere(n)
