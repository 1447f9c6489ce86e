#!/usr/bin/env python3
"""Writes the glTF 2.0 test scenes of `depthprec audit` (docs/audit.md) into data/audit/.

Each scene is a small, named, deterministic file built here from the standard library alone (no
downloads, no packages), so the tests' inputs are reproducible from the repository: run it again
and the files come out byte for byte the same (a test checks that). Each file has a camera node
"main" looking at what the scene is about, and its surfaces are drawn in node order, the surface
meant to be in front last.

  scripts/make_audit_scenes.py                  the five test scenes into data/audit/
  scripts/make_audit_scenes.py --out DIR        ... into DIR
  scripts/make_audit_scenes.py --terrain N OUT.glb
                                                a terrain of N x N quads (about 2 N^2 triangles)
                                                with a road, for bench/audit_throughput.sh
"""
import argparse
import array
import base64
import json
import math
import struct
from pathlib import Path

GENERATOR = "depthprec scripts/make_audit_scenes.py"


class Scene:
    """Meshes, nodes and one camera, packed into one buffer."""

    def __init__(self):
        self.buffer = bytearray()
        self.views, self.accessors, self.meshes, self.nodes, self.roots = [], [], [], [], []

    def _view(self, data, target):
        while len(self.buffer) % 4:
            self.buffer.append(0)
        self.views.append({"buffer": 0, "byteOffset": len(self.buffer),
                           "byteLength": len(data), "target": target})
        self.buffer.extend(data)
        return len(self.views) - 1

    def mesh(self, name, positions, triangles):
        """A mesh of float positions [(x, y, z)] and triangles [(a, b, c)]; returns its index."""
        flat = array.array("f", [c for p in positions for c in p])
        stored = [flat[i:i + 3] for i in range(0, len(flat), 3)]  # as binary32, for min/max
        pos = self._view(flat.tobytes(), 34962)
        idx = self._view(array.array("I", [i for t in triangles for i in t]).tobytes(), 34963)
        self.accessors.append({"bufferView": pos, "componentType": 5126, "count": len(positions),
                               "type": "VEC3",
                               "min": [min(p[k] for p in stored) for k in range(3)],
                               "max": [max(p[k] for p in stored) for k in range(3)]})
        self.accessors.append({"bufferView": idx, "componentType": 5125,
                               "count": 3 * len(triangles), "type": "SCALAR"})
        self.meshes.append({"name": name, "primitives": [{
            "attributes": {"POSITION": len(self.accessors) - 2},
            "indices": len(self.accessors) - 1, "mode": 4}]})
        return len(self.meshes) - 1

    def node(self, name, parent=None, **fields):
        """A node (mesh=..., camera=..., translation=..., rotation=...), a root or a child."""
        self.nodes.append(dict(name=name, **fields))
        index = len(self.nodes) - 1
        if parent is None:
            self.roots.append(index)
        else:
            self.nodes[parent].setdefault("children", []).append(index)
        return index

    def surface(self, name, positions, triangles, parent=None, **fields):
        return self.node(name, parent, mesh=self.mesh(name, positions, triangles), **fields)

    def camera(self, eye, target, yfov_deg, znear, zfar, parent=None):
        """The camera "main" at eye looking at target (local coordinates of parent), +y up."""
        self.cameras = [{"name": "main", "type": "perspective", "perspective": {
            "yfov": math.radians(yfov_deg), "aspectRatio": 16 / 9, "znear": znear,
            "zfar": zfar}}]
        self.node("main", parent, camera=0, translation=list(eye),
                  rotation=look_at_quaternion(eye, target))

    def gltf(self, uri):
        g = {"asset": {"version": "2.0", "generator": GENERATOR}, "scene": 0,
             "scenes": [{"nodes": self.roots}], "nodes": self.nodes, "meshes": self.meshes,
             "cameras": self.cameras, "accessors": self.accessors, "bufferViews": self.views,
             "buffers": [{"byteLength": len(self.buffer)}]}
        if uri:
            g["buffers"][0]["uri"] = ("data:application/octet-stream;base64," +
                                      base64.b64encode(bytes(self.buffer)).decode())
        return json.dumps(g, separators=(",", ":"))

    def write(self, path):
        path = Path(path)
        if path.suffix == ".glb":
            path.write_bytes(glb(self.gltf(uri=False).encode(), bytes(self.buffer)))
        else:
            path.write_text(self.gltf(uri=True) + "\n")


def glb(json_bytes, binary):
    """The GLB container: header, JSON chunk padded with spaces, BIN chunk padded with zeros."""
    json_bytes += b" " * (-len(json_bytes) % 4)
    binary += b"\0" * (-len(binary) % 4)
    total = 12 + 8 + len(json_bytes) + 8 + len(binary)
    return (struct.pack("<III", 0x46546C67, 2, total) +
            struct.pack("<II", len(json_bytes), 0x4E4F534A) + json_bytes +
            struct.pack("<II", len(binary), 0x004E4942) + binary)


def look_at_quaternion(eye, target):
    """The rotation (x, y, z, w) turning the camera's -z towards target with +y up."""
    f = [t - e for t, e in zip(target, eye)]
    n = math.sqrt(sum(c * c for c in f))
    back = [-c / n for c in f]  # the camera's +z
    right = [back[2], 0.0, -back[0]]  # up x back with up = +y
    rn = math.sqrt(sum(c * c for c in right)) or 1.0
    right = [c / rn for c in right]
    up = [back[1] * right[2] - back[2] * right[1], back[2] * right[0] - back[0] * right[2],
          back[0] * right[1] - back[1] * right[0]]
    m = [[right[0], up[0], back[0]], [right[1], up[1], back[1]], [right[2], up[2], back[2]]]
    trace = m[0][0] + m[1][1] + m[2][2]
    if trace > 0:
        s = 2 * math.sqrt(trace + 1)
        q = [(m[2][1] - m[1][2]) / s, (m[0][2] - m[2][0]) / s, (m[1][0] - m[0][1]) / s, s / 4]
    else:
        i = max(range(3), key=lambda k: m[k][k])
        j, k = (i + 1) % 3, (i + 2) % 3
        s = 2 * math.sqrt(1 + m[i][i] - m[j][j] - m[k][k])
        q = [0.0] * 4
        q[i] = s / 4
        q[j] = (m[j][i] + m[i][j]) / s
        q[k] = (m[k][i] + m[i][k]) / s
        q[3] = (m[k][j] - m[j][k]) / s
    return [round(c, 12) for c in q]


def quad(x0, x1, y0, y1, z):
    """A quad in the plane z facing +z: 4 corners, 2 counter-clockwise triangles."""
    return [(x0, y0, z), (x1, y0, z), (x1, y1, z), (x0, y1, z)], [(0, 1, 2), (0, 2, 3)]


def box(cx, cy, cz, sx, sy, sz):
    """An axis-aligned box of 12 outward-facing triangles."""
    p = [(cx + dx * sx / 2, cy + dy * sy / 2, cz + dz * sz / 2)
         for dz in (-1, 1) for dy in (-1, 1) for dx in (-1, 1)]
    faces = [(0, 2, 3, 1), (4, 5, 7, 6), (0, 1, 5, 4), (2, 6, 7, 3), (0, 4, 6, 2), (1, 3, 7, 5)]
    return p, [t for a, b, c, d in faces for t in ((a, b, c), (a, c, d))]


def grid(columns, rows, position):
    """A height field of columns x rows quads: position(i, j) gives vertex (i, j)."""
    p = [position(i, j) for j in range(rows + 1) for i in range(columns + 1)]
    t = []
    for j in range(rows):
        for i in range(columns):
            a = j * (columns + 1) + i
            b, c, d = a + 1, a + columns + 2, a + columns + 1
            t += [(a, d, c), (a, c, b)]  # counter-clockwise seen from above
    return p, t


def height(x, z):
    return 8 * math.sin(x / 90) * math.cos(z / 70)


def decal_wall(distance, gap):
    s = Scene()
    s.surface("wall", *quad(-50, 50, -50, 50, -distance))
    s.surface("decal", *quad(0, 10, -2, 8, -distance + gap))
    return s


def slab_railing():
    s = Scene()
    s.surface("slab", *box(0, -0.15, 0, 20, 0.3, 20))
    railing = s.node("railing", translation=[0, 0, -8.9])  # along the slab's far edge
    for k in range(10):
        s.surface(f"post_{k}", *box(-9 + 2 * k, 0.5, 0, 0.05, 1.0, 0.05), parent=railing)
    s.surface("top_rail", *box(0, 1.0, 0, 18.1, 0.05, 0.05), parent=railing)
    # in the slab's top plane y = 0 exactly: coplanar by construction
    p, t = quad(-10, 10, -1.0, 1.0, 0)
    s.surface("railing_base", [(x, 0.0, -y) for x, y, _ in p], [(a, c, b) for a, b, c in t],
              parent=railing)
    s.camera((0, 8, 25), (0, 0, 0), 50, 0.1, 1000)
    return s


def terrain_road(n):
    s = Scene()
    size = 1000.0
    s.surface("terrain", *grid(n, n, lambda i, j: (
        -size / 2 + size * i / n, height(-size / 2 + size * i / n, -size / 2 + size * j / n),
        -size / 2 + size * j / n)))
    s.surface("road", *grid(2, n, lambda i, j: (
        -4.0 + 4.0 * i, height(-4.0 + 4.0 * i, -size / 2 + size * j / n) + 0.05,
        -size / 2 + size * j / n)))
    s.camera((0, 250, 700), (0, 0, -100), 45, 0.1, 5000)
    return s


def intersecting_boxes():
    s = Scene()
    s.surface("box_a", *box(-1, 0, -20, 4, 4, 4))
    s.surface("box_b", *box(1, 0.5, -21, 4, 4, 4))
    s.camera((6, 5, 0), (0, 0, -20), 40, 0.1, 1000)
    return s


def far_from_origin():
    s = Scene()
    site = s.node("site", translation=[1000000, 0, 1000000])
    s.surface("wall", *quad(-50, 50, -50, 50, -50), parent=site)
    s.surface("decal", *quad(0, 10, -2, 8, -49.99), parent=site)
    s.camera((0, 0, 0), (0, 0, -1), 10, 0.1, 100000, parent=site)
    return s


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--out", type=Path,
                        default=Path(__file__).resolve().parent.parent / "data" / "audit")
    parser.add_argument("--terrain", nargs=2, metavar=("N", "OUT.glb"))
    args = parser.parse_args()
    if args.terrain:
        terrain_road(int(args.terrain[0])).write(args.terrain[1])
        return
    args.out.mkdir(parents=True, exist_ok=True)
    decal = decal_wall(500, 0.001)
    decal.camera((0, 0, 0), (0, 0, -1), 10, 0.1, 100000)
    decal.write(args.out / "decal_wall.gltf")
    decal.write(args.out / "decal_wall.glb")
    slab_railing().write(args.out / "slab_railing.gltf")
    terrain_road(64).write(args.out / "terrain_road.gltf")
    intersecting_boxes().write(args.out / "intersecting_boxes.gltf")
    far_from_origin().write(args.out / "far_from_origin.glb")


if __name__ == "__main__":
    main()
