# Beam decks with closed-form answers: SOL 101 decks of CBAR and CBEAM written to
# reference-data/decks/beams/, read by the verification cases beam-cantilever,
# beam-turned, beam-offset, beam-hinge and beam-frequencies. Each deck's header says
# its closed form; the numbers the cases hold them to are printed by this script.
# Run from the project root:
#     python3 reference-data/decks/beams.py
# Numbers are written with Python's repr (the shortest text that reads back to the
# same double).
import math
import os

OUT = "reference-data/decks/beams"
E, NU, RHO = 3.0e7, 0.3, 7.3e-4
G = E / (2.0 * (1.0 + NU))
# The cantilevers' PBAR: plane 1 stiffer than plane 2, so a swap of I1 and I2 shows.
A, I1, I2, J = 0.5, 0.02, 0.005, 0.01
L, N = 10.0, 4
FX, FY, FZ, MX = 200.0, 3.0, 5.0, 40.0


def write(name, header, bulk):
    lines = [f"$ {h}" for h in header] + [
        "$ Units: unspecified",
        "SOL 101",
        "CEND",
        "  SPC = 1",
        "  LOAD = 1",
        "BEGIN BULK",
        f"MAT1,1,{E!r},{G!r},,{RHO!r}",
    ] + bulk + ["ENDDATA"]
    with open(os.path.join(OUT, f"{name}.bdf"), "w") as f:
        f.write("\n".join(lines) + "\n")


def cantilever():
    # Along basic x, plane 1 = x-z (v = +z): a tip force along z bends it about I1.
    bulk = [f"PBAR,1,1,{A!r},{I1!r},{I2!r},{J!r}"]
    bulk += [f"GRID,{k + 1},,{L * k / N!r},0.0,0.0" for k in range(N + 1)]
    bulk += [f"CBAR,{k + 1},1,{k + 1},{k + 2},0.0,0.0,1.0" for k in range(N)]
    bulk += ["SPC1,1,123456,1", f"FORCE,1,{N + 1},,1.0,{FX!r},{FY!r},{FZ!r}", f"MOMENT,1,{N + 1},,{MX!r},1.0,0.0,0.0"]
    write(
        "cantilever",
        [
            "A cantilever of 4 CBARs (PBAR, plane 1 = x-z) under a tip force (200, 3, 5) and torque 40:",
            "tip u = FxL/EA, v = FyL^3/3EI2, w = FzL^3/3EI1, thx = MxL/GJ, thy = -FzL^2/2EI1 (Euler-Bernoulli).",
        ],
        bulk,
    )


def unit(v):
    n = math.sqrt(sum(x * x for x in v))
    return [x / n for x in v]


def cross(a, b):
    return [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]]


def dot(a, b):
    return sum(x * y for x, y in zip(a, b))


# The turned cantilever's element axes in basic: x along (1, 2, 2)/3, plane 1 normal
# to x containing (0, 0, 1)... made exact by Gram-Schmidt.
TX = unit([1.0, 2.0, 2.0])
TY = unit([v - dot([0.0, -1.0, 1.0], TX) * t for v, t in zip([0.0, -1.0, 1.0], TX)])
TZ = cross(TX, TY)
# GA's displacement frame: CORD2R 7, its z axis along (1, 1, 0), its xz-plane through (0, 0, 1).
C7 = (unit([1.0, 1.0, 0.0]), unit(cross(unit([1.0, 1.0, 0.0]), [0.0, 0.0, 1.0])))


def turned():
    # The cantilever above along TX, plane 1 = x-TY; its orientation vector given in
    # system 7 (GA's CD), its loads in the element's own axes written in basic.
    z7 = C7[0]
    x7 = unit(cross(cross(z7, [0.0, 0.0, 1.0]), z7))
    x7 = [-v for v in x7] if x7[2] < 0 else x7
    y7 = cross(z7, x7)
    v7 = [dot(TY, x7), dot(TY, y7), dot(TY, z7)]
    origin = [3.0, -1.0, 2.0]
    bulk = [f"PBAR,1,1,{A!r},{I1!r},{I2!r},{J!r}"]
    bulk.append(
        "CORD2R,7,,0.0,0.0,0.0," + ",".join(repr(v) for v in z7) + ",\n,"
        + ",".join(repr(x7[k] + 0.0) for k in range(3))
    )
    pts = [[origin[i] + L * k / N * TX[i] for i in range(3)] for k in range(N + 1)]
    bulk += [f"GRID,{k + 1},,{p[0]!r},{p[1]!r},{p[2]!r},{7 if k == 0 else ''}" for k, p in enumerate(pts)]
    bulk += [f"CBAR,1,1,1,2,{v7[0]!r},{v7[1]!r},{v7[2]!r}"]
    bulk += [f"CBAR,{k + 1},1,{k + 1},{k + 2},{TY[0]!r},{TY[1]!r},{TY[2]!r},BGG" for k in range(1, N)]
    f = [FX * TX[i] + FZ * TY[i] + FY * -TZ[i] for i in range(3)]
    m = [MX * TX[i] for i in range(3)]
    bulk += ["SPC1,1,123456,1", f"FORCE,1,{N + 1},,1.0,{f[0]!r},{f[1]!r},{f[2]!r}",
             f"MOMENT,1,{N + 1},,1.0,{m[0]!r},{m[1]!r},{m[2]!r}"]
    write(
        "cantilever-turned",
        [
            "The cantilever of cantilever.bdf turned in space: its axis along (1, 2, 2)/3, GA displaced in",
            "CORD2R 7 (its first bar's orientation vector given there), the loads along the element's axes.",
        ],
        bulk,
    )
    print("turned: tip", pts[-1], "x", TX, "plane-1 direction", TY, "plane-2 direction", [-v for v in TZ])


E_OFF = 0.4


def offset():
    # Grids on basic x, the bar E_OFF below them (WA = WB = (0, 0, -e)), plane 1 = x-z;
    # an axial tip force at the grid: u = FxL (1/EA + e^2/EI1), w = -e Fx L^2 / 2EI1.
    bulk = [f"PBAR,1,1,{A!r},{I1!r},{I2!r},{J!r}"]
    bulk += [f"GRID,{k + 1},,{L * k / N!r},0.0,0.0" for k in range(N + 1)]
    bulk += [
        f"CBAR,{k + 1},1,{k + 1},{k + 2},0.0,0.0,1.0\n,,,0.0,0.0,{-E_OFF!r},0.0,0.0,{-E_OFF!r}"
        for k in range(N)
    ]
    bulk += ["SPC1,1,123456,1", f"FORCE,1,{N + 1},,{FX!r},1.0,0.0,0.0"]
    write(
        "cantilever-offset",
        [
            f"The cantilever of cantilever.bdf with its bars {E_OFF} below its grids (WA = WB = (0, 0, -{E_OFF})),",
            "an axial force at the tip grid: u = FxL(1/EA + e^2/EI1), w = -e Fx L^2/2EI1.",
        ],
        bulk,
    )


L1, L2, B, H = 6.0, 4.0, 0.6, 0.8


def hinge():
    # A cantilever of length L1 hinged at its tip (element 2's PA = 6: its rotation in
    # plane 1 released at end A) to a link of length L2 on a roller: the link carries no
    # moment, so the hinge deflects F L1^3 / 3EI1 as a free cantilever's tip.
    bulk = [f"PBARL,1,1,,BAR\n,{B!r},{H!r}"]
    bulk += ["GRID,1,,0.0,0.0,0.0", f"GRID,2,,{L1!r},0.0,0.0", f"GRID,3,,{L1 + L2!r},0.0,0.0"]
    bulk += ["CBAR,1,1,1,2,0.0,0.0,1.0", "CBAR,2,1,2,3,0.0,0.0,1.0\n,6"]
    bulk += ["SPC1,1,123456,1", "SPC1,1,3,3", "FORCE,1,2,,10.0,0.0,0.0,1.0"]
    write(
        "hinge",
        [
            "A cantilever of length 6 hinged (PA = 6 on the second CBAR) to a link of length 4 on a roller,",
            "PBARL BAR 0.6 x 0.8, a force 10 along z at the hinge: w = F L1^3 / 3EI1, I1 = 0.6 * 0.8^3 / 12.",
        ],
        bulk,
    )


def hinge_twin():
    # The hinge of hinge() made by a rigid element instead of a pin flag: the link's
    # CBAR starts at grid 22, on grid 2, which an RBE2 ties to grid 2 in every
    # component but R2 (CM = 12346), the rotation in plane 1 (about -y, the element's
    # z). The same closed form.
    bulk = [f"PBARL,1,1,,BAR\n,{B!r},{H!r}"]
    bulk += ["GRID,1,,0.0,0.0,0.0", f"GRID,2,,{L1!r},0.0,0.0", f"GRID,22,,{L1!r},0.0,0.0",
             f"GRID,3,,{L1 + L2!r},0.0,0.0"]
    bulk += ["CBAR,1,1,1,2,0.0,0.0,1.0", "CBAR,2,1,22,3,0.0,0.0,1.0", "RBE2,9,2,12346,22"]
    bulk += ["SPC1,1,123456,1", "SPC1,1,3,3", "FORCE,1,2,,10.0,0.0,0.0,1.0"]
    write(
        "hinge-rbe2",
        [
            "The hinge of hinge.bdf made by an RBE2 of some components: grid 22 on grid 2 follows it in all",
            "but R2 (CM = 12346), the link's CBAR on 22 without a pin flag: w = F L1^3 / 3EI1.",
        ],
        bulk,
    )


LS = 20.0
BOX = [2.0, 1.0, 0.1, 0.15]


def ss_beam(n):
    # Simply supported CBEAMs (PBEAML BOX), plane 1 = x-z, a midspan force along z.
    bulk = [f"PBEAML,1,1,,BOX\n," + ",".join(repr(d) for d in BOX)]
    bulk += [f"GRID,{k + 1},,{LS * k / n!r},0.0,0.0" for k in range(n + 1)]
    bulk += [f"CBEAM,{k + 1},1,{k + 1},{k + 2},0.0,0.0,1.0" for k in range(n)]
    bulk += ["SPC1,1,1234,1", f"SPC1,1,234,{n + 1}", f"FORCE,1,{n // 2 + 1},,100.0,0.0,0.0,1.0"]
    write(
        f"ss-beam-{n}",
        [
            f"A simply supported beam of {n} CBEAMs (PBEAML BOX 2 x 1, walls 0.1 and 0.15), length 20,",
            "plane 1 = x-z, a force 100 along z at midspan: w = F L^3 / 48 E I1.",
        ],
        bulk,
    )


def box_constants(b, h, t1, t2):
    bi, hi = b - 2 * t2, h - 2 * t1
    a = b * h - bi * hi
    i1 = (b * h**3 - bi * hi**3) / 12
    i2 = (h * b**3 - hi * bi**3) / 12
    bm, hm = b - t2, h - t1
    j = 4 * (bm * hm) ** 2 / (2 * bm / t1 + 2 * hm / t2)
    return a, i1, i2, j


ES, TS, ZO, FS = 1.0e7, 0.2, 0.3, 100.0


def shell_offset_twin():
    # The strip of shell_offset() modelled without ZOFFS: its shells on grids 0.3 above,
    # each tied back to the grid below it by an RBE2 (NASTRAN's offset is that rigid
    # link), the clamp and the load on the grids below.
    bulk = [f"MAT1,2,{ES!r},,0.0,{RHO!r}", f"PSHELL,1,2,{TS!r},2"]
    for k in range(N + 1):
        x = L * k / N
        bulk += [f"GRID,{100 + k},,{x!r},0.0,0.0", f"GRID,{200 + k},,{x!r},1.0,0.0",
                 f"GRID,{300 + k},,{x!r},0.0,{ZO!r}", f"GRID,{400 + k},,{x!r},1.0,{ZO!r}",
                 f"RBE2,{500 + k},{100 + k},123456,{300 + k}", f"RBE2,{600 + k},{200 + k},123456,{400 + k}"]
    bulk += [f"CQUAD4,{k + 1},1,{300 + k},{301 + k},{401 + k},{400 + k}" for k in range(N)]
    bulk += ["SPC1,1,123456,100,200", f"FORCE,1,{100 + N},,{FS / 2!r},1.0,0.0,0.0",
             f"FORCE,1,{200 + N},,{FS / 2!r},1.0,0.0,0.0"]
    write(
        "shell-offset-twin",
        [
            f"The strip of shell-offset.bdf without ZOFFS: its CQUAD4s on grids {ZO} above, each tied to the grid",
            "below by an RBE2; clamped and pulled at the grids below, as the offset strip.",
        ],
        bulk,
    )


def shell_offset(turn=0.0):
    # A strip of 4 x 1 CQUAD4 (length 10, width 1, t = 0.2, NU = 0) with ZOFFS = +0.3 (its
    # reference plane above its grids), clamped at x = 0, pulled along x at the tip grids
    # (50 each): with NU = 0 it is a beam of section 1 x 0.2, so u = FL(1/EA + e^2/EI) and
    # w = +e F L^2 / 2EI; the membrane and DKQ bending are exact for its constant strain
    # and curvature.
    bulk = [f"MAT1,2,{ES!r},,0.0,{RHO!r}", f"PSHELL,1,2,{TS!r},2"]
    # Turned by `turn` degrees about the x axis (the grid line stays where it is).
    c, s = math.cos(math.radians(turn)), math.sin(math.radians(turn))
    for k in range(N + 1):
        bulk += [f"GRID,{100 + k},,{L * k / N!r},0.0,0.0", f"GRID,{200 + k},,{L * k / N!r},{c!r},{s!r}"]
    bulk += [f"CQUAD4,{k + 1},1,{100 + k},{101 + k},{201 + k},{200 + k},,{ZO!r}" for k in range(N)]
    bulk += ["SPC1,1,123456,100,200", f"FORCE,1,{100 + N},,{FS / 2!r},1.0,0.0,0.0",
             f"FORCE,1,{200 + N},,{FS / 2!r},1.0,0.0,0.0"]
    write(
        "shell-offset" if turn == 0.0 else "shell-offset-turned",
        [f"Turned {turn} degrees about x (its normal along (0, -sin, cos))."] * (turn != 0.0) + [
            f"A strip of 4 CQUAD4 (10 x 1, t = {TS}, NU = 0) with ZOFFS = +{ZO}, clamped at x = 0, pulled by",
            f"{FS} along its grid line at the tip: u = FL(1/EA + e^2/EI), w = +e F L^2/2EI (a beam of 1 x {TS}).",
        ],
        bulk,
    )


LK1, GAP, LK2, EK, FK = 4.0, 2.0, 4.0, 0.5, 20.0


def rigid_link():
    # A cantilever of two CBAR pieces joined by an RBE2 (GN the end of the first piece,
    # GM the start of the second, 2 along and 0.5 across, displaced in a turned CORD2R):
    # a crank. A tip force along z bends both pieces (plane 1) and twists the first by
    # F e: w = F[(L^3 - (L - L1)^3)/3 + L2^3/3]/EI1 + F e^2 L1/GJ (unit-load method;
    # the link stores nothing).
    L_ = LK1 + GAP + LK2
    bulk = [f"PBAR,1,1,{A!r},{I1!r},{I2!r},{J!r}",
            "CORD2R,7,,0.0,0.0,0.0,0.3,0.2,1.0,\n,1.0,-0.4,0.1"]
    pts = {1: (0.0, 0.0), 11: (LK1 / 2, 0.0), 2: (LK1, 0.0), 3: (LK1 + GAP, EK), 12: (LK1 + GAP + LK2 / 2, EK),
           4: (L_, EK)}
    for g, (x, y) in pts.items():
        bulk.append(f"GRID,{g},,{x!r},{y!r},0.0" + (",7" if g == 3 else ""))
    bulk += ["CBAR,1,1,1,11,0.0,0.0,1.0", "CBAR,2,1,11,2,0.0,0.0,1.0",
             "CBAR,3,1,3,12,0.0,0.0,1.0,BGG", "CBAR,4,1,12,4,0.0,0.0,1.0",
             "RBE2,9,2,123456,3", "SPC1,1,123456,1", f"FORCE,1,4,,{FK!r},0.0,0.0,1.0"]
    write(
        "rigid-link",
        [
            "A cantilever of two CBAR pieces (4 and 4) joined across a gap of 2 and a step of 0.5 by an RBE2",
            "(GN 2, GM 3 in a turned CORD2R), a tip force 20 along z: w = F[(L^3-(L-L1)^3)/3 + L2^3/3]/EI1 + F e^2 L1/GJ.",
        ],
        bulk,
    )


os.makedirs(OUT, exist_ok=True)
rigid_link()
shell_offset()
shell_offset(30.0)
shell_offset_twin()
cantilever()
turned()
offset()
hinge()
hinge_twin()
for n in (8, 16, 32):
    ss_beam(n)
print("cantilever tip: u", FX * L / (E * A), "v", FY * L**3 / (3 * E * I2), "w", FZ * L**3 / (3 * E * I1),
      "thx", MX * L / (G * J), "thy", -FZ * L**2 / (2 * E * I1))
print("offset tip: u", FX * L * (1 / (E * A) + E_OFF**2 / (E * I1)), "w", -E_OFF * FX * L**2 / (2 * E * I1))
print("hinge: w", 10.0 * L1**3 / (3 * E * B * H**3 / 12))
LL = LK1 + GAP + LK2
print("rigid link: w", FK * ((LL**3 - (LL - LK1) ** 3) / 3 + LK2**3 / 3) / (E * I1) + FK * EK**2 * LK1 / (G * J))
ia = TS**3 / 12
print("shell offset (turned 30: w along (0, -0.5, 0.866...)): u", FS * L * (1 / (ES * TS) + ZO**2 / (ES * ia)), "w", ZO * FS * L**2 / (2 * ES * ia))
a, i1, i2, j = box_constants(*BOX)
print("ss beam: A", a, "I1", i1, "I2", i2, "J", j, "midspan w", 100.0 * LS**3 / (48 * E * i1))
