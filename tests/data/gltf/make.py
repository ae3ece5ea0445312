#!/usr/bin/env python3
"""Writes the glTF test files beside this script, as Blender's exporter lays them out (one
interleaved-free buffer of positions, normals, uvs and u16 indices; a node hierarchy; named
materials; a PNG base-colour texture), and broken variants for the error tests.

    python3 tests/data/gltf/make.py

two-cubes.gltf (+ two-cubes.bin, checker.png): one cube mesh (side 2, centred on its
origin) placed by two nodes under a parent moved to z = -3: `CubeA` at the parent's
origin, `CubeB` moved 2 along x and scaled by 0.5. Its faces are `Red` (a dielectric,
roughness 0.5) on the first three and `Checker` (a metal whose base colour is a 4 x 4
checker of red and white texels, times a base colour factor that halves green) on the other
three.
two-cubes.glb: the same, in one binary file.
pbr-maps.gltf (+ pbr-maps.bin and four PNGs): two unit quads in the plane z = 0 facing +z,
`u` along +x and glTF's `v` down along -y, under one material with every map snell reads:
`Plain` at x = -2 (no tangents: MikkTSpace's are +x) and `Tangent` at x = +2 (a TANGENT
attribute of +y, w = 1, which a reader must use). The material `Maps`: base colour
halves.png (left half red, right half white) through KHR_texture_transform offset
[0.5, 0]; metallic-roughness mr.png (green 128, blue 0: roughness 0.5 x the factor 0.8);
normal map tilt.png (one texel tilted 45 degrees toward +x of the map); emissive
glow.png (one texel of 51, 102, 204) times the factor [1, 1, 0.5] and
KHR_materials_emissive_strength 4.
cutout.gltf (+ cutout.bin, leaf.png): alpha modes. The unit quad of pbr-maps.gltf placed
three times: `Leaf` at the origin (alphaMode MASK, cutoff 0.5, base colour leaf.png:
left half alpha 0, right half alpha 255), `Veil` at x = 3 (BLEND, alpha factor 0.25, no
image) and `Wall` 1 behind both, scaled by 8 (opaque).
lit.gltf (+ cutout.bin): the quad with cameras and KHR_lights_punctual lights: camera
`Front` at (0, 0, 5) looking down -z (yfov 0.5), camera `Side` at (5, 0, 0) turned 90
degrees about y (looking down -x; orthographic, ymag 2); a point light `Bulb` at
(0, 2, 3) of 683 cd, red; a spot light `Spot` at (0, 0, 4) (inner 0.2, outer 0.4 rad, 1366 cd);
a directional light `Sun` turned -90 degrees about x (shining down -y) of 1366 lux.
vertex-colors.gltf (+ vertex-colors.bin): the quad with COLOR_0 (VEC4 of normalized
unsigned shorts, as Blender exports colour attributes): red, green, blue and white at the
corners (-x -y, +x -y, +x +y, -x +y), under a white dielectric.
metallic-map.gltf (+ pbr-maps.bin, metal-strip.png): the quad stretched to 6 x 2 (x from
-3 to 3), under `ThreeMetals`: base colour factor pure red, roughness factor 0.5, metallic
factor 1 times metal-strip.png, whose six texels' blue runs 0, 0, 128, 128, 255, 255 along
u (green 255): a dielectric third, a half-metal third and a metal third.
unread.gltf (+ cutout.bin): what snell does not read, each on the quad: node `Body` shows
mesh `Skinned` under skin `Armature` (its joint the node `Joint`, which the animation `Wave`
turns; no JOINTS_0 or WEIGHTS_0, which snell would not read either); node `Face` shows mesh
`Morphed`, one morph target (the normals as displacements) at weight 0.5, and carries
EXT_mesh_gpu_instancing (the positions as translations); node `Panels` shows mesh `Panels`,
two primitives under `OldSchool` (KHR_materials_pbrSpecularGlossiness only) and `Frost`
(KHR_materials_transmission 0.3 and KHR_materials_volume). `Skinned` is under `CarPaint`
(metal, KHR_materials_clearcoat), `Morphed` under `Velvet` (KHR_materials_sheen and
KHR_materials_specular); the material `Unused`, which no primitive names, has
KHR_materials_anisotropy.
no-bounds.gltf (+ two-cubes.bin): two-cubes.gltf with no `min` or `max` on its POSITION
accessor (glTF asks for them; viewers read such files).
The broken files (each with the same two-cubes.bin unless said):
  bad-accessor.gltf   the POSITION accessor claims more vertices than its view holds
  bad-index.gltf      an index points past the vertices (its own bad-index.bin)
  bad-position.gltf   a primitive's POSITION names an accessor that does not exist
  bad-uv-type.gltf    a primitive's TEXCOORD_0 names the VEC3 positions
  bad-uv1-type.gltf   both primitives' TEXCOORD_1 name the VEC3 positions; only the second's
                      material (Checker, its base colour now on texCoord 1) reads it, so
                      only the second is at fault
  missing-buffer.gltf the buffer's file does not exist
  needs-draco.gltf    requires KHR_draco_mesh_compression
  not-json.gltf       not JSON at all
  no-elements.gltf    the TEXCOORD_0 accessor has a count of 0 (glTF asks for 1 or more; the
                      gltf crate's readers underflow on it)
  camera-type.gltf    lit.gltf with a camera of type orthographic that holds only a
                      perspective projection (the gltf crate's reader unwraps the one the
                      type names; uses cutout.bin)
  short-header.glb    a GLB whose header gives a length shorter than the header
"""
import json
import os
import struct
import zlib

HERE = os.path.dirname(os.path.abspath(__file__))


def cube():
    """24 vertices (4 a face), normals, uvs (v = 0 at the top, glTF's), 36 indices."""
    faces = [
        ((1, 0, 0), (0, 0, -1), (0, 1, 0)),
        ((-1, 0, 0), (0, 0, 1), (0, 1, 0)),
        ((0, 1, 0), (1, 0, 0), (0, 0, -1)),
        ((0, -1, 0), (1, 0, 0), (0, 0, 1)),
        ((0, 0, 1), (1, 0, 0), (0, 1, 0)),
        ((0, 0, -1), (-1, 0, 0), (0, 1, 0)),
    ]
    pos, nrm, uv, idx = [], [], [], []
    for n, u, v in faces:
        base = len(pos)
        for su, sv in ((-1, -1), (1, -1), (1, 1), (-1, 1)):
            pos.append(tuple(n[k] + su * u[k] + sv * v[k] for k in range(3)))
            nrm.append(n)
            uv.append(((su + 1) / 2, (1 - sv) / 2))
        idx += [base, base + 1, base + 2, base, base + 2, base + 3]
    return pos, nrm, uv, idx


def png_rgba(w, h, rgba):
    raw = b''.join(b'\x00' + bytes(c for px in rgba[y * w:(y + 1) * w] for c in px) for y in range(h))
    chunk = lambda t, d: struct.pack('>I', len(d)) + t + d + struct.pack('>I', zlib.crc32(t + d))
    return (b'\x89PNG\r\n\x1a\n' + chunk(b'IHDR', struct.pack('>IIBBBBB', w, h, 8, 6, 0, 0, 0))
            + chunk(b'IDAT', zlib.compress(raw)) + chunk(b'IEND', b''))


def png(w, h, rgb):
    raw = b''.join(b'\x00' + bytes(c for px in rgb[y * w:(y + 1) * w] for c in px) for y in range(h))
    chunk = lambda t, d: struct.pack('>I', len(d)) + t + d + struct.pack('>I', zlib.crc32(t + d))
    return (b'\x89PNG\r\n\x1a\n' + chunk(b'IHDR', struct.pack('>IIBBBBB', w, h, 8, 2, 0, 0, 0))
            + chunk(b'IDAT', zlib.compress(raw)) + chunk(b'IEND', b''))


def build(bad_index=False):
    pos, nrm, uv, idx = cube()
    if bad_index:
        idx[5] = 99
    blobs = [
        b''.join(struct.pack('<3f', *p) for p in pos),
        b''.join(struct.pack('<3f', *n) for n in nrm),
        b''.join(struct.pack('<2f', *t) for t in uv),
        b''.join(struct.pack('<H', i) for i in idx[:18]),
        b''.join(struct.pack('<H', i) for i in idx[18:]),
    ]
    views, data = [], b''
    for k, b in enumerate(blobs):
        views.append({'buffer': 0, 'byteOffset': len(data), 'byteLength': len(b),
                      'target': 34963 if k >= 3 else 34962})
        data += b + b'\x00' * (-len(b) % 4)
    accessors = [
        {'bufferView': 0, 'componentType': 5126, 'count': 24, 'type': 'VEC3',
         'min': [-1, -1, -1], 'max': [1, 1, 1]},
        {'bufferView': 1, 'componentType': 5126, 'count': 24, 'type': 'VEC3'},
        {'bufferView': 2, 'componentType': 5126, 'count': 24, 'type': 'VEC2'},
        {'bufferView': 3, 'componentType': 5123, 'count': 18, 'type': 'SCALAR'},
        {'bufferView': 4, 'componentType': 5123, 'count': 18, 'type': 'SCALAR'},
    ]
    attrs = {'POSITION': 0, 'NORMAL': 1, 'TEXCOORD_0': 2}
    doc = {
        'asset': {'generator': 'Khronos glTF Blender I/O v4.2.70', 'version': '2.0'},
        'scene': 0,
        'scenes': [{'name': 'Scene', 'nodes': [0]}],
        'nodes': [
            {'name': 'Parent', 'translation': [0, 0, -3], 'children': [1, 2]},
            {'name': 'CubeA', 'mesh': 0},
            {'name': 'CubeB', 'mesh': 0, 'translation': [2, 0, 0], 'scale': [0.5, 0.5, 0.5]},
        ],
        'meshes': [{'name': 'Cube', 'primitives': [
            {'attributes': attrs, 'indices': 3, 'material': 0},
            {'attributes': attrs, 'indices': 4, 'material': 1},
        ]}],
        'materials': [
            {'name': 'Red', 'pbrMetallicRoughness': {
                'baseColorFactor': [0.8, 0.05, 0.05, 1], 'metallicFactor': 0, 'roughnessFactor': 0.5}},
            {'name': 'Checker', 'pbrMetallicRoughness': {
                'baseColorTexture': {'index': 0}, 'baseColorFactor': [1, 0.5, 1, 1],
                'metallicFactor': 1, 'roughnessFactor': 0.3}},
        ],
        'textures': [{'sampler': 0, 'source': 0}],
        'samplers': [{'magFilter': 9729, 'minFilter': 9987}],
        'images': [{'name': 'checker', 'uri': 'checker.png', 'mimeType': 'image/png'}],
        'accessors': accessors,
        'bufferViews': views,
        'buffers': [{'byteLength': len(data), 'uri': 'two-cubes.bin'}],
    }
    return doc, data


def pbr_maps():
    """The quads of pbr-maps.gltf and their buffer."""
    pos = [(-0.5, -0.5, 0), (0.5, -0.5, 0), (0.5, 0.5, 0), (-0.5, 0.5, 0)]
    nrm = [(0, 0, 1)] * 4
    uv = [(0, 1), (1, 1), (1, 0), (0, 0)]
    tan = [(0, 1, 0, 1)] * 4
    idx = [0, 1, 2, 0, 2, 3]
    blobs = [
        b''.join(struct.pack('<3f', *p) for p in pos),
        b''.join(struct.pack('<3f', *n) for n in nrm),
        b''.join(struct.pack('<2f', *t) for t in uv),
        b''.join(struct.pack('<4f', *t) for t in tan),
        b''.join(struct.pack('<H', i) for i in idx),
    ]
    views, data = [], b''
    for k, b in enumerate(blobs):
        views.append({'buffer': 0, 'byteOffset': len(data), 'byteLength': len(b)})
        data += b + b'\x00' * (-len(b) % 4)
    accessors = [
        {'bufferView': 0, 'componentType': 5126, 'count': 4, 'type': 'VEC3',
         'min': [-0.5, -0.5, 0], 'max': [0.5, 0.5, 0]},
        {'bufferView': 1, 'componentType': 5126, 'count': 4, 'type': 'VEC3'},
        {'bufferView': 2, 'componentType': 5126, 'count': 4, 'type': 'VEC2'},
        {'bufferView': 3, 'componentType': 5126, 'count': 4, 'type': 'VEC4'},
        {'bufferView': 4, 'componentType': 5123, 'count': 6, 'type': 'SCALAR'},
    ]
    plain = {'POSITION': 0, 'NORMAL': 1, 'TEXCOORD_0': 2}
    doc = {
        'asset': {'generator': 'Khronos glTF Blender I/O v4.2.70', 'version': '2.0'},
        'extensionsUsed': ['KHR_texture_transform', 'KHR_materials_emissive_strength'],
        'scene': 0,
        'scenes': [{'name': 'Scene', 'nodes': [0, 1]}],
        'nodes': [
            {'name': 'Plain', 'mesh': 0, 'translation': [-2, 0, 0]},
            {'name': 'Tangent', 'mesh': 1, 'translation': [2, 0, 0]},
        ],
        'meshes': [
            {'name': 'Plain', 'primitives': [{'attributes': plain, 'indices': 4, 'material': 0}]},
            {'name': 'Tangent', 'primitives': [
                {'attributes': dict(plain, TANGENT=3), 'indices': 4, 'material': 0}]},
        ],
        'materials': [{
            'name': 'Maps',
            'pbrMetallicRoughness': {
                'baseColorTexture': {'index': 0, 'extensions': {
                    'KHR_texture_transform': {'offset': [0.5, 0]}}},
                'metallicRoughnessTexture': {'index': 1},
                'metallicFactor': 1, 'roughnessFactor': 0.8},
            'normalTexture': {'index': 2, 'scale': 1},
            'emissiveTexture': {'index': 3},
            'emissiveFactor': [1, 1, 0.5],
            'extensions': {'KHR_materials_emissive_strength': {'emissiveStrength': 4}},
        }],
        'textures': [{'sampler': 0, 'source': i} for i in range(4)],
        'samplers': [{'magFilter': 9728, 'minFilter': 9728}],
        'images': [{'uri': n, 'mimeType': 'image/png'}
                   for n in ('halves.png', 'mr.png', 'tilt.png', 'glow.png')],
        'accessors': accessors,
        'bufferViews': views,
        'buffers': [{'byteLength': len(data), 'uri': 'pbr-maps.bin'}],
    }
    return doc, data


def cutout():
    """cutout.gltf: the pbr-maps quad under three materials."""
    doc, data = pbr_maps()
    plain = {'POSITION': 0, 'NORMAL': 1, 'TEXCOORD_0': 2}
    doc['extensionsUsed'] = []
    doc['scenes'] = [{'name': 'Scene', 'nodes': [0, 1, 2]}]
    doc['nodes'] = [
        {'name': 'Leaf', 'mesh': 0},
        {'name': 'Veil', 'mesh': 1, 'translation': [3, 0, 0]},
        {'name': 'Wall', 'mesh': 2, 'translation': [0, 0, -1], 'scale': [8, 8, 8]},
    ]
    doc['meshes'] = [
        {'name': name, 'primitives': [{'attributes': plain, 'indices': 4, 'material': k}]}
        for k, name in enumerate(['Leaf', 'Veil', 'Wall'])
    ]
    doc['materials'] = [
        {'name': 'Leaf', 'alphaMode': 'MASK', 'alphaCutoff': 0.5, 'doubleSided': True,
         'pbrMetallicRoughness': {'baseColorTexture': {'index': 0}, 'metallicFactor': 0}},
        {'name': 'Veil', 'alphaMode': 'BLEND',
         'pbrMetallicRoughness': {'baseColorFactor': [1, 1, 1, 0.25], 'metallicFactor': 0}},
        {'name': 'Wall', 'pbrMetallicRoughness': {'metallicFactor': 0}},
    ]
    doc['textures'] = [{'sampler': 0, 'source': 0}]
    doc['images'] = [{'uri': 'leaf.png', 'mimeType': 'image/png'}]
    doc['buffers'][0]['uri'] = 'cutout.bin'
    return doc, data


def lit():
    """lit.gltf: the quad, two cameras and three lights."""
    doc, data = cutout()
    q = 0.5 ** 0.5
    doc['extensionsUsed'] = ['KHR_lights_punctual']
    doc['scenes'] = [{'name': 'Scene', 'nodes': [0, 1, 2, 3, 4, 5]}]
    doc['nodes'] = [
        {'name': 'Quad', 'mesh': 0},
        {'name': 'Front', 'camera': 0, 'translation': [0, 0, 5]},
        {'name': 'SideNode', 'camera': 1, 'translation': [5, 0, 0], 'rotation': [0, q, 0, q]},
        {'name': 'BulbNode', 'translation': [0, 2, 3],
         'extensions': {'KHR_lights_punctual': {'light': 0}}},
        {'name': 'SpotNode', 'translation': [0, 0, 4],
         'extensions': {'KHR_lights_punctual': {'light': 1}}},
        {'name': 'SunNode', 'rotation': [-q, 0, 0, q],
         'extensions': {'KHR_lights_punctual': {'light': 2}}},
    ]
    doc['cameras'] = [
        {'name': 'Front', 'type': 'perspective',
         'perspective': {'yfov': 0.5, 'znear': 0.1, 'aspectRatio': 1.5}},
        {'name': 'Side', 'type': 'orthographic',
         'orthographic': {'xmag': 3, 'ymag': 2, 'znear': 0.1, 'zfar': 100}},
    ]
    doc['extensions'] = {'KHR_lights_punctual': {'lights': [
        {'name': 'Bulb', 'type': 'point', 'color': [1, 0, 0], 'intensity': 683},
        {'name': 'Spot', 'type': 'spot', 'intensity': 1366,
         'spot': {'innerConeAngle': 0.2, 'outerConeAngle': 0.4}},
        {'name': 'Sun', 'type': 'directional', 'intensity': 1366},
    ]}}
    doc['meshes'] = doc['meshes'][2:]
    doc['materials'] = doc['materials'][2:]
    doc['meshes'][0]['primitives'][0]['material'] = 0
    del doc['textures'], doc['images']
    return doc, data


def vertex_colors():
    """vertex-colors.gltf: the pbr-maps quad with COLOR_0 as Blender exports colour
    attributes (VEC4 of normalized unsigned shorts): red, green, blue and white at its
    corners (-x -y, +x -y, +x +y, -x +y), under a white dielectric."""
    doc, data = pbr_maps()
    colors = [(65535, 0, 0, 65535), (0, 65535, 0, 65535), (0, 0, 65535, 65535),
              (65535, 65535, 65535, 65535)]
    blob = b''.join(struct.pack('<4H', *c) for c in colors)
    doc['bufferViews'].append({'buffer': 0, 'byteOffset': len(data), 'byteLength': len(blob)})
    data += blob
    doc['accessors'].append({'bufferView': len(doc['bufferViews']) - 1, 'componentType': 5123,
                             'normalized': True, 'count': 4, 'type': 'VEC4'})
    doc['extensionsUsed'] = []
    doc['scenes'] = [{'name': 'Scene', 'nodes': [0]}]
    doc['nodes'] = [{'name': 'Painted', 'mesh': 0}]
    doc['meshes'] = [{'name': 'Painted', 'primitives': [{
        'attributes': {'POSITION': 0, 'NORMAL': 1, 'TEXCOORD_0': 2,
                       'COLOR_0': len(doc['accessors']) - 1},
        'indices': 4, 'material': 0}]}]
    doc['materials'] = [{'name': 'White', 'pbrMetallicRoughness': {'metallicFactor': 0}}]
    for key in ('textures', 'samplers', 'images'):
        doc.pop(key)
    doc['buffers'] = [{'byteLength': len(data), 'uri': 'vertex-colors.bin'}]
    return doc, data


def metallic_map():
    """metallic-map.gltf: the pbr-maps quad, stretched to 6 x 2, whose metallic map runs
    from dielectric through half metal to metal along u."""
    doc, _ = pbr_maps()
    doc['extensionsUsed'] = []
    doc['scenes'] = [{'name': 'Scene', 'nodes': [0]}]
    doc['nodes'] = [{'name': 'Strip', 'mesh': 0, 'scale': [6, 2, 1]}]
    doc['meshes'] = doc['meshes'][:1]
    doc['meshes'][0]['name'] = 'Strip'
    doc['materials'] = [{'name': 'ThreeMetals', 'pbrMetallicRoughness': {
        'baseColorFactor': [1, 0, 0, 1], 'metallicFactor': 1, 'roughnessFactor': 0.5,
        'metallicRoughnessTexture': {'index': 0}}}]
    doc['textures'] = [{'source': 0}]
    doc.pop('samplers')
    doc['images'] = [{'uri': 'metal-strip.png', 'mimeType': 'image/png'}]
    return doc


def unread():
    """unread.gltf: the quad under everything snell does not read (see the top)."""
    doc, _ = cutout()
    plain = {'POSITION': 0, 'NORMAL': 1, 'TEXCOORD_0': 2}
    doc['extensionsUsed'] = [
        'KHR_materials_clearcoat', 'KHR_materials_sheen', 'KHR_materials_specular',
        'KHR_materials_pbrSpecularGlossiness', 'KHR_materials_transmission',
        'KHR_materials_volume', 'KHR_materials_anisotropy', 'KHR_materials_emissive_strength',
        'EXT_mesh_gpu_instancing']
    doc['scenes'] = [{'name': 'Scene', 'nodes': [0, 1, 2, 3]}]
    doc['nodes'] = [
        {'name': 'Body', 'mesh': 0, 'skin': 0},
        {'name': 'Joint', 'translation': [0, 1, 0]},
        {'name': 'Face', 'mesh': 1, 'translation': [2, 0, 0],
         'extensions': {'EXT_mesh_gpu_instancing': {'attributes': {'TRANSLATION': 0}}}},
        {'name': 'Panels', 'mesh': 2, 'translation': [-2, 0, 0]},
    ]
    doc['skins'] = [{'name': 'Armature', 'joints': [1]}]
    doc['meshes'] = [
        {'name': 'Skinned', 'primitives': [{'attributes': plain, 'indices': 4, 'material': 0}]},
        {'name': 'Morphed', 'weights': [0.5], 'primitives': [
            {'attributes': plain, 'indices': 4, 'material': 1, 'targets': [{'POSITION': 1}]}]},
        {'name': 'Panels', 'primitives': [
            {'attributes': plain, 'indices': 4, 'material': 2},
            {'attributes': plain, 'indices': 4, 'material': 3}]},
    ]
    doc['materials'] = [
        {'name': 'CarPaint', 'pbrMetallicRoughness': {'metallicFactor': 1},
         'extensions': {'KHR_materials_clearcoat': {
             'clearcoatFactor': 1, 'clearcoatRoughnessFactor': 0.1}}},
        {'name': 'Velvet', 'pbrMetallicRoughness': {'metallicFactor': 0},
         'extensions': {'KHR_materials_sheen': {'sheenColorFactor': [1, 0, 0]},
                        'KHR_materials_specular': {'specularFactor': 0.5}}},
        {'name': 'OldSchool', 'extensions': {'KHR_materials_pbrSpecularGlossiness': {
            'diffuseFactor': [0, 1, 0, 1], 'glossinessFactor': 0.5}}},
        {'name': 'Frost', 'pbrMetallicRoughness': {'metallicFactor': 0},
         'extensions': {'KHR_materials_transmission': {'transmissionFactor': 0.3},
                        'KHR_materials_volume': {'thicknessFactor': 0.1,
                                                 'attenuationColor': [1, 0.5, 0.5]}}},
        {'name': 'Unused', 'extensions': {'KHR_materials_anisotropy': {'anisotropyStrength': 1}}},
    ]
    # The animation's times: the uvs' first four floats (0, 1, 1, 1) as scalars; its
    # rotations: the tangents.
    doc['accessors'].append({'bufferView': 2, 'componentType': 5126, 'count': 4,
                             'type': 'SCALAR', 'min': [0], 'max': [1]})
    doc['animations'] = [{'name': 'Wave', 'samplers': [
        {'input': len(doc['accessors']) - 1, 'output': 3, 'interpolation': 'STEP'}],
        'channels': [{'sampler': 0, 'target': {'node': 1, 'path': 'rotation'}}]}]
    for key in ('textures', 'samplers', 'images'):
        doc.pop(key)
    return doc


def as_glb(doc, data):
    """The document and its buffer (its images read from beside this script and moved
    into the buffer) as one GLB file's bytes."""
    doc = json.loads(json.dumps(doc))
    blob = data
    for im in doc.get('images', []):
        with open(os.path.join(HERE, im.pop('uri')), 'rb') as f:
            png_bytes = f.read()
        doc['bufferViews'].append({'buffer': 0, 'byteOffset': len(blob), 'byteLength': len(png_bytes)})
        im['bufferView'] = len(doc['bufferViews']) - 1
        blob += png_bytes + b'\x00' * (-len(png_bytes) % 4)
    doc['buffers'] = [{'byteLength': len(blob)}]
    js = json.dumps(doc).encode()
    js += b' ' * (-len(js) % 4)
    body = struct.pack('<I4s', len(js), b'JSON') + js + struct.pack('<I4s', len(blob), b'BIN\x00') + blob
    return struct.pack('<4sII', b'glTF', 2, 12 + len(body)) + body


def write(name, doc):
    with open(os.path.join(HERE, name), 'w') as f:
        json.dump(doc, f, indent=1)
        f.write('\n')


def main():
    red, white = (200, 20, 20), (240, 240, 240)
    with open(os.path.join(HERE, 'checker.png'), 'wb') as f:
        f.write(png(4, 4, [red if (x + y) % 2 == 0 else white for y in range(4) for x in range(4)]))
    doc, data = build()
    with open(os.path.join(HERE, 'two-cubes.bin'), 'wb') as f:
        f.write(data)
    write('two-cubes.gltf', doc)

    # The GLB: the JSON chunk (the image now in a buffer view too) and the BIN chunk.
    with open(os.path.join(HERE, 'checker.png'), 'rb') as f:
        image = f.read()
    glb = json.loads(json.dumps(doc))
    glb['bufferViews'].append({'buffer': 0, 'byteOffset': len(data), 'byteLength': len(image)})
    glb['images'] = [{'name': 'checker', 'bufferView': 5, 'mimeType': 'image/png'}]
    blob = data + image + b'\x00' * (-len(image) % 4)
    glb['buffers'] = [{'byteLength': len(blob)}]
    js = json.dumps(glb).encode()
    js += b' ' * (-len(js) % 4)
    body = struct.pack('<I4s', len(js), b'JSON') + js + struct.pack('<I4s', len(blob), b'BIN\x00') + blob
    with open(os.path.join(HERE, 'two-cubes.glb'), 'wb') as f:
        f.write(struct.pack('<4sII', b'glTF', 2, 12 + len(body)) + body)

    maps, maps_data = pbr_maps()
    with open(os.path.join(HERE, 'pbr-maps.bin'), 'wb') as f:
        f.write(maps_data)
    write('pbr-maps.gltf', maps)
    cut, cut_data = cutout()
    with open(os.path.join(HERE, 'cutout.bin'), 'wb') as f:
        f.write(cut_data)
    write('cutout.gltf', cut)
    write('lit.gltf', lit()[0])
    painted, painted_data = vertex_colors()
    with open(os.path.join(HERE, 'vertex-colors.bin'), 'wb') as f:
        f.write(painted_data)
    write('vertex-colors.gltf', painted)
    with open(os.path.join(HERE, 'metal-strip.png'), 'wb') as f:
        f.write(png(6, 1, [(0, 255, b) for b in (0, 0, 128, 128, 255, 255)]))
    write('metallic-map.gltf', metallic_map())
    write('unread.gltf', unread())
    bounds = json.loads(json.dumps(doc))
    del bounds['accessors'][0]['min'], bounds['accessors'][0]['max']
    write('no-bounds.gltf', bounds)
    odd = lit()[0]
    odd['cameras'][0]['type'] = 'orthographic'
    write('camera-type.gltf', odd)
    with open(os.path.join(HERE, 'leaf.png'), 'wb') as f:
        f.write(png_rgba(2, 1, [(40, 160, 40, 0), (40, 160, 40, 255)]))
    for name, w, h, px in [
        ('halves.png', 2, 1, [(255, 0, 0), (255, 255, 255)]),
        ('mr.png', 1, 1, [(0, 128, 0)]),
        ('tilt.png', 1, 1, [(218, 128, 218)]),
        ('glow.png', 1, 1, [(51, 102, 204)]),
    ]:
        with open(os.path.join(HERE, name), 'wb') as f:
            f.write(png(w, h, px))

    # Fuzz seeds: each of these as one self-contained GLB.
    seeds = os.path.join(HERE, '..', '..', '..', 'fuzz', 'seeds', 'gltf')
    for name, (d, b) in [('pbr-maps.glb', (maps, maps_data)), ('cutout.glb', (cut, cut_data)),
                         ('lit.glb', (lit()[0], cut_data)),
                         ('vertex-colors.glb', vertex_colors())]:
        with open(os.path.join(seeds, name), 'wb') as f:
            f.write(as_glb(d, b))

    bad = json.loads(json.dumps(doc))
    bad['accessors'][0]['count'] = 2400
    write('bad-accessor.gltf', bad)
    bad_doc, bad_data = build(bad_index=True)
    bad_doc['buffers'][0]['uri'] = 'bad-index.bin'
    with open(os.path.join(HERE, 'bad-index.bin'), 'wb') as f:
        f.write(bad_data)
    write('bad-index.gltf', bad_doc)
    position = json.loads(json.dumps(doc))
    position['meshes'][0]['primitives'][0]['attributes']['POSITION'] = 7
    write('bad-position.gltf', position)
    uv = json.loads(json.dumps(doc))
    uv['meshes'][0]['primitives'][1]['attributes']['TEXCOORD_0'] = 0
    write('bad-uv-type.gltf', uv)
    uv1 = json.loads(json.dumps(doc))
    for prim in uv1['meshes'][0]['primitives']:
        prim['attributes']['TEXCOORD_1'] = 0
    uv1['materials'][1]['pbrMetallicRoughness']['baseColorTexture']['texCoord'] = 1
    write('bad-uv1-type.gltf', uv1)
    empty = json.loads(json.dumps(doc))
    empty['accessors'][2]['count'] = 0
    write('no-elements.gltf', empty)
    missing = json.loads(json.dumps(doc))
    missing['buffers'][0]['uri'] = 'gone.bin'
    write('missing-buffer.gltf', missing)
    draco = json.loads(json.dumps(doc))
    draco['extensionsUsed'] = draco['extensionsRequired'] = ['KHR_draco_mesh_compression']
    write('needs-draco.gltf', draco)
    with open(os.path.join(HERE, 'short-header.glb'), 'wb') as f:
        f.write(b'glTF' + struct.pack('<II', 2, 4) + bytes(16))
    with open(os.path.join(HERE, 'not-json.gltf'), 'w') as f:
        f.write('solid cube\n  facet normal 0 0 1\n')


if __name__ == '__main__':
    main()
