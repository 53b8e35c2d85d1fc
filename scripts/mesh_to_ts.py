#!/usr/bin/env python3
"""Converts a MEDIT .mesh of tetrahedra (e.g. `starplex generate grid 95 95 95 -o g.mesh`) to the
Stellar reference's .ts format (`nv nt`, then `x y z field` per vertex, then 0-based tetrahedra),
for the side-by-side harness ../shared/peers/bench_stellar_ref.py. Standard library only.
usage: scripts/mesh_to_ts.py IN.mesh OUT.ts"""
import sys

def main(src, dst):
    lines = open(src).read().split('\n')
    i = lines.index('Vertices'); nv = int(lines[i + 1]); verts = lines[i + 2:i + 2 + nv]
    j = lines.index('Tetrahedra'); nt = int(lines[j + 1]); tets = lines[j + 2:j + 2 + nt]
    with open(dst, 'w') as o:
        o.write(f"{nv} {nt}\n")
        for l in verts:
            x, y, z = l.split()[:3]
            o.write(f"{x} {y} {z} {z}\n")
        for l in tets:
            q = [int(x) - 1 for x in l.split()[:4]]
            o.write(f"{q[0]} {q[1]} {q[2]} {q[3]}\n")

if __name__ == '__main__':
    if len(sys.argv) != 3:
        sys.exit(__doc__)
    main(sys.argv[1], sys.argv[2])
