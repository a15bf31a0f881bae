#!/usr/bin/env python3
"""Writes the glTF fuzz seeds into corpus/gltf: a tiny valid skinned rig (three joints, one triangle, a
two-key animation) as .gltf (buffer in a data URI) and as .glb, plus variants that each break one thing
glTF loaders are known to get wrong: accessor offsets and counts that overflow, sparse accessors with bad
indices, deep and cyclic node trees, huge declared buffer sizes, skins with bad joints or too few inverse
bind matrices. Run it again after changing it; the files are small and checked in."""
import base64
import copy
import json
import os
import struct

here = os.path.dirname(os.path.abspath(__file__))
out_dir = os.path.join(here, "corpus", "gltf")

FLOAT, UBYTE, USHORT, UINT = 5126, 5121, 5123, 5125


def rig(key_times=(0.0, 0.5)):
    """The valid rig: its JSON (without buffers) and its binary buffer; its two animation keys at key_times."""
    blob = b""
    views, accessors = [], []

    def add(data, fmt, count, comp, typ, extra=None):
        nonlocal blob
        while len(blob) % 4:
            blob += b"\0"
        views.append({"buffer": 0, "byteOffset": len(blob), "byteLength": len(data)})
        blob += data
        acc = {"bufferView": len(views) - 1, "componentType": comp, "count": count, "type": typ}
        acc.update(extra or {})
        accessors.append(acc)
        return len(accessors) - 1

    f = lambda *v: struct.pack("<%df" % len(v), *v)
    positions = add(f(0.1, 1.0, 0, -0.1, 1.0, 0, 0, 1.5, 0), None, 3, FLOAT, "VEC3",
                    {"min": [-0.1, 1.0, 0], "max": [0.1, 1.5, 0]})
    joints = add(bytes([0, 1, 0, 0, 0, 1, 0, 0, 1, 0, 0, 0]), None, 3, UBYTE, "VEC4")
    weights = add(f(0.5, 0.5, 0, 0, 0.5, 0.5, 0, 0, 1, 0, 0, 0), None, 3, FLOAT, "VEC4")
    indices = add(struct.pack("<3H", 0, 1, 2), None, 3, USHORT, "SCALAR")
    ident = lambda ty: f(1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, -ty, 0, 1)
    ibm = add(ident(1.0) + ident(1.3), None, 2, FLOAT, "MAT4")
    times = add(f(*key_times), None, 2, FLOAT, "SCALAR", {"min": [key_times[0]], "max": [key_times[1]]})
    rots = add(f(0, 0, 0, 1, 0.0998, 0, 0, 0.995), None, 2, FLOAT, "VEC4")
    moves = add(f(0, 1.0, 0, 0, 1.0, 0.2), None, 2, FLOAT, "VEC3")
    doc = {
        "asset": {"version": "2.0", "generator": "prep fuzz seeds"},
        "scene": 0,
        "scenes": [{"nodes": [0, 3]}],
        "nodes": [
            {"name": "Hips", "translation": [0, 1.0, 0], "children": [1]},
            {"name": "Spine", "translation": [0, 0.3, 0], "children": [2]},
            {"name": "Spine_end", "translation": [0, 0.2, 0]},
            {"name": "body", "mesh": 0, "skin": 0},
        ],
        "meshes": [{"primitives": [{"attributes": {"POSITION": positions, "JOINTS_0": joints, "WEIGHTS_0": weights},
                                     "indices": indices}]}],
        "skins": [{"name": "rig", "joints": [0, 1], "inverseBindMatrices": ibm, "skeleton": 0}],
        "animations": [{"name": "sway",
                        "samplers": [{"input": times, "output": rots, "interpolation": "LINEAR"},
                                     {"input": times, "output": moves, "interpolation": "LINEAR"}],
                        "channels": [{"sampler": 0, "target": {"node": 1, "path": "rotation"}},
                                     {"sampler": 1, "target": {"node": 0, "path": "translation"}}]}],
        "accessors": accessors,
        "bufferViews": views,
    }
    return doc, blob


def as_gltf(doc, blob):
    d = copy.deepcopy(doc)
    d["buffers"] = [{"byteLength": len(blob),
                     "uri": "data:application/octet-stream;base64," + base64.b64encode(blob).decode()}]
    return json.dumps(d, separators=(",", ":")).encode()


def as_glb(doc, blob, declared_length=None):
    d = copy.deepcopy(doc)
    d["buffers"] = [{"byteLength": len(blob) if declared_length is None else declared_length}]
    js = json.dumps(d, separators=(",", ":")).encode()
    js += b" " * (-len(js) % 4)
    bin_ = blob + b"\0" * (-len(blob) % 4)
    total = 12 + 8 + len(js) + 8 + len(bin_)
    return (struct.pack("<4sII", b"glTF", 2, total) + struct.pack("<I4s", len(js), b"JSON") + js +
            struct.pack("<I4s", len(bin_), b"BIN\0") + bin_)


def variants(doc):
    """(name, edit) pairs: each edit breaks one thing in a copy of the rig's JSON."""
    def accessor_overflow(d):
        d["accessors"][0]["byteOffset"] = 4294967292
    def count_overflow(d):
        d["accessors"][0]["count"] = 4611686018427387904
    def view_overflow(d):
        d["bufferViews"][0]["byteOffset"] = 18446744073709551600
        d["bufferViews"][0]["byteLength"] = 64
    def stride_odd(d):
        d["bufferViews"][0]["byteStride"] = 13
    def sparse_bad_indices(d):
        d["accessors"][0]["sparse"] = {"count": 2, "indices": {"bufferView": 3, "componentType": USHORT},
                                       "values": {"bufferView": 0}}
        d["accessors"][3]["count"] = 1
    def sparse_huge_count(d):
        d["accessors"][6]["sparse"] = {"count": 2000000000, "indices": {"bufferView": 3, "byteOffset": 4, "componentType": UINT},
                                       "values": {"bufferView": 6, "byteOffset": 30}}
    def deep_tree(d):
        first = len(d["nodes"])
        for i in range(300):
            d["nodes"].append({"name": "n%d" % i, "translation": [0, 0.01, 0]})
            if i:
                d["nodes"][first + i - 1]["children"] = [first + i]
        d["nodes"][2]["children"] = [first]
    def cycle(d):
        d["nodes"][2]["children"] = [0]
    def self_child(d):
        d["nodes"][1]["children"] = [1, 2]
    def two_parents(d):
        d["nodes"][3]["children"] = [2]
    def child_out_of_range(d):
        d["nodes"][1]["children"] = [2, 99]
    def skin_joint_out_of_range(d):
        d["skins"][0]["joints"] = [0, 7]
    def skin_joint_repeated(d):
        d["skins"][0]["joints"] = [0, 0]
    def skin_joints_unrelated(d):
        d["skins"][0]["joints"] = [1, 3]
    def too_few_ibms(d):
        d["accessors"][4]["count"] = 1
    def ibm_wrong_type(d):
        d["accessors"][4]["type"] = "VEC4"
    def vertex_bad_joint(d):
        d["skins"][0]["joints"] = [0]
    def mesh_out_of_range(d):
        d["nodes"][3]["mesh"] = 5
    def anim_bad_node(d):
        d["animations"][0]["channels"][0]["target"]["node"] = 40
    def anim_bad_sampler(d):
        d["animations"][0]["channels"][0]["sampler"] = 9
    def anim_times_backwards(d):
        d["accessors"][5]["min"] = [0.5]
        d["animations"][0]["samplers"][0]["input"] = 6
    def anim_output_short(d):
        d["accessors"][6]["count"] = 1
    def anim_cubic(d):
        d["animations"][0]["samplers"][0]["interpolation"] = "CUBICSPLINE"
    def node_matrix_zero(d):
        d["nodes"][1].pop("translation")
        d["nodes"][1]["matrix"] = [0] * 16
    def node_scale_zero(d):
        d["nodes"][0]["scale"] = [0, 0, 0]
    def negative_index(d):
        d["nodes"][3]["skin"] = -2
    return [(n.__name__, n) for n in (accessor_overflow, count_overflow, view_overflow, stride_odd, sparse_bad_indices,
                                      sparse_huge_count, deep_tree, cycle, self_child, two_parents, child_out_of_range,
                                      skin_joint_out_of_range, skin_joint_repeated, skin_joints_unrelated, too_few_ibms,
                                      ibm_wrong_type, vertex_bad_joint, mesh_out_of_range, anim_bad_node,
                                      anim_bad_sampler, anim_times_backwards, anim_output_short, anim_cubic,
                                      node_matrix_zero, node_scale_zero, negative_index)]


def main():
    os.makedirs(out_dir, exist_ok=True)
    doc, blob = rig()
    files = {"rig.gltf": as_gltf(doc, blob), "rig.glb": as_glb(doc, blob),
             "huge_buffer_length.glb": as_glb(doc, blob, declared_length=4294967295),
             "huge_buffer_uri.gltf": as_gltf(doc, blob).replace(b'"byteLength":%d' % len(blob), b'"byteLength":9007199254740991'),
             "glb_chunk_too_long.glb": as_glb(doc, blob)[:12] + struct.pack("<I", 4000000000) + as_glb(doc, blob)[16:],
             "glb_truncated.glb": as_glb(doc, blob)[:200],
             # Keys 6.8e22 s apart: their spacing, as a frame rate, rounded to 0 frames/s.
             "anim_keys_far_apart.gltf": as_gltf(*rig(key_times=(0.0, 6.8e22)))}
    for name, edit in variants(doc):
        d = copy.deepcopy(doc)
        edit(d)
        files[name + ".gltf"] = as_gltf(d, blob)
    for name, data in files.items():
        with open(os.path.join(out_dir, name), "wb") as f:
            f.write(data)


if __name__ == "__main__":
    main()
