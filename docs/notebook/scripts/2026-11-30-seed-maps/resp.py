import csv, sys
rows = [r for r in csv.DictReader(l for l in open(sys.argv[1]) if not l.startswith("#"))]
for inp in sorted({r["input"] for r in rows}):
    sel = {(int(r["ix"]), int(r["iy"])): r for r in rows if r["input"] == inp}
    # cold column n*vy response (rows 3..6) approximated as n * du_y; T at (9,9) and column means of T
    col = [float(sel[(9, iy)]["u_y"]) * 5.5 for iy in range(3, 7)]
    corner = float(sel[(9, 9)]["T"]); hotc = float(sel[(0, 0)]["T"]), float(sel[(1, 0)]["T"])
    colT = [sum(float(sel[(ix, iy)]["T"]) for iy in range(10)) / 10 for ix in range(10)]
    print(f"{inp:20s} cold-col n*vy {sum(col)/4:+.4f}  T(19,19) {corner:+.4f}  T(1..3,1) {hotc[0]:+.4f} {hotc[1]:+.4f}  colT " + " ".join(f"{100*v:+.2f}" for v in colT))
