# The paper's plate deck with a mass hung on an RBE3: plate.bdf with a CONM2 (mass
# 1.0e-4 lbf s^2/in, about the impactor's, and inertias 1.0e-6 lbf s^2 in) on grid
# 9998, half an inch behind the plate under grid 3535 (1.16 in from the centre along
# both x and y), which an RBE3 ties to the translations of the nine grids 3434-3636
# about it, weights 1 at the corners, 2 at the mid-sides and 4 at 3535. The RBE3 is
# in the load path: the plate carries the mass through it. Written to
# reference-data/decks/plate-rbe3.bdf; run from the root:
#     python3 reference-data/decks/plate-rbe3.py
src = open("reference-data/decks/plate.bdf").read().splitlines()
out = [
    "$ The paper's plate (plate.bdf) with a mass hung on an RBE3: CONM2 9002 on grid 9998, 0.5 in behind",
    "$ grid 3535, which RBE3 9001 ties to the translations of grids 3434-3636. Made by plate-rbe3.py.",
]
x = (35 - 25.5) * 6 / 49
for line in src:
    if line.startswith("GRDSET"):
        out.append(line)
        out += [
            "$          A MASS HUNG ON THE PLATE BY AN RBE3 (ITS GRID HOLDS NO COMPONENT: PS = 0)",
            f"GRID,9998,,{x!r},{x!r},-0.5,,0",
            "CONM2,9002,9998,0,1.0-4,,,,,+M9002",
            "+M9002,1.0-6,,1.0-6,,,1.0-6",
            "RBE3,9001,,9998,123456,1.0,123,3434,3436,",
            ",3634,3636,2.0,123,3435,3534,3536,3635,",
            ",4.0,123,3535",
        ]
        continue
    if line.startswith("  SET 15"):
        out.append(line)
        out.append("  SET 16 = 9998,3535")
        out.append("  DISP = 16")
        continue
    out.append(line)
open("reference-data/decks/plate-rbe3.bdf", "w").write("\n".join(out) + "\n")
