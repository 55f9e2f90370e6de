# The paper's plate deck turned in space: every grid (the impactor's too) turned by
# R = Rz(2.2) Ry(-0.4) Rx(0.7) and moved by (3, -2, 11), displaced in CORD2R 7, the
# plate's own axes turned the same way.
import math
ax, ay, az = 0.7, -0.4, 2.2
def mat(a, b):
    return [[sum(a[i][k]*b[k][j] for k in range(3)) for j in range(3)] for i in range(3)]
rx = [[1,0,0],[0,math.cos(ax),-math.sin(ax)],[0,math.sin(ax),math.cos(ax)]]
ry = [[math.cos(ay),0,math.sin(ay)],[0,1,0],[-math.sin(ay),0,math.cos(ay)]]
rz = [[math.cos(az),-math.sin(az),0],[math.sin(az),math.cos(az),0],[0,0,1]]
R = mat(rz, mat(ry, rx))
t = [3.0, -2.0, 11.0]
def turn(p):
    return [sum(R[i][k]*p[k] for k in range(3)) + t[i] for i in range(3)]
src = open('reference-data/decks/plate-mesh-49x49.bdf').read().splitlines()
out = ["$ The paper's plate mesh (plate-mesh-49x49.bdf) turned in space for plate-turned.bdf:",
       "$ every grid at R p + t, R = Rz(2.2) Ry(-0.4) Rx(0.7) (radians), t = (3, -2, 11) in,",
       "$ displaced in CORD2R 7 (the plate's normal its z). Units: in."]
i = 0
while i < len(src):
    l = src[i]
    if l.startswith('GRID*'):
        gid = int(l[8:24]); x = float(l[40:56]); y = float(l[56:72])
        z = float(src[i+1][8:24])
        X = turn([x, y, z])
        out.append(f"GRID,{gid},,{X[0]!r},{X[1]!r},{X[2]!r},7")
        i += 2
        continue
    if not l.startswith('$'):
        out.append(l)
    i += 1
open('reference-data/decks/plate-turned-mesh.bdf','w').write('\n'.join(out)+'\n')
deck = open('reference-data/decks/plate.bdf').read().replace("  NLLOAD = 15\n", "  NLLOAD = 15\n  DISP = 15\n")
assert "DISP = 15" in deck
flat = open('reference-data/decks/plate.bdf').read().replace("  NLLOAD = 15\n", "  NLLOAD = 15\n  DISP = 15\n")
open('/tmp/plate-disp.bdf', 'w').write(flat)
c30, s30 = math.cos(math.radians(30.0)), math.sin(math.radians(30.0))
A = t; B = [t[i] + R[i][2] for i in range(3)]; C = [t[i] + R[i][1] for i in range(3)]
imp = turn([0.0, 0.0, -0.1875])
deck = deck.replace("GRID,999,,0.0,0.0,-0.1875", f"GRID,999,,{imp[0]!r},{imp[1]!r},{imp[2]!r},7")
deck = deck.replace("INCLUDE 'plate-mesh-49x49.bdf'", "CORD2R,7,0,{!r},{!r},{!r},{!r},{!r},{!r}\n,{!r},{!r},{!r}\nINCLUDE 'plate-turned-mesh.bdf'".format(*A, *B, *C))
head = ("$ The paper's plate deck (plate.bdf) turned in space: its grids, the impactor's too, turned\n"
        "$ by R = Rz(2.2) Ry(-0.4) Rx(0.7) and moved by (3, -2, 11) in, each displaced in CORD2R 7,\n"
        "$ its z the plate's normal, its x the plate's y, its y the plate's -x: every SPC1, TF,\n"
        "$ NOLIN3, TIC and PS of the deck means what it meant (none names an in-plane\n"
        "$ component but all six together), and DISP = 15 writes the rotations in that\n"
        "$ frame (R1 here is the flat plate's R2). Otherwise plate.bdf with DISP = 15.\n")
open('reference-data/decks/plate-turned.bdf','w').write(head + deck)
