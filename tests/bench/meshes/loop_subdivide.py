#!/usr/bin/env python3
"""Loop subdivision of a closed triangle mesh (OFF in, OFF out), for larger real-mesh benchmarks:
each level has four times the triangles of the last, on a smooth surface near the original.
    loop_subdivide.py IN.off LEVELS OUT.off
(Loop 1987: new edge points 3/8 (a + b) + 1/8 (c + d); old vertices (1 - n beta) v + beta sum,
beta = 3 / (8 n) for n > 3, 3/16 for n = 3 (Warren's weights).)"""
import sys


def read_off(path):
    tokens = [t for line in open(path) for t in line.split('#')[0].split()]
    assert tokens[0] == 'OFF', 'not an OFF file'
    nv, nf = int(tokens[1]), int(tokens[2])
    at = 4
    verts = []
    for _ in range(nv):
        verts.append(tuple(float(x) for x in tokens[at:at + 3]))
        at += 3
    faces = []
    for _ in range(nf):
        k = int(tokens[at])
        faces.append(tuple(int(x) for x in tokens[at + 1:at + 1 + k]))
        at += 1 + k
    return verts, faces


def subdivide(verts, faces):
    opposite = {}  # edge (a, b) -> the third vertex of the triangle on it
    neighbours = [set() for _ in verts]
    for a, b, c in faces:
        for p, q, r in ((a, b, c), (b, c, a), (c, a, b)):
            opposite[(p, q)] = r
            neighbours[p].add(q)
            neighbours[q].add(p)
    new_verts = []
    for v, ring in zip(verts, neighbours):
        n = len(ring)
        beta = 3.0 / 16.0 if n == 3 else 3.0 / (8.0 * n)
        s = [sum(verts[w][k] for w in ring) for k in range(3)]
        new_verts.append(tuple((1 - n * beta) * v[k] + beta * s[k] for k in range(3)))
    edge_point = {}
    for (p, q), r in opposite.items():
        if (q, p) in edge_point:
            edge_point[(p, q)] = edge_point[(q, p)]
            continue
        d = opposite[(q, p)]
        new_verts.append(tuple(0.375 * (verts[p][k] + verts[q][k]) + 0.125 * (verts[r][k] + verts[d][k]) for k in range(3)))
        edge_point[(p, q)] = len(new_verts) - 1
    new_faces = []
    for a, b, c in faces:
        ab, bc, ca = edge_point[(a, b)], edge_point[(b, c)], edge_point[(c, a)]
        new_faces += [(a, ab, ca), (b, bc, ab), (c, ca, bc), (ab, bc, ca)]
    return new_verts, new_faces


def main():
    if len(sys.argv) != 4:
        sys.exit(__doc__)
    verts, faces = read_off(sys.argv[1])
    for _ in range(int(sys.argv[2])):
        verts, faces = subdivide(verts, faces)
    with open(sys.argv[3], 'w') as out:
        out.write('OFF\n%d %d 0\n' % (len(verts), len(faces)))
        out.writelines('%.17g %.17g %.17g\n' % v for v in verts)
        out.writelines('3 %d %d %d\n' % f for f in faces)


main()
