# An unsymmetric [0/90] laminate plate, free, stretched along x by a uniform edge load:
# reference-data/decks/laminate-coupling-{regular,distorted}.bdf (SOL 101), read by the
# verification case laminate-coupling. Run from the project root:
#     python3 reference-data/decks/laminate-coupling.py
# It prints the reference: the centre deflection classical lamination theory gives.
#
# The plate: L x L = 6 x 6 in, plies of the paper's glass/epoxy MAT8 (E1 5.735e6,
# E2 1.2855e6, NU12 0.2231, G12 5.7e5 psi), 0.075 in each, 0 deg below 90 deg (PCOMP
# lists plies from the bottom). Edge load Nx = 100 lbf/in on x = 0 and x = L, as
# consistent nodal forces (N h / 2 at the corners, N h between). Held against rigid
# motion only, at three corners: (0, 0) T1 T2 T3, (L, 0) T2 T3, (0, L) T3.
#
# Classical lamination theory: [N; M] = [A B; B D] [e0; k], with N = (Nx, 0, 0) and
# M = 0, is a uniform state; w = -(kx x^2 + ky y^2 + kxy x y)/2 plus the rigid motion
# the three supports fix (NASTRAN's kx = d(theta_y)/dx = -w,xx), so at the centre
# w = (kx + ky - kxy) L^2 / 8. The membrane is bilinear and the DKQ's bending takes any
# constant curvature exactly, so the plate gives it on any mesh, distorted or not.

L, N, PLY = 6.0, 100.0, 0.075
E1, E2, NU12, G12, RHO = 5.735e6, 1.2855e6, 0.2231, 5.7e5, 1.8e-4


def q_matrix(theta):
    nu21 = NU12 * E2 / E1
    d = 1.0 - NU12 * nu21
    q11, q22, q12, q66 = E1 / d, E2 / d, NU12 * E2 / d, G12
    if theta == 90:
        q11, q22 = q22, q11
    return [[q11, q12, 0.0], [q12, q22, 0.0], [0.0, 0.0, q66]]


def solve(a, b):
    n = len(b)
    m = [row[:] + [b[i]] for i, row in enumerate(a)]
    for c in range(n):
        p = max(range(c, n), key=lambda r: abs(m[r][c]))
        m[c], m[p] = m[p], m[c]
        for r in range(n):
            if r != c:
                f = m[r][c] / m[c][c]
                m[r] = [x - f * y for x, y in zip(m[r], m[c])]
    return [m[i][n] / m[i][i] for i in range(n)]


plies = [(0, -PLY, 0.0), (90, 0.0, PLY)]  # angle, z bottom, z top
A = [[0.0] * 3 for _ in range(3)]
B = [[0.0] * 3 for _ in range(3)]
D = [[0.0] * 3 for _ in range(3)]
for angle, z0, z1 in plies:
    q = q_matrix(angle)
    for i in range(3):
        for j in range(3):
            A[i][j] += q[i][j] * (z1 - z0)
            B[i][j] += q[i][j] * (z1 ** 2 - z0 ** 2) / 2.0
            D[i][j] += q[i][j] * (z1 ** 3 - z0 ** 3) / 3.0
abd = [A[i] + B[i] for i in range(3)] + [B[i] + D[i] for i in range(3)]
e0x, e0y, g0, kx, ky, kxy = solve(abd, [N, 0.0, 0.0, 0.0, 0.0, 0.0])
centre = (kx + ky - kxy) * L * L / 8.0
print(f"strains {e0x!r} {e0y!r} {g0!r}, curvatures {kx!r} {ky!r} {kxy!r}")
print(f"centre deflection {centre!r}; end stretch {e0x * L!r}")


def deck(name, n, shift, mcid=""):
    h = L / n
    gid = lambda i, j: 100 * (j + 1) + i + 1
    lines = [
        "$ An unsymmetric [0/90] glass/epoxy laminate, free, stretched by Nx = 100 lbf/in on",
        f"$ x = 0 and x = 6 in: classical lamination theory's curvature on an {n}x{n} mesh",
        "$ (reference-data/decks/laminate-coupling.py, which prints the reference).",
        "$ Units: in, lbf, s",
        "SOL 101",
        "CEND",
        "  SPC = 1",
        "  LOAD = 1",
        "BEGIN BULK",
        "PCOMP,1,,,,,,,,+P0",
        f"+P0,8,{PLY!r},0.0,,8,{PLY!r},90.0",
        f"MAT8,8,{E1!r},{E2!r},{NU12!r},{G12!r},,,{RHO!r}",
    ]
    for j in range(n + 1):
        for i in range(n + 1):
            x, y = i * h, j * h
            if 0 < i < n and 0 < j < n:
                dx, dy = shift(i, j)
                x, y = x + dx * h, y + dy * h
            lines.append(f"GRID,{gid(i, j)},,{x!r},{y!r},0.0")
    for j in range(n):
        for i in range(n):
            lines.append(
                f"CQUAD4,{gid(i, j)},1,{gid(i, j)},{gid(i + 1, j)},{gid(i + 1, j + 1)},{gid(i, j + 1)}{mcid}"
            )
    lines += [f"SPC1,1,123,{gid(0, 0)}", f"SPC1,1,23,{gid(n, 0)}", f"SPC1,1,3,{gid(0, n)}"]
    for j in range(n + 1):
        share = N * h * (0.5 if j in (0, n) else 1.0)
        lines.append(f"FORCE,1,{gid(n, j)},,{share!r},1.0,0.0,0.0")
        lines.append(f"FORCE,1,{gid(0, j)},,{share!r},-1.0,0.0,0.0")
    lines.append("ENDDATA")
    with open(f"reference-data/decks/{name}.bdf", "w") as f:
        f.write("\n".join(lines) + "\n")


deck("laminate-coupling-regular", 4, lambda i, j: (0.0, 0.0))
# Interior grids moved by up to a quarter of the spacing, in a fixed pattern. With THETA
# blank a ply's angle counts from its element's G1->G2 side, which the distortion turns:
# MCID 0 lays every element's material x along basic x, so the laminate is the same
# plate as on the regular mesh.
deck(
    "laminate-coupling-distorted",
    4,
    lambda i, j: (0.25 * ((i * 7 + j * 3) % 5 - 2) / 2, 0.2 * ((i * 3 + j * 5) % 5 - 2) / 2),
    mcid=",0",
)
