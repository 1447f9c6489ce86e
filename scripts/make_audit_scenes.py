#!/usr/bin/env python3
"""Writes the glTF 2.0 test scenes of `depthprec audit` (docs/audit.md) into data/audit/.

The audit finds z-fighting pixels in a user's scene; its tests need scenes whose fights are known
by construction: a decal 1 mm before a wall at 500 m, a strip in a slab's plane, a road 5 cm above
a terrain, two boxes through each other, and the decal layout 10^6 m and 2000 m from the origin
(the second for mediump shaders). They are
built here from Python's standard library alone (no packages, no downloads), so the test inputs
can be regenerated from the repository, and the same run writes the same bytes.

Every visible surface is its own named mesh and node, so a report can say which surfaces fight;
nodes are drawn in scene order (depth first), so the surface meant to be in front comes last.
Each file has a perspective camera "main" (node and camera) looking at what the scene is about.

  scripts/make_audit_scenes.py                  the test scenes into data/audit/
  scripts/make_audit_scenes.py --out DIR        ... into DIR
  scripts/make_audit_scenes.py --terrain N OUT.glb
                                                terrain_road with N x N terrain quads (about
                                                2 N^2 triangles) for bench/audit_throughput.sh
"""
import argparse
import array
import base64
import json
import math
import struct
from pathlib import Path

GENERATOR = "depthprec scripts/make_audit_scenes.py"
ARRAY_BUFFER, ELEMENT_ARRAY_BUFFER = 34962, 34963
FLOAT, UNSIGNED_INT = 5126, 5125
TRIANGLES = 4
GLB_MAGIC, GLB_JSON, GLB_BIN = 0x46546C67, 0x4E4F534A, 0x004E4942


class Scene:
    """Named meshes, a node tree and one camera "main", all data in one buffer."""

    def __init__(self):
        self.buffer = bytearray()
        self.views, self.accessors, self.meshes = [], [], []
        self.nodes, self.roots, self.cameras = [], [], []

    def _view(self, data, target):
        # glTF wants each accessor aligned to its component size; 4 covers float and uint32
        self.buffer.extend(b"\0" * (-len(self.buffer) % 4))
        self.views.append({"buffer": 0, "byteOffset": len(self.buffer), "byteLength": len(data),
                           "target": target})
        self.buffer.extend(data)
        return len(self.views) - 1

    def mesh(self, name, positions, indices):
        """A one-primitive mesh from flat xyz floats and flat triangle indices; its index."""
        xyz = array.array("f", positions)
        # min/max of the binary32 values stored, as validators compare them with those
        lo = [min(xyz[k::3]) for k in range(3)]
        hi = [max(xyz[k::3]) for k in range(3)]
        position = len(self.accessors)
        self.accessors.append({"bufferView": self._view(xyz.tobytes(), ARRAY_BUFFER),
                               "componentType": FLOAT, "count": len(xyz) // 3, "type": "VEC3",
                               "min": lo, "max": hi})
        self.accessors.append({"bufferView": self._view(array.array("I", indices).tobytes(),
                                                        ELEMENT_ARRAY_BUFFER),
                               "componentType": UNSIGNED_INT, "count": len(indices),
                               "type": "SCALAR"})
        self.meshes.append({"name": name, "primitives": [{
            "attributes": {"POSITION": position}, "indices": position + 1, "mode": TRIANGLES}]})
        return len(self.meshes) - 1

    def node(self, name, parent=None, **fields):
        """A node (mesh=, camera=, translation=, rotation=, scale=): a root, or parent's child."""
        self.nodes.append({"name": name, **fields})
        index = len(self.nodes) - 1
        if parent is None:
            self.roots.append(index)
        else:
            self.nodes[parent].setdefault("children", []).append(index)
        return index

    def surface(self, name, geometry, parent=None, **fields):
        """A mesh and the node that draws it, both called name."""
        return self.node(name, parent, mesh=self.mesh(name, *geometry), **fields)

    def camera(self, eye, target, yfov_degrees, znear, zfar, parent=None):
        """The camera "main" at eye looking at target (both in parent's frame), +y up."""
        self.cameras.append({"name": "main", "type": "perspective", "perspective": {
            "yfov": math.radians(yfov_degrees), "aspectRatio": 16 / 9, "znear": znear,
            "zfar": zfar}})
        return self.node("main", parent, camera=len(self.cameras) - 1,
                         translation=list(eye), rotation=look_at(eye, target))

    def document(self, uri=None):
        buffer = {"byteLength": len(self.buffer)}
        if uri is not None:
            buffer["uri"] = uri
        return {"asset": {"version": "2.0", "generator": GENERATOR}, "scene": 0,
                "scenes": [{"nodes": self.roots}], "nodes": self.nodes, "meshes": self.meshes,
                "cameras": self.cameras, "accessors": self.accessors,
                "bufferViews": self.views, "buffers": [buffer]}


def dumps(document):
    return json.dumps(document, separators=(",", ":"))


def write_gltf(scene, path):
    """A .gltf with its buffer embedded, so the file stands alone."""
    uri = "data:application/octet-stream;base64," + base64.b64encode(scene.buffer).decode()
    Path(path).write_text(dumps(scene.document(uri)) + "\n", encoding="utf-8")


def write_glb(scene, path):
    """The GLB container: header, JSON chunk padded with spaces, BIN chunk padded with zeros."""
    text = dumps(scene.document()).encode()
    text += b" " * (-len(text) % 4)
    binary = bytes(scene.buffer) + b"\0" * (-len(scene.buffer) % 4)
    total = 12 + 8 + len(text) + 8 + len(binary)
    Path(path).write_bytes(struct.pack("<3I", GLB_MAGIC, 2, total) +
                           struct.pack("<2I", len(text), GLB_JSON) + text +
                           struct.pack("<2I", len(binary), GLB_BIN) + binary)


def write(scene, path):
    (write_glb if Path(path).suffix == ".glb" else write_gltf)(scene, path)


def look_at(eye, target):
    """The unit quaternion (x, y, z, w) turning local -z towards target, local +y up."""
    f = [t - e for t, e in zip(target, eye)]
    back = normalised([-c for c in f])  # the camera's +z: glTF cameras look down -z
    right = normalised([back[2], 0.0, -back[0]])  # +y x back
    up = cross(back, right)
    # the rotation matrix has columns right, up, back; Shepperd's method picks the largest
    # of w, x, y, z to divide by, so no branch loses precision
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
        q[i], q[j], q[k] = s / 4, (m[j][i] + m[i][j]) / s, (m[k][i] + m[i][k]) / s
        q[3] = (m[k][j] - m[j][k]) / s
    return normalised(q)


def normalised(v):
    n = math.sqrt(sum(c * c for c in v))
    if n == 0:
        raise ValueError("cannot normalise a zero vector (camera looking straight up or down?)")
    return [c / n for c in v]


def cross(a, b):
    return [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]]


def quad(origin, u, v):
    """The parallelogram origin, +u, +u+v, +v: 2 triangles facing u x v."""
    corners = [origin, [o + a for o, a in zip(origin, u)],
               [o + a + b for o, a, b in zip(origin, u, v)], [o + b for o, b in zip(origin, v)]]
    return [c for p in corners for c in p], [0, 1, 2, 0, 2, 3]


def box(lo, hi):
    """The axis-aligned box from corner lo to corner hi: 12 triangles facing outwards."""
    # corner k takes hi on x if bit 0 of k is set, on y for bit 1, on z for bit 2
    corners = [[(lo, hi)[k >> a & 1][a] for a in range(3)] for k in range(8)]
    faces = [(0, 2, 3, 1), (4, 5, 7, 6), (0, 1, 5, 4), (2, 6, 7, 3), (0, 4, 6, 2), (1, 3, 7, 5)]
    return ([c for p in corners for c in p],
            [i for a, b, c, d in faces for i in (a, b, c, a, c, d)])


def centred_box(centre, size):
    return box([c - s / 2 for c, s in zip(centre, size)],
               [c + s / 2 for c, s in zip(centre, size)])


def height_field(xs, zs, y):
    """Vertices (x, y(x, z), z) on the grid xs by zs, 2 triangles a quad facing +y."""
    positions = [c for z in zs for x in xs for c in (x, y(x, z), z)]
    row = len(xs)
    indices = []
    for j in range(len(zs) - 1):
        for a in range(j * row, j * row + row - 1):
            # a at (x, z), a + 1 at (x+, z), a + row at (x, z+): counter-clockwise from above
            indices += (a, a + row, a + row + 1, a, a + row + 1, a + 1)
    return positions, indices


def terrain_height(x, z):
    return 8 * math.sin(x / 90) * math.cos(z / 70)


def decal_wall(distance, gap, parent=None, scene=None):
    """The 100 m wall facing the camera at distance and a 10 m decal, centred on (5, 3), gap
    before it."""
    s = Scene() if scene is None else scene
    s.surface("wall", quad([-50, -50, -distance], [100, 0, 0], [0, 100, 0]), parent)
    s.surface("decal", quad([0, -2, -distance + gap], [10, 0, 0], [0, 10, 0]), parent)
    s.camera([0, 0, 0], [0, 0, -1], 10, 0.1, 100000, parent)
    return s


def slab_railing():
    s = Scene()
    s.surface("slab", box([-10, -0.3, -10], [10, 0, 10]))
    # the railing along the slab's near edge: the base strip there covers enough pixels
    railing = s.node("railing", translation=[0, 0, 9.9])
    for k in range(10):
        x = -9 + 2 * k
        s.surface(f"post_{k}", box([x - 0.025, 0, -0.025], [x + 0.025, 1.0, 0.025]), railing)
    # on the posts' tops rather than through them: only the base is meant to share a plane
    s.surface("top_rail", box([-9.025, 1.0, -0.025], [9.025, 1.05, 0.025]), railing)
    # in the slab's top plane y = 0 exactly, by construction: coplanar, not fighting
    s.surface("railing_base", quad([-10, 0, -0.1], [0, 0, 0.2], [20, 0, 0]), railing)
    s.camera([0, 8, 25], [0, 0, 0], 50, 0.1, 1000)
    return s


def terrain_road(n):
    """A 1 km height field of n x n quads and an 8 m road 5 cm above it along z."""
    s = Scene()
    rows = [-500 + 1000 * j / n for j in range(n + 1)]
    s.surface("terrain", height_field(rows, rows, terrain_height))
    # the same z rows; across, x = -4, 0, 4, which the terrain only interpolates between, so
    # the gap is 5 cm at the road's vertices only (for n = 64, -0.9 to 10.9 cm in between)
    s.surface("road", height_field([-4, 0, 4], rows, lambda x, z: terrain_height(x, z) + 0.05))
    # from 250 m up: seen from near the ground the gap along each ray grows with the distance as
    # fast as unorm24's resolution shrinks, and nothing fights before 4 km
    s.camera([0, 250, 700], [0, 0, -100], 45, 0.1, 5000)
    return s


def intersecting_boxes():
    s = Scene()
    s.surface("box_a", centred_box([-1, 0, -20], [4, 4, 4]))
    s.surface("box_b", centred_box([1, 0.5, -21], [4, 4, 4]))
    s.camera([6, 5, 0], [0, 0, -20], 40, 0.1, 1000)
    return s


def far_from_origin():
    """The decal layout at 50 m with a 1 cm gap, under a node 10^6 m from the origin."""
    s = Scene()
    site = s.node("site", translation=[1000000, 0, 1000000])
    return decal_wall(50, 0.01, site, s)


def mobile_site():
    """The decal layout at 20 m with a 5 cm gap, under a node 2000 m from the origin: a mediump
    vertex shader holds world coordinates there to a metre or two (binary16's spacing from 1024
    and from 2048), highp to a tenth of a millimetre."""
    s = Scene()
    site = s.node("site", translation=[2000, 0, 2000])
    return decal_wall(20, 0.05, site, s)


def drone_road():
    """An 800 m road 1 cm above the ground, reaching behind a drone camera 60 m up: the ground and
    the road cross the near plane, as ground planes do in almost every game view."""
    s = Scene()
    s.surface("ground", quad([-2500, 0, 2500], [5000, 0, 0], [0, 0, -5000]))
    s.surface("road", quad([-10, 0.01, 400], [20, 0, 0], [0, 0, -800]))
    s.camera([0, 60, 300], [0, 0, -300], 50, 0.1, 5000)
    return s


def ground_strip():
    """A 20 km ground crossing the near plane (near 1 mm) with a strip 1 cm above it, seen from
    eye height: whether it fights in one view is a matter of where the eye stands to the mm."""
    s = Scene()
    s.surface("ground", quad([-10000, 0, 10000], [20000, 0, 0], [0, 0, -20000]))
    s.surface("strip", quad([-2, 0.01, 10000], [4, 0, 0], [0, 0, -20000]))
    s.camera([0, 1.7, 0], [0, 0, -100], 60, 0.001, 10000)
    return s


def shelf_wall():
    """A shelf whose back face lies in the wall, drawn after the wall: the shelf's top and front
    hide both, so no pixel of it is coplanar."""
    s = Scene()
    s.surface("wall", quad([-5, 0, -5], [10, 0, 0], [0, 4, 0]))
    s.surface("shelf", box([-1, 1.0, -5], [1, 1.05, -4.7]))
    s.camera([0, 1.8, 0], [0, 1.0, -5], 50, 0.1, 100)
    return s


def rug_tiles():
    """A rug 0.1 mm above a floor drawn twice, as two coplanar meshes of other tessellations, seen
    25 m away with near 3 cm: the floors are coplanar where they show, not under the rug."""
    s = Scene()
    s.surface("floor_coarse", quad([-10, 0, 0], [20, 0, 0], [0, 0, -40]))
    s.surface("floor_tiles", height_field([-10 + 2.5 * k for k in range(9)],
                                          [-5 * k for k in range(9)], lambda x, z: 0.0))
    s.surface("rug", quad([-1, 0.0001, -23.5], [2, 0, 0], [0, 0, -3]))
    s.camera([0, 1.7, 0], [0, 0, -25], 50, 0.03, 1000)
    return s


def write_test_scenes(out):
    out.mkdir(parents=True, exist_ok=True)
    decal = decal_wall(500, 0.001)
    write(decal, out / "decal_wall.gltf")
    write(decal, out / "decal_wall.glb")
    write(slab_railing(), out / "slab_railing.gltf")
    write(terrain_road(64), out / "terrain_road.gltf")
    write(intersecting_boxes(), out / "intersecting_boxes.gltf")
    write(far_from_origin(), out / "far_from_origin.glb")
    write(mobile_site(), out / "mobile_site.gltf")
    write(drone_road(), out / "drone_road.gltf")
    write(ground_strip(), out / "ground_strip.gltf")
    write(shelf_wall(), out / "shelf_wall.gltf")
    write(rug_tiles(), out / "rug_tiles.gltf")


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--out", type=Path,
                        default=Path(__file__).resolve().parent.parent / "data" / "audit",
                        help="directory for the test scenes (default: data/audit/)")
    parser.add_argument("--terrain", nargs=2, metavar=("N", "OUT.glb"),
                        help="write only a terrain of N x N quads with a road, for benchmarks")
    args = parser.parse_args()
    if args.terrain:
        n = int(args.terrain[0]) if args.terrain[0].isdigit() else 0
        if n < 1:
            parser.error("--terrain N needs a whole number N >= 1")
        write(terrain_road(n), args.terrain[1])
    else:
        write_test_scenes(args.out)


if __name__ == "__main__":
    main()
