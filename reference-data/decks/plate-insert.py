# The paper's plate deck with a rigid insert under the impactor: plate.bdf with a grid
# at the centre element's centre (9999, at the plate's mid-plane) that an RBE2 makes the
# centre element's four corners follow (a rigid 0.12 in square), the contact acting on
# that grid alone (NOLIN3 scale K = 7.779e5, the impactor's, so the load derives from
# the Hertz potential: no external work), the indentation the impactor's travel minus
# grid 9999's. Written to reference-data/decks/plate-insert.bdf; run from the root:
#     python3 reference-data/decks/plate-insert.py
src = open("reference-data/decks/plate.bdf").read().splitlines()
out = [
    "$ The paper's plate (plate.bdf) with a rigid insert under the impactor: RBE2 9001 ties the centre",
    "$ element's corners 2525, 2526, 2625, 2626 to grid 9999 at its centre; the contact acts on 9999.",
    "$ Made by plate-insert.py.",
]
skip = False
for line in src:
    if line.startswith("NOLIN3, 5,2") or line.startswith("TF,111") or line.startswith("+TF-"):
        continue
    if line.startswith("NOLIN3, 5, 999"):
        out += [
            "$          THE INSERT: GRID 9999 AT THE CENTRE ELEMENT'S CENTRE, ITS CORNERS TIED TO IT",
            "GRID,9999,,0.0,0.0,0.0",
            "RBE2,9001,9999,123456,2525,2526,2625,2626",
            "NOLIN3,5,9999,3,+7.779+5,10001,0,1.5",
            line,
            "TF,111,10001,0,+1.0,00.0,00.0,,,+TF-1",
            "+TF-1,999,3,-1.0,00.0,00.0,,,,+TF-2",
            "+TF-2,9999,3,+1.0,00.0,00.0",
        ]
        continue
    if line.startswith("  SET 15"):
        line = "  SET 15 = 999,9999,2525,2626"
        out.append(line)
        out.append("  DISP = 15")
        continue
    out.append(line)
open("reference-data/decks/plate-insert.bdf", "w").write("\n".join(out) + "\n")
