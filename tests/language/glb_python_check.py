#!/usr/bin/env python3
"""An independent reader of the .glb files sculpt exports (the test sculpt.glb_python_check).

Only Python's struct and json: the container as glTF 2.0 sec. 4.4 lays it out (magic, version,
length, 4-byte aligned JSON and BIN chunks, their padding), the POSITION and index accessors as the
spec defines them (sec. 3.6), and then the mesh: closed (every directed edge once, positions merged
by their exact float32 values) and of the volume sculpt prints, within float32 precision.

Usage: glb_python_check.py SCULPT_EXECUTABLE SCRATCH_DIR
"""
import json
import os
import struct
import subprocess
import sys

SOLIDS = {
    "box": "box([-1.5, 0, 0.25], [2, 3.125, 4])",
    "sphere": "sphere(1.3, segments=24)",
    "csg": "box([-1, -1, -1], [1, 1, 1]) - sphere(1.2, segments=16) | cylinder(0.3, 2.5, segments=12)",
}
COMPONENT = {5121: ("B", 1), 5123: ("H", 2), 5125: ("I", 4), 5126: ("f", 4)}
WIDTH = {"SCALAR": 1, "VEC3": 3}


def fail(message):
    print("glb_python_check: " + message)
    sys.exit(1)


def read_accessor(gltf, binary, index):
    acc = gltf["accessors"][index]
    view = gltf["bufferViews"][acc["bufferView"]]
    fmt, size = COMPONENT[acc["componentType"]]
    n = WIDTH[acc["type"]]
    stride = view.get("byteStride", size * n)
    start = view.get("byteOffset", 0) + acc.get("byteOffset", 0)
    end = start + (acc["count"] - 1) * stride + size * n
    if end > view.get("byteOffset", 0) + view["byteLength"] or end > len(binary):
        fail("accessor %d reads beyond its buffer view" % index)
    return [struct.unpack_from("<" + fmt * n, binary, start + i * stride) for i in range(acc["count"])]


def check(path, expected_volume, area):
    data = open(path, "rb").read()
    magic, version, length = struct.unpack_from("<III", data, 0)
    if magic != 0x46546C67 or version != 2 or length != len(data):
        fail("%s: header magic %x version %d length %d (file %d)" % (path, magic, version, length, len(data)))
    json_length, json_type = struct.unpack_from("<II", data, 12)
    if json_type != 0x4E4F534A or json_length % 4:
        fail("%s: the first chunk is not a 4-byte aligned JSON chunk" % path)
    text = data[20:20 + json_length]
    if text.rstrip(b" ") != text.rstrip():
        fail("%s: the JSON chunk is not padded with spaces" % path)
    gltf = json.loads(text.decode("utf-8"))
    at = 20 + json_length
    bin_length, bin_type = struct.unpack_from("<II", data, at)
    if bin_type != 0x004E4942 or bin_length % 4 or at + 8 + bin_length != len(data):
        fail("%s: the BIN chunk is not 4-byte aligned or does not end the file" % path)
    binary = data[at + 8:]
    byte_length = gltf["buffers"][0]["byteLength"]
    if byte_length > len(binary) or any(binary[byte_length:]):
        fail("%s: the BIN chunk is not padded with zeros" % path)
    if gltf["asset"]["version"] != "2.0":
        fail("%s: asset.version is %r" % (path, gltf["asset"]["version"]))
    (primitive,) = gltf["meshes"][0]["primitives"]
    if primitive.get("mode", 4) != 4:
        fail("%s: mode %r" % (path, primitive.get("mode")))
    acc = gltf["accessors"][primitive["attributes"]["POSITION"]]
    points = read_accessor(gltf, binary, primitive["attributes"]["POSITION"])
    for k in range(3):  # min and max must be the data's own bounds (sec. 3.6.2.5)
        if acc["min"][k] != min(p[k] for p in points) or acc["max"][k] != max(p[k] for p in points):
            fail("%s: POSITION min/max differ from the data" % path)
    indices = [i for (i,) in read_accessor(gltf, binary, primitive["indices"])]
    if len(indices) % 3 or max(indices) >= len(points):
        fail("%s: bad index count or an index out of range" % path)
    merged = {}
    vertex = [merged.setdefault(p, len(merged)) for p in points]
    edges = {}
    volume = 0.0
    for t in range(0, len(indices), 3):
        a, b, c = (vertex[indices[t + k]] for k in range(3))
        for e in ((a, b), (b, c), (c, a)):
            edges[e] = edges.get(e, 0) + 1
        p, q, r = (points[indices[t + k]] for k in range(3))
        volume += (p[0] * (q[1] * r[2] - q[2] * r[1]) - p[1] * (q[0] * r[2] - q[2] * r[0]) +
                   p[2] * (q[0] * r[1] - q[1] * r[0])) / 6
    for (a, b), n in edges.items():
        if n != 1 or edges.get((b, a)) != 1:
            fail("%s: edge %d-%d is used %d times, its reverse %s times (not closed)" % (path, a, b, n, edges.get((b, a))))
    largest = max(max(abs(x) for x in p) for p in points)
    bound = area * largest * 2.0 ** -23
    if abs(volume - expected_volume) > bound:
        fail("%s: volume %.17g, sculpt says %.17g (bound %.3g)" % (path, volume, expected_volume, bound))
    print("%s: %d triangles, closed, volume %.12g (sculpt %.12g)" % (os.path.basename(path), len(indices) // 3,
                                                                        volume, expected_volume))


def main():
    sculpt, scratch = sys.argv[1], sys.argv[2]
    os.makedirs(scratch, exist_ok=True)
    code = ""
    for name, solid in SOLIDS.items():
        path = os.path.join(scratch, name + ".glb")
        code += 's = %s\nexport(s, "%s")\nprint(volume(s), area(s))\n' % (solid, path)
    out = subprocess.run([sculpt, "-e", code], capture_output=True, text=True, check=True).stdout.split()
    for k, name in enumerate(SOLIDS):
        check(os.path.join(scratch, name + ".glb"), float(out[2 * k]), float(out[2 * k + 1]))


if __name__ == "__main__":
    main()
