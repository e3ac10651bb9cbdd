#!/usr/bin/env python3
"""Writes the seed corpus of fuzz_geometry (tests/fuzz/corpus_geometry/): a few programs in the
byte layout fuzz_geometry.cpp decodes, so the fuzzer starts from every kind of operation.
Run from anywhere: python3 tests/fuzz/make_geometry_corpus.py"""
import os
import struct

HERE = os.path.dirname(os.path.abspath(__file__))
OUT = os.path.join(HERE, "corpus_geometry")


def s8(v):
    return struct.pack("b", v)


def coord(sixteenths, fine=None):
    """A coordinate: sixteenths / 16, plus fine * 2^-15 when given."""
    if fine is None:
        return bytes([0]) + s8(sixteenths)
    return bytes([3]) + s8(sixteenths) + s8(fine)


def point(x, y, z):
    return coord(x) + coord(y) + coord(z)


CLASSIFY = bytes([64, 128, 192, 200, 30, 100, 10, 250, 128])  # three points per checked solid


def box(lo, ext):  # lo in sixteenths, ext bytes (e -> (1 + e % 64) / 16)
    return bytes([0]) + point(*lo) + bytes(ext) + CLASSIFY


def sphere(r, seg):  # r -> (2 + r % 63) / 16, seg -> 3 + seg % 22
    return bytes([1, r, seg]) + CLASSIFY


def cylinder(r, h, seg, cone=False):
    return bytes([2, 1 if cone else 0, r, h, seg]) + CLASSIFY


def translate(a, v):
    return bytes([3, a]) + point(*v) + CLASSIFY


def rotate(a, axis, mode, k, general=None):  # axis bytes -> b % 7 - 3
    b = bytes([4, a] + [c + 3 for c in axis] + [mode]) + s8(k)
    if mode % 5 == 3:
        b += struct.pack("<h", general)
    return b + CLASSIFY


def scale(a, factors):  # factor indices into {1, 2, 3, -1, -2, 0.5, 1.5, 0.75, -0.5, 0.1}
    if len(factors) == 1:
        return bytes([5, a, 0, factors[0]]) + CLASSIFY
    return bytes([5, a, 1] + factors) + CLASSIFY


def setop(a, b, which):  # which: 0 union, 1 difference, 2 intersection
    return bytes([6, a, b, which]) + CLASSIFY


def union_all(items):
    return bytes([8, len(items) - 2] + items) + CLASSIFY


def revolve(z0, points, path_kind, seg, radii=()):  # points: (r byte, axis flag or None, dz byte)
    b = bytes([9, len(points) - 2]) + s8(z0)
    for k, (r, flag, dz) in enumerate(points):
        b += bytes([r])
        if k == 0 or k == len(points) - 1:
            b += bytes([0 if flag else 1])
        b += bytes([dz])
    return b + bytes([path_kind, seg] + list(radii)) + CLASSIFY


def export_import(a, fmt):  # fmt: 0 off, 1 obj, 2 ply, 3 stl
    return bytes([10, a, fmt]) + CLASSIFY


def small_mesh(kind, size, centre, offsets):
    b = bytes([11, kind, size]) + point(*centre)
    for o in offsets:
        b += b"".join(s8(c) for c in o)
    return b + CLASSIFY


def mesh_bytes(kind, size, centre, offsets):
    b = bytes([kind, size]) + point(*centre)
    for o in offsets:
        b += b"".join(s8(c) for c in o)
    return b


def crossing_shells(a, b, inverted):  # two small meshes in one file (winding import)
    return bytes([12]) + mesh_bytes(*a) + mesh_bytes(*b) + bytes([1 if inverted else 0]) + CLASSIFY


def touching_box(a, axis, upper, spans):  # spans: for the two other axes, (mode, extent byte or None)
    b = bytes([13, a, axis, 1 if upper else 0, 15])
    for mode, ext in spans:
        b += bytes([mode]) + (bytes([ext]) if ext is not None else b"")
    return b + CLASSIFY


OCTAHEDRON = [(0, 0, 0)] * 6
SEEDS = {
    "boxes_union": box((0, 0, 0), [15, 15, 15]) + box((8, 8, 8), [15, 15, 15]) + setop(0, 1, 0),
    "boxes_shared_face": box((0, 0, 0), [15, 15, 15]) + box((16, 0, 0), [15, 15, 15]) + setop(0, 1, 0)
    + setop(2, 0, 1),
    "sphere_rotated_minus_box": sphere(14, 13) + rotate(0, (1, 2, -1), 3, 0, 37 * 64 + 5)
    + box((-4, -4, -4), [15, 15, 15]) + setop(1, 2, 1),
    "cone_cylinder_quarter_turn": cylinder(10, 20, 9) + cylinder(12, 16, 5, cone=True)
    + rotate(1, (0, 1, 0), 0, 1) + setop(0, 2, 2) + scale(3, [5])
    + translate(4, (1, -2, 3)),
    "self_operations": box((-8, -8, -8), [31, 7, 3]) + setop(0, 0, 0) + setop(0, 0, 1) + setop(0, 0, 2)
    + union_all([0, 1, 0]),
    "revolve_and_import": revolve(-8, [(0, True, 8), (20, None, 8), (12, None, 8), (0, True, 0)], 0, 13)
    + export_import(0, 0) + rotate(1, (1, 1, 0), 1, 1) + export_import(2, 2) + setop(0, 3, 1),
    "small_meshes": small_mesh(1, 20, (0, 0, 0), [(3, -2, 1), (0, 0, 0), (1, 5, -3), (0, 0, 0), (2, 2, 2), (-4, 1, 0)])
    + small_mesh(6, 14, (4, 4, 4), [(0, 0, 0), (7, 0, 0), (0, -5, 0), (0, 0, 9)])
    + setop(0, 1, 0) + export_import(2, 3) + scale(3, [1, 5, 3]),
    "fine_features": bytes([0]) + coord(0, 3) + coord(0) + coord(0, -5) + bytes([15, 240, 15]) + CLASSIFY
    + box((0, 0, 0), [15, 15, 15]) + setop(0, 1, 1) + rotate(2, (3, -1, 2), 4, 100)
    + rotate(3, (0, 0, 1), 2, 1),
    "crossing_shells": crossing_shells((1, 20, (0, 0, 0), OCTAHEDRON), (1, 20, (8, 4, 0), OCTAHEDRON), False)
    + crossing_shells((3, 30, (0, 0, 0), OCTAHEDRON), (1, 10, (2, 0, 0), [(3, 1, -2)] * 6), True),
    "touching_box_and_cylinder": cylinder(10, 20, 8) + touching_box(0, 0, True, [(0, None), (2, 15)])
    + box((0, 0, 0), [15, 15, 15]) + touching_box(2, 2, False, [(3, 7), (1, None)]) + setop(1, 3, 0),
}

os.makedirs(OUT, exist_ok=True)
for name, data in SEEDS.items():
    with open(os.path.join(OUT, name), "wb") as f:
        f.write(data)
print(f"{len(SEEDS)} seeds in {OUT}")
