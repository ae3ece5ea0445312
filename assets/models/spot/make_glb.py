"""Writes spot-scene.glb: Keenan Crane's Spot (spot_triangulated.obj, spot_texture.png) on a
tiled ground, with a camera, laid out as Blender's glTF exporter writes a scene: one binary
buffer, the images inside it, smooth normals, no tangents (a reader computes MikkTSpace's).

- `Spot`: the cow, standing on y = 0, base colour spot_texture.png, roughness 0.55.
- `Ground`: a 400 x 400 square at y = 0, grey-brown, with ../../maps/tiles-normal.png as its
  normal map repeated 200 x 200 times through KHR_texture_transform.
- `Camera`: a perspective camera (yfov 0.6) looking at the cow from her front right.

    python3 assets/models/spot/make_glb.py
"""

import json
import math
import os
import struct

HERE = os.path.dirname(os.path.abspath(__file__))


def read_obj(path):
    v, vt, faces = [], [], []
    for line in open(path):
        p = line.split()
        if not p:
            continue
        if p[0] == 'v':
            v.append(tuple(map(float, p[1:4])))
        elif p[0] == 'vt':
            vt.append(tuple(map(float, p[1:3])))
        elif p[0] == 'f':
            faces.append([tuple(int(x) - 1 for x in c.split('/')[:2]) for c in p[1:4]])
    return v, vt, faces


def sub(a, b):
    return tuple(x - y for x, y in zip(a, b))


def cross(a, b):
    return (a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0])


def norm(a):
    l = math.sqrt(sum(x * x for x in a)) or 1.0
    return tuple(x / l for x in a)


def spot():
    v, vt, faces = read_obj(os.path.join(HERE, 'spot_triangulated.obj'))
    lift = -min(p[1] for p in v)
    v = [(p[0], p[1] + lift, p[2]) for p in v]
    # Area-weighted normals per position.
    acc = [(0.0, 0.0, 0.0)] * len(v)
    for f in faces:
        a, b, c = (v[i] for i, _ in f)
        n = cross(sub(b, a), sub(c, a))
        for i, _ in f:
            acc[i] = tuple(x + y for x, y in zip(acc[i], n))
    # One glTF vertex per (position, uv) pair; glTF's v runs down the image (OBJ's up).
    index, pos, nrm, uv, idx = {}, [], [], [], []
    for f in faces:
        for key in f:
            if key not in index:
                index[key] = len(pos)
                pos.append(v[key[0]])
                nrm.append(norm(acc[key[0]]))
                t = vt[key[1]]
                uv.append((t[0], 1.0 - t[1]))
            idx.append(index[key])
    return pos, nrm, uv, idx


def ground():
    s = 200.0
    pos = [(-s, 0, s), (s, 0, s), (s, 0, -s), (-s, 0, -s)]
    return pos, [(0, 1, 0)] * 4, [(0, 1), (1, 1), (1, 0), (0, 0)], [0, 1, 2, 0, 2, 3]


def look_rotation(eye, target):
    """The quaternion turning -z toward target and +y up, as a glTF node's rotation."""
    back = norm(sub(eye, target))
    right = norm(cross((0, 1, 0), back))
    up = cross(back, right)
    r = [[right[i], up[i], back[i]] for i in range(3)]  # rows of the matrix
    t = r[0][0] + r[1][1] + r[2][2]
    if t > 0:
        s = math.sqrt(t + 1.0) * 2
        q = [(r[2][1] - r[1][2]) / s, (r[0][2] - r[2][0]) / s, (r[1][0] - r[0][1]) / s, s / 4]
    elif r[0][0] > r[1][1] and r[0][0] > r[2][2]:
        s = math.sqrt(1.0 + r[0][0] - r[1][1] - r[2][2]) * 2
        q = [s / 4, (r[0][1] + r[1][0]) / s, (r[0][2] + r[2][0]) / s, (r[2][1] - r[1][2]) / s]
    elif r[1][1] > r[2][2]:
        s = math.sqrt(1.0 + r[1][1] - r[0][0] - r[2][2]) * 2
        q = [(r[0][1] + r[1][0]) / s, s / 4, (r[1][2] + r[2][1]) / s, (r[0][2] - r[2][0]) / s]
    else:
        s = math.sqrt(1.0 + r[2][2] - r[0][0] - r[1][1]) * 2
        q = [(r[0][2] + r[2][0]) / s, (r[1][2] + r[2][1]) / s, s / 4, (r[1][0] - r[0][1]) / s]
    return q


def main():
    blobs, views, accessors = [], [], []
    data = b''

    def view(blob):
        nonlocal data
        views.append({'buffer': 0, 'byteOffset': len(data), 'byteLength': len(blob)})
        data += blob + b'\x00' * (-len(blob) % 4)
        return len(views) - 1

    def accessor(values, kind, fmt, ctype=5126, bounds=False):
        blob = b''.join(struct.pack('<' + fmt, *(x if isinstance(x, tuple) else (x,))) for x in values)
        a = {'bufferView': view(blob), 'componentType': ctype, 'count': len(values), 'type': kind}
        if bounds:
            a['min'] = [min(p[k] for p in values) for k in range(3)]
            a['max'] = [max(p[k] for p in values) for k in range(3)]
        accessors.append(a)
        return len(accessors) - 1

    meshes = []
    for name, (pos, nrm, uv, idx), material in [('Spot', spot(), 0), ('Ground', ground(), 1)]:
        attrs = {'POSITION': accessor(pos, 'VEC3', '3f', bounds=True),
                 'NORMAL': accessor(nrm, 'VEC3', '3f'),
                 'TEXCOORD_0': accessor(uv, 'VEC2', '2f')}
        indices = accessor(idx, 'SCALAR', 'I', ctype=5125)
        meshes.append({'name': name, 'primitives': [
            {'attributes': attrs, 'indices': indices, 'material': material}]})
    images = []
    for name, path in [('spot_texture', os.path.join(HERE, 'spot_texture.png')),
                       ('tiles-normal', os.path.join(HERE, '..', '..', 'maps', 'tiles-normal.png'))]:
        with open(path, 'rb') as f:
            images.append({'name': name, 'bufferView': view(f.read()), 'mimeType': 'image/png'})
    eye, target = (2.1, 1.35, -3.5), (0.0, 0.75, 0.15)
    doc = {
        'asset': {'generator': 'Khronos glTF Blender I/O v4.2.70', 'version': '2.0'},
        'extensionsUsed': ['KHR_texture_transform'],
        'scene': 0,
        'scenes': [{'name': 'Scene', 'nodes': [0, 1, 2]}],
        'nodes': [
            {'name': 'Spot', 'mesh': 0},
            {'name': 'Ground', 'mesh': 1},
            {'name': 'Camera', 'camera': 0, 'translation': list(eye),
             'rotation': look_rotation(eye, target)},
        ],
        'cameras': [{'name': 'Camera', 'type': 'perspective',
                     'perspective': {'yfov': 0.6, 'aspectRatio': 16 / 9, 'znear': 0.1}}],
        'meshes': meshes,
        'materials': [
            {'name': 'Spot', 'pbrMetallicRoughness': {
                'baseColorTexture': {'index': 0}, 'metallicFactor': 0, 'roughnessFactor': 0.55}},
            {'name': 'Ground', 'pbrMetallicRoughness': {
                'baseColorFactor': [0.45, 0.4, 0.35, 1], 'metallicFactor': 0, 'roughnessFactor': 0.7},
             'normalTexture': {'index': 1, 'extensions': {
                 'KHR_texture_transform': {'scale': [200, 200]}}}},
        ],
        'textures': [{'sampler': 0, 'source': 0}, {'sampler': 0, 'source': 1}],
        'samplers': [{'magFilter': 9729, 'minFilter': 9987}],
        'images': images,
        'accessors': accessors,
        'bufferViews': views,
        'buffers': [{'byteLength': len(data)}],
    }
    js = json.dumps(doc, separators=(',', ':')).encode()
    js += b' ' * (-len(js) % 4)
    body = struct.pack('<I4s', len(js), b'JSON') + js + struct.pack('<I4s', len(data), b'BIN\x00') + data
    with open(os.path.join(HERE, 'spot-scene.glb'), 'wb') as f:
        f.write(struct.pack('<4sII', b'glTF', 2, 12 + len(body)) + body)


if __name__ == '__main__':
    main()
