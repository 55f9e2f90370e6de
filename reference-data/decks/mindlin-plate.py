# A thick simply supported square plate under uniform pressure (SOL 101), a quarter on
# 4x4 ... 32x32 CQUAD4 with transverse shear flexibility (PSHELL MID3: the MITC4
# element): reference-data/decks/mindlin-plate-{4,8,16,32}.bdf, read by the verification
# case mindlin-plate. Run from the project root:
#     python3 reference-data/decks/mindlin-plate.py
# It prints the reference: the centre deflection of Mindlin's plate by Navier's series.
#
# The plate: a = 10 in, t = 1 in (a/t = 10), E = 1e7 psi, nu = 0.3, shear correction
# 5/6 (PSHELL TS/T blank), q = 1 psi along +z (PLOAD4). Hard simple support, as Navier's
# solution has it: w = 0 and the rotation along the edge 0 (theta_x on x = 0, theta_y
# on y = 0); symmetry on x = a/2 (theta_y = 0) and y = a/2 (theta_x = 0). The membrane
# is unloaded and uncoupled: GRDSET holds T1, T2 and the drilling R3 everywhere.
#
# Navier's series for Mindlin's plate (w = sum W_mn sin(m pi x/a) sin(n pi y/a), m, n
# odd): W_mn = q_mn (1/(D alpha^4) + 1/(k G t alpha^2)), q_mn = 16 q/(pi^2 m n),
# alpha^2 = (m^2 + n^2) pi^2/a^2, D = E t^3/12(1 - nu^2), k G t = 5/6 E/(2(1 + nu)) t.
# The shear part's terms fall as 1/(m n (m^2 + n^2)) with alternating signs at the
# centre; the sum to m, n <= 4001 and to 2001 agree to the digits printed.
import math

A, T, E, NU, Q = 10.0, 1.0, 1.0e7, 0.3, 1.0
D = E * T ** 3 / (12.0 * (1.0 - NU * NU))
KGT = 5.0 / 6.0 * E / (2.0 * (1.0 + NU)) * T


def centre(limit):
    total = 0.0
    for m in range(1, limit + 1, 2):
        for n in range(1, limit + 1, 2):
            alpha2 = (m * m + n * n) * math.pi ** 2 / A ** 2
            qmn = 16.0 * Q / (math.pi ** 2 * m * n)
            sign = (-1) ** ((m - 1) // 2 + (n - 1) // 2)
            total += sign * qmn * (1.0 / (D * alpha2 * alpha2) + 1.0 / (KGT * alpha2))
    return total


w2001, w4001 = centre(2001), centre(4001)
print(f"centre deflection {w4001!r} (to m, n <= 2001: {w2001!r}; relative change {abs(w4001 / w2001 - 1):.1e})")


def deck(n):
    h = 0.5 * A / n
    gid = lambda i, j: 1000 * (j + 1) + i + 1
    lines = [
        "$ A thick simply supported square plate (a = 10 in, t = 1 in) under uniform pressure,",
        f"$ a quarter on a {n}x{n} mesh of MITC4 (PSHELL MID3): reference-data/decks/mindlin-plate.py.",
        "$ Units: in, lbf, s",
        "SOL 101",
        "CEND",
        "  SPC = 1",
        "  LOAD = 1",
        "BEGIN BULK",
        "GRDSET,,,,,,,126",
        f"MAT1,1,{E!r},,{NU!r},0.1",
        f"PSHELL,1,1,{T!r},1,,1",
    ]
    for j in range(n + 1):
        for i in range(n + 1):
            lines.append(f"GRID,{gid(i, j)},,{i * h!r},{j * h!r},0.0")
    eid = 0
    for j in range(n):
        for i in range(n):
            eid += 1
            lines.append(f"CQUAD4,{eid},1,{gid(i, j)},{gid(i + 1, j)},{gid(i + 1, j + 1)},{gid(i, j + 1)}")
    for k in range(n + 1):
        lines.append(f"SPC1,1,34,{gid(0, k)}")
        lines.append(f"SPC1,1,35,{gid(k, 0)}")
        lines.append(f"SPC1,1,5,{gid(n, k)}")
        lines.append(f"SPC1,1,4,{gid(k, n)}")
    lines.append(f"PLOAD4,1,1,{Q!r},,,,THRU,{eid}")
    lines.append("ENDDATA")
    with open(f"reference-data/decks/mindlin-plate-{n}.bdf", "w") as f:
        f.write("\n".join(lines) + "\n")


for n in (4, 8, 16, 32):
    deck(n)
