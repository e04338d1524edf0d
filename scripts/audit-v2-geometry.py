#!/usr/bin/env python3
"""Independent check of the exporter's mesh geometry (scripts/audit-v2.ts
writes the scenes and exports): the world-space PLY the exporter wrote for
meshes[i] must hold the same triangles as Mitsuba's own loader gives for the
original file with Mitsuba's own to_world (scale, rotate x, y, z, translate =
translate * Rz * Ry * Rx * scale, the format's definition). Our renderer and
the exporter share src/scene/mesh/transform.ts, so a bug there would be
invisible in the image comparison; this catches it. For glTF (which Mitsuba
cannot read) the node transforms are applied here with numpy from the JSON.
Also checks that the exported vertex normals / winding agree with Mitsuba's.

    python3 scripts/audit-v2-geometry.py [/tmp/audit-v2]
"""
import base64
import json
import os
import re
import sys

import numpy as np
import mitsuba as mi

FIXTURE_MESHES = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "test", "fixtures", "meshes")
mi.set_variant("scalar_rgb")
mi.set_log_level(mi.LogLevel.Error)


def to_world(mesh):
    s = mesh.get("scale", 1)
    s = [s, s, s] if isinstance(s, (int, float)) else s
    rx, ry, rz = mesh.get("rotation", [0, 0, 0])
    t = mi.ScalarTransform4f().translate(mesh.get("position", [0, 0, 0]))
    return t @ mi.ScalarTransform4f().rotate([0, 0, 1], rz) @ mi.ScalarTransform4f().rotate([0, 1, 0], ry) \
        @ mi.ScalarTransform4f().rotate([1, 0, 0], rx) @ mi.ScalarTransform4f().scale(s)


def triangles(shape):
    p = np.array(mi.traverse(shape)["vertex_positions"]).reshape(-1, 3)
    f = np.array(mi.traverse(shape)["faces"]).reshape(-1, 3)
    tri = p[f]  # (n, 3, 3)
    n = np.cross(tri[:, 1] - tri[:, 0], tri[:, 2] - tri[:, 0])
    return tri, n / np.linalg.norm(n, axis=1, keepdims=True)


def centroid_normals(shape):
    """Per triangle: centroid and the normalized mean of its vertex normals (None when flat)."""
    params = mi.traverse(shape)
    if "vertex_normals" not in params or len(params["vertex_normals"]) == 0:
        return None
    p = np.array(params["vertex_positions"]).reshape(-1, 3)
    n = np.array(params["vertex_normals"]).reshape(-1, 3)
    f = np.array(params["faces"]).reshape(-1, 3)
    c, m = p[f].mean(1), n[f].mean(1)
    m /= np.linalg.norm(m, axis=1, keepdims=True)
    order = np.lexsort(np.round(c, 5).T[::-1])
    return m[order]


def canonical(tri):
    """Triangles as sorted centroids (order- and rotation-of-corners-independent)."""
    c = tri.mean(axis=1)
    return c[np.lexsort(np.round(c, 5).T[::-1])]


def quat_matrix(q):
    x, y, z, w = q
    return np.array([
        [1 - 2 * (y * y + z * z), 2 * (x * y - z * w), 2 * (x * z + y * w)],
        [2 * (x * y + z * w), 1 - 2 * (x * x + z * z), 2 * (y * z - x * w)],
        [2 * (x * z - y * w), 2 * (y * z + x * w), 1 - 2 * (x * x + y * y)],
    ])


def gltf_triangles(path):
    g = json.load(open(path))
    buf = base64.b64decode(g["buffers"][0]["uri"].split(",", 1)[1])

    def accessor(i):
        a = g["accessors"][i]
        v = g["bufferViews"][a["bufferView"]]
        comps = {"VEC3": 3, "SCALAR": 1}[a["type"]]
        dtype = {5126: np.float32, 5123: np.uint16, 5125: np.uint32}[a["componentType"]]
        stride = v.get("byteStride", comps * np.dtype(dtype).itemsize)
        base = v.get("byteOffset", 0) + a.get("byteOffset", 0)
        out = [np.frombuffer(buf, dtype, comps, base + k * stride) for k in range(a["count"])]
        return np.array(out).reshape(a["count"], comps)

    def local(node):
        if "matrix" in node:
            return np.array(node["matrix"]).reshape(4, 4).T
        m = np.eye(4)
        m[:3, :3] = quat_matrix(node.get("rotation", [0, 0, 0, 1])) @ np.diag(node.get("scale", [1, 1, 1]))
        m[:3, 3] = node.get("translation", [0, 0, 0])
        return m

    tris = []

    def walk(i, parent):
        node = g["nodes"][i]
        m = parent @ local(node)
        if "mesh" in node:
            for prim in g["meshes"][node["mesh"]]["primitives"]:
                p = accessor(prim["attributes"]["POSITION"])
                idx = accessor(prim["indices"]).reshape(-1, 3)
                pw = (m[:3, :3] @ p.T).T + m[:3, 3]
                tri = pw[idx]
                if np.linalg.det(m[:3, :3]) < 0:
                    tri = tri[:, [0, 2, 1]]
                tris.append(tri)
        for c in node.get("children", []):
            walk(c, m)

    for i in g["scenes"][g.get("scene", 0)]["nodes"]:
        walk(i, np.eye(4))
    return np.concatenate(tris)


def main(root):
    bad = 0
    for name in sorted(os.listdir(root)):
        d = os.path.join(root, name)
        sf = os.path.join(d, "scene.json")
        if not os.path.exists(sf) or not os.path.exists(os.path.join(d, "scene.xml")):
            continue
        scene = json.load(open(sf))
        for i, mesh in enumerate(scene.get("meshes", [])):
            exported = mi.load_dict({"type": "ply", "filename": os.path.join(d, f"scene-mesh{i}.ply"), "face_normals": True})
            et, en = triangles(exported)
            f = os.path.join(d, mesh["file"])
            ext = f.rsplit(".", 1)[1].lower()
            twin = re.match(r"(ico-(?:smooth|flat))(-.*)?\.(ply|glb)$", os.path.basename(f))
            if ext in ("obj", "ply", "glb") and (ext == "obj" or twin):
                if ext != "obj":
                    # Mitsuba 3.9.1 cannot read glb, nor our PLY fixtures (extra elements,
                    # "trailing content"): use the OBJ twin, the same mesh (make-mesh-fixtures.ts).
                    f, ext = os.path.join(FIXTURE_MESHES, twin.group(1) + ".obj"), "obj"
                    print(f"{name} meshes[{i}] {mesh['file']}: checked against its twin {os.path.basename(f)}")
                raw = mi.load_dict({"type": ext, "filename": f, "to_world": to_world(mesh), "face_normals": True})
                rt, rn = triangles(raw)
            elif ext == "gltf":
                m = np.array(to_world(mesh).matrix)
                rt = gltf_triangles(f)
                rt = np.einsum("ij,nkj->nki", m[:3, :3], rt) + m[:3, 3]
                if np.linalg.det(m[:3, :3]) < 0:
                    rt = rt[:, [0, 2, 1]]
                rn = np.cross(rt[:, 1] - rt[:, 0], rt[:, 2] - rt[:, 0])
                rn /= np.linalg.norm(rn, axis=1, keepdims=True)
            else:
                print(f"{name} meshes[{i}] {mesh['file']}: skipped (Mitsuba cannot read .{ext})")
                continue
            if len(et) != len(rt):
                print(f"{name} meshes[{i}]: triangle count {len(et)} vs {len(rt)}  MISMATCH")
                bad += 1
                continue
            ce, cr = canonical(et), canonical(rt)
            dp = np.abs(ce - cr).max()
            # Winding: mean face normal dotted with the centroid direction from the mesh centre.
            oe = np.mean(np.sum(en * (et.mean(1) - et.mean((0, 1))), 1))
            orr = np.mean(np.sum(rn * (rt.mean(1) - rt.mean((0, 1))), 1))
            dn = np.abs(en.mean(0) - rn.mean(0)).max()  # mean face normal (informative for open meshes too)
            ok = dp < 1e-4 and np.sign(oe) == np.sign(orr) and dn < 1e-4
            exported_path = os.path.join(d, f"scene-mesh{i}.ply")
            smooth = b"property float nx" in open(exported_path, "rb").read(600)
            if ext == "obj" and smooth:
                # Smooth files: the exported vertex normals vs Mitsuba's own to_world of the file's normals.
                ne = centroid_normals(mi.load_dict({"type": "ply", "filename": os.path.join(d, f"scene-mesh{i}.ply")}))
                nr = centroid_normals(mi.load_dict({"type": "obj", "filename": f, "to_world": to_world(mesh)}))
                if ne is not None and nr is not None:
                    dvn = np.abs(ne - nr).max()
                    ok = ok and dvn < 1e-4
                    print(f"    vertex normals: max diff {dvn:.2e}")
            bad += not ok
            print(f"{name} meshes[{i}] {mesh['file']}: {len(et)} triangles, max centroid diff {dp:.2e}, "
                  f"outward winding exported {oe:+.3f} vs independent {orr:+.3f}, mean face normal diff {dn:.1e}  {'ok' if ok else 'MISMATCH'}")
    sys.exit(1 if bad else 0)


if __name__ == "__main__":
    main(sys.argv[1] if len(sys.argv) > 1 else "/tmp/audit-v2")
