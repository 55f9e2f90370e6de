# Rigid-element decks with closed-form answers: SOL 101 decks written to
# reference-data/decks/rigid/, read by the verification cases rbe3-spreader and
# rbe3-read-only. Each deck's header says what it checks; the numbers the cases hold
# them to are printed by this script. Run from the project root:
#     python3 reference-data/decks/rigid.py
# Numbers are written with Python's repr (the shortest text that reads back to the
# same double).
import math
import os

OUT = "reference-data/decks/rigid"
E, G_, RHO = 3.0e7, 1.15e7, 7.3e-4

# The spreader: four grids in the plane z = 0, each on a vertical CROD spring of
# stiffness k = EA/L to a clamped grid below, held in x, y and in rotation; an RBE3
# with weights 1-4 on their translations, its reference grid above and off the
# weighted centroid, displaced in a turned CORD2R.
XS = [(0.0, 0.0), (4.0, 0.0), (4.0, 3.0), (0.0, 3.0)]
WS = [1.0, 2.0, 3.0, 4.0]
XR = (1.0, 1.0, 2.0)
AREA, LS = 0.5, 2.0
F = (30.0, -10.0, -100.0)
M = (5.0, 7.0, -3.0)


def sub(a, b):
    return [x - y for x, y in zip(a, b)]


def cross(a, b):
    return [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]]


def solve3(a, b):
    # Cramer's rule on a 3x3 system.
    def det(m):
        return (m[0][0] * (m[1][1] * m[2][2] - m[1][2] * m[2][1])
                - m[0][1] * (m[1][0] * m[2][2] - m[1][2] * m[2][0])
                + m[0][2] * (m[1][0] * m[2][1] - m[1][1] * m[2][0]))
    d = det(a)
    out = []
    for k in range(3):
        m = [row[:] for row in a]
        for i in range(3):
            m[i][k] = b[i]
        out.append(det(m) / d)
    return out


def spreader():
    bulk = [
        f"MAT1,1,{E!r},{G_!r},,{RHO!r}",
        f"PROD,1,1,{AREA!r}",
        "CORD2R,7,,0.0,0.0,0.0,0.3,0.2,1.0,\n,1.0,-0.4,0.1",
    ]
    for i, (x, y) in enumerate(XS):
        bulk.append(f"GRID,{i + 1},,{x!r},{y!r},0.0")
        bulk.append(f"GRID,{i + 11},,{x!r},{y!r},{-LS!r}")
        bulk.append(f"CROD,{i + 1},1,{i + 11},{i + 1}")
    bulk.append(f"GRID,9,,{XR[0]!r},{XR[1]!r},{XR[2]!r},7")
    bulk.append("RBE3,7,,9,123456,1.0,123,1,\n,2.0,123,2,3.0,123,3,4.0,123,\n,4")
    bulk += ["SPC1,1,123456,11,THRU,14", "SPC1,1,12456,1,THRU,4"]
    bulk += [f"FORCE,1,9,,1.0,{F[0]!r},{F[1]!r},{F[2]!r}", f"MOMENT,1,9,,1.0,{M[0]!r},{M[1]!r},{M[2]!r}"]
    write(
        "spreader",
        [
            "An RBE3 spreading a load: four grids on vertical CROD springs (k = EA/L), weights 1-4 on their",
            "translations, the reference grid 9 above and off the weighted centroid (displaced in CORD2R 7),",
            "a force (30, -10, -100) and a moment (5, 7, -3) on it. Each spring takes",
            "f_i = w_i F/W + w_i (J^-1 M_c) x r_i about the weighted centroid c; w_i = f_i,z / k.",
        ],
        bulk,
    )
    k = E * AREA / LS
    w = sum(WS)
    c = [sum(wi * x[j] for wi, x in zip(WS, XS)) / w for j in range(2)] + [0.0]
    mc = [m + t for m, t in zip(M, cross(sub(XR, c), F))]
    r = [sub([x, y, 0.0], c) for x, y in XS]
    jm = [[sum(wi * ((ri[0] ** 2 + ri[1] ** 2 + ri[2] ** 2) * (a == b) - ri[a] * ri[b]) for wi, ri in zip(WS, r))
           for b in range(3)] for a in range(3)]
    kk = solve3(jm, mc)
    ws = []
    for i, (wi, ri) in enumerate(zip(WS, r)):
        f = [wi * F[j] / w + wi * cross(kk, ri)[j] for j in range(3)]
        ws.append(f[2] / k)
        print(f"spreader: grid {i + 1} at {XS[i]}: force z {f[2]!r}, w {f[2] / k!r}")
    # The reference grid reads the springs' motion back: the weighted fit of vertical
    # motions, u_r = u_c + theta x (x_r - c), theta = J^-1 sum w_i r_i x u_i.
    uc = [0.0, 0.0, sum(wi * wz for wi, wz in zip(WS, ws)) / w]
    s = [sum(wi * cross(ri, [0.0, 0.0, wz])[j] for wi, ri, wz in zip(WS, r, ws)) for j in range(3)]
    th = solve3(jm, s)
    ur = [uc[j] + cross(th, sub(XR, c))[j] for j in range(3)]
    print("spreader: reference grid motion (basic)", ur, "rotation", th)


def write(name, header, bulk, case=("  SPC = 1", "  LOAD = 1")):
    lines = [f"$ {h}" for h in header] + ["$ Units: unspecified", "SOL 101", "CEND", *case, "BEGIN BULK"] + bulk + ["ENDDATA"]
    with open(os.path.join(OUT, f"{name}.bdf"), "w") as f:
        f.write("\n".join(lines) + "\n")


def read_only():
    # The simply supported beam of beams/ss-beam-16.bdf with an RBE3 that reads the
    # motion of the three grids about midspan at a reference grid off the beam: it adds
    # no stiffness and no mass, so the frequencies and the deflection stay the beam's.
    src = open("reference-data/decks/beams/ss-beam-16.bdf").read().splitlines()
    head = [
        "The simply supported beam of beams/ss-beam-16.bdf with an RBE3 reading the midspan grids 8-10",
        "at grid 100, off the beam: its frequencies and deflection are the beam's. Made by rigid.py.",
    ]
    out = [f"$ {h}" for h in head]
    for line in src:
        if line == "ENDDATA":
            out += ["GRID,100,,10.0,1.0,0.5", "RBE3,1,,100,123456,1.0,123456,8,10,\n,2.0,123456,9"]
        out.append(line)
    with open(os.path.join(OUT, "ss-beam-16-read.bdf"), "w") as f:
        f.write("\n".join(out) + "\n")


os.makedirs(OUT, exist_ok=True)
spreader()
read_only()
