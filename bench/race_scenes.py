"""The scenes `mitsuba_compare.py` races on, and the files it hands each
renderer: the small plane and box, the real model (fetched once into the
cache, centred and scaled to 4 m across), the million generated triangles,
and the same f32 triangles written as GLB for lumlab and as binary PLY for
Mitsuba (face normals only: neither file has vertex normals)."""

import hashlib
import json
import math
import os
import struct
import sys
import urllib.request
from pathlib import Path

import numpy as np

PLANE_COLOR = (0.7, 0.7, 0.7)
BOX_COLOR = (0.8, 0.2, 0.1)
MODEL_COLOR = (0.6, 0.6, 0.65)


# ---------------------------------------------------------------- geometry


def quads(corners, faces):
    """Triangles of quads given as corner index lists (counter-clockwise)."""
    tris = [(f[0], f[1], f[2]) for f in faces] + [(f[0], f[2], f[3]) for f in faces]
    return np.asarray(corners, dtype=np.float64), np.asarray(tris, dtype=np.uint32)


def plane(half):
    c = [(-half, 0.0, half), (half, 0.0, half), (half, 0.0, -half), (-half, 0.0, -half)]
    return quads(c, [(0, 1, 2, 3)])


def box(lo, hi, yaw_deg):
    """An axis-aligned box turned by yaw_deg about +Y."""
    c = [(hi[0] if i & 1 else lo[0], hi[1] if i & 2 else lo[1], hi[2] if i & 4 else lo[2]) for i in range(8)]
    faces = [(1, 3, 7, 5), (4, 6, 2, 0), (2, 6, 7, 3), (0, 1, 5, 4), (4, 5, 7, 6), (1, 0, 2, 3)]
    positions, indices = quads(c, faces)
    a = math.radians(yaw_deg)
    # Rotation about +Y (right-handed): x' = x cos a + z sin a, z' = −x sin a + z cos a.
    turn = np.array([[math.cos(a), 0, math.sin(a)], [0, 1, 0], [-math.sin(a), 0, math.cos(a)]])
    return positions @ turn.T, indices


def bumpy_sphere(centre, radius, n):
    """A UV sphere of 2 n² triangles, its radius rippled by 4 %."""
    theta = np.linspace(0.0, math.pi, n + 1)
    phi = np.linspace(0.0, 2.0 * math.pi, n + 1)
    t, p = np.meshgrid(theta, phi, indexing="ij")
    r = radius * (1.0 + 0.04 * np.sin(7.0 * t) * np.sin(9.0 * p))
    pos = np.stack([r * np.sin(t) * np.cos(p), r * np.cos(t), -r * np.sin(t) * np.sin(p)], axis=-1)
    pos = pos.reshape(-1, 3) + np.asarray(centre)
    i, j = np.meshgrid(np.arange(n), np.arange(n), indexing="ij")
    a = (i * (n + 1) + j).ravel()
    b, c, d = a + 1, a + n + 2, a + n + 1
    # (t, φ) → (a, b = φ + 1, c, d = θ + 1): counter-clockwise seen from outside.
    tris = np.concatenate([np.stack([a, d, c], 1), np.stack([a, c, b], 1)])
    return pos, tris.astype(np.uint32)


def read_glb(path):
    """Every triangle of a GLB file in world space (node matrices and TRS
    applied), as one (positions, indices) pair."""
    data = Path(path).read_bytes()
    magic, _, _ = struct.unpack_from("<III", data, 0)
    if magic != 0x46546C67:
        sys.exit(f"{path}: not a GLB file")
    offset, doc, blob = 12, None, b""
    while offset < len(data):
        length, kind = struct.unpack_from("<II", data, offset)
        chunk = data[offset + 8 : offset + 8 + length]
        doc, blob = (json.loads(chunk), blob) if kind == 0x4E4F534A else (doc, chunk)
        offset += 8 + length

    def accessor(index):
        acc = doc["accessors"][index]
        view = doc["bufferViews"][acc["bufferView"]]
        dtype = {5121: np.uint8, 5123: np.uint16, 5125: np.uint32, 5126: np.float32}[acc["componentType"]]
        width = {"SCALAR": 1, "VEC3": 3}[acc["type"]]
        itemsize = np.dtype(dtype).itemsize * width
        stride = view.get("byteStride", itemsize)
        start = view.get("byteOffset", 0) + acc.get("byteOffset", 0)
        raw = np.frombuffer(blob, np.uint8, count=stride * (acc["count"] - 1) + itemsize, offset=start)
        rows = np.lib.stride_tricks.as_strided(raw, (acc["count"], itemsize), (stride, 1))
        return np.ascontiguousarray(rows).view(dtype).reshape(acc["count"], width)

    def local(node):
        if "matrix" in node:
            return np.array(node["matrix"], dtype=np.float64).reshape(4, 4).T
        x, y, z, w = node.get("rotation", (0.0, 0.0, 0.0, 1.0))
        rot = np.array(
            [
                [1 - 2 * (y * y + z * z), 2 * (x * y - z * w), 2 * (x * z + y * w)],
                [2 * (x * y + z * w), 1 - 2 * (x * x + z * z), 2 * (y * z - x * w)],
                [2 * (x * z - y * w), 2 * (y * z + x * w), 1 - 2 * (x * x + y * y)],
            ]
        )
        m = np.eye(4)
        m[:3, :3] = rot * np.asarray(node.get("scale", (1.0, 1.0, 1.0)))
        m[:3, 3] = node.get("translation", (0.0, 0.0, 0.0))
        return m

    positions, indices, count = [], [], 0
    stack = [(n, np.eye(4)) for n in doc["scenes"][doc.get("scene", 0)]["nodes"]]
    while stack:
        index, parent = stack.pop()
        node = doc["nodes"][index]
        world = parent @ local(node)
        stack += [(c, world) for c in node.get("children", [])]
        for prim in doc["meshes"][node["mesh"]]["primitives"] if "mesh" in node else []:
            if prim.get("mode", 4) != 4:
                continue
            p = accessor(prim["attributes"]["POSITION"]).astype(np.float64)
            ids = accessor(prim["indices"]).ravel() if "indices" in prim else np.arange(len(p))
            positions.append(p @ world[:3, :3].T + world[:3, 3])
            indices.append(ids.astype(np.uint32) + count)
            count += len(p)
    return np.concatenate(positions), np.concatenate(indices).reshape(-1, 3)


# ---------------------------------------------------------------- scenes


class Scene:
    """Meshes (name, positions, triangles, colour), a camera and a light."""

    def __init__(self, meshes, eye, target, light, size, spp):
        self.meshes, self.eye, self.target, self.light = meshes, eye, target, light
        self.size, self.spp = size, spp

    def triangles(self):
        return sum(len(t) for _, _, t, _ in self.meshes)


def small_scene():
    meshes = [
        ("plane", *plane(5.0), PLANE_COLOR),
        ("box", *box((-0.6, 0.0, -0.6), (0.6, 1.2, 0.6), 25.0), BOX_COLOR),
    ]
    return Scene(meshes, (3.5, 3.0, 5.0), (0.0, 0.4, 0.0), (2.0, 4.0, 1.5), (256, 192), 64)


def framed(meshes, size, spp):
    """A camera and light placed from the meshes' bounds."""
    allp = np.concatenate([p for _, p, _, _ in meshes])
    lo, hi = allp.min(0), allp.max(0)
    c, r = 0.5 * (lo + hi), 0.5 * float(np.linalg.norm(hi - lo))
    eye = tuple(c + r * np.array([1.3, 1.0, 2.2]))
    light = tuple(c + r * np.array([0.8, 1.6, 0.9]))
    return Scene(meshes, eye, tuple(c), light, size, spp)


MODEL_NAME = "2CylinderEngine.glb"
MODEL_URLS = (
    "https://raw.githubusercontent.com/KhronosGroup/glTF-Sample-Models/HEAD/2.0/2CylinderEngine/glTF-Binary/",
    "https://raw.githubusercontent.com/assimp/assimp/HEAD/test/models/glTF2/2CylinderEngine-glTF-Binary/",
)
# The copy the README's and docs/performance.md's numbers were measured on.
MODEL_SHA256 = "bb5fbccc73a3f68c52f26687fbb25b4a1248ab5f8a115ec55e7ac6a4451c47ee"


def fetched_model():
    """The model race's GLB from the cache, fetched there first if need be
    (written to a temporary name, then renamed: never a half file)."""
    cache = Path(os.environ.get("XDG_CACHE_HOME") or Path.home() / ".cache") / "lumlab" / MODEL_NAME
    if not cache.exists():
        errors = []
        for url in (base + MODEL_NAME for base in MODEL_URLS):
            try:
                with urllib.request.urlopen(url, timeout=60) as response:
                    data = response.read()
            except OSError as e:
                errors.append(f"{url}: {e}")
                continue
            if data[:4] != b"glTF":
                errors.append(f"{url}: not a GLB file")
                continue
            cache.parent.mkdir(parents=True, exist_ok=True)
            part = cache.with_name(cache.name + ".part")
            part.write_bytes(data)
            part.replace(cache)
            print(f"fetched {url} into {cache}")
            break
        else:
            sys.exit(f"could not fetch {MODEL_NAME} ({'; '.join(errors)}): pass --model FILE.glb")
    digest = hashlib.sha256(cache.read_bytes()).hexdigest()
    if digest != MODEL_SHA256:
        print(f"note: {cache} is not the copy the README measured (SHA-256 {digest})")
    return cache


def model_scene(path):
    p, t = read_glb(path)
    lo, hi = p.min(0), p.max(0)
    p = (p - 0.5 * (lo + hi)) * (4.0 / float((hi - lo).max()))
    return framed([("model", p, t, MODEL_COLOR)], (512, 384), 32)


def million_scene():
    meshes = [("ground", *plane(6.5), PLANE_COLOR)]
    for i in range(5):
        for j in range(5):
            centre = (2.2 * (i - 2), 1.0, 2.2 * (j - 2))
            meshes.append((f"s{i}{j}", *bumpy_sphere(centre, 1.0, 141), MODEL_COLOR))
    return framed(meshes, (512, 384), 16)


# ---------------------------------------------------------------- files


def write_glb(path, scene):
    """GLB 2.0: one node per mesh, f32 positions already in world space, u32
    indices, a base colour per material (no normals: face normals)."""
    blob, doc = bytearray(), {"asset": {"version": "2.0"}, "scene": 0, "scenes": [{"nodes": []}]}
    for key in ("nodes", "meshes", "materials", "accessors", "bufferViews"):
        doc[key] = []

    def add(data, target, **acc):
        while len(blob) % 4:
            blob.append(0)
        doc["bufferViews"].append({"buffer": 0, "byteOffset": len(blob), "byteLength": len(data), "target": target})
        blob.extend(data)
        doc["accessors"].append({"bufferView": len(doc["bufferViews"]) - 1, **acc})
        return len(doc["accessors"]) - 1

    for name, positions, tris, color in scene.meshes:
        p = positions.astype("<f4")
        pos = add(p.tobytes(), 34962, componentType=5126, count=len(p), type="VEC3",
                  min=p.min(0).tolist(), max=p.max(0).tolist())  # fmt: skip
        ids = add(tris.astype("<u4").tobytes(), 34963, componentType=5125, count=tris.size, type="SCALAR")
        doc["materials"].append(
            {"name": name, "pbrMetallicRoughness": {"baseColorFactor": [*color, 1.0], "metallicFactor": 0.0}}
        )
        prim = {"attributes": {"POSITION": pos}, "indices": ids, "material": len(doc["materials"]) - 1}
        doc["meshes"].append({"name": name, "primitives": [prim]})
        doc["nodes"].append({"name": name, "mesh": len(doc["meshes"]) - 1})
        doc["scenes"][0]["nodes"].append(len(doc["nodes"]) - 1)
    doc["buffers"] = [{"byteLength": len(blob)}]
    text = json.dumps(doc).encode()
    text += b" " * (-len(text) % 4)
    blob += b"\0" * (-len(blob) % 4)
    total = 12 + 8 + len(text) + 8 + len(blob)
    Path(path).write_bytes(
        struct.pack("<III", 0x46546C67, 2, total)
        + struct.pack("<II", len(text), 0x4E4F534A) + text
        + struct.pack("<II", len(blob), 0x004E4942) + bytes(blob)
    )  # fmt: skip


def write_ply(path, positions, tris):
    """Binary little-endian PLY with the same f32 vertices and faces."""
    header = (
        "ply\nformat binary_little_endian 1.0\n"
        f"element vertex {len(positions)}\nproperty float x\nproperty float y\nproperty float z\n"
        f"element face {len(tris)}\nproperty list uchar int vertex_indices\nend_header\n"
    )
    faces = np.zeros(len(tris), dtype=[("n", "u1"), ("i", "<i4", 3)])
    faces["n"], faces["i"] = 3, tris
    Path(path).write_bytes(header.encode() + positions.astype("<f4").tobytes() + faces.tobytes())
