"""Makes tiles-height.png and tiles-normal.png: a 4 x 4 grid of square tiles with bevelled
edges and a low dome on each, as a height map (16-bit grey, 0 in the grout, 1 on the dome
tops) and the tangent-space normal map of the same surface (8-bit RGB, linear, +x along u,
+y up the image, as glTF and Blender bake them).

The normal map is the surface `z = DEPTH * height(u, v)` over one texture unit, so a bump
map of tiles-height.png with `bump_height = DEPTH` (scene units per unit of value, where one
texture unit spans one scene unit) shows the same relief. Both repeat seamlessly.

    python3 assets/maps/make.py        (numpy and Pillow)
"""

import numpy as np
from PIL import Image

SIZE = 512
TILES = 4
DEPTH = 0.02  # height of a dome top above the grout, in texture units

x = (np.arange(SIZE) + 0.5) / SIZE
u, v = np.meshgrid(x, x)  # v grows down the rows, as in snell
cell = 1.0 / TILES
fu, fv = (u % cell) / cell, (v % cell) / cell  # position inside a tile, 0..1
edge = np.minimum(np.minimum(fu, 1 - fu), np.minimum(fv, 1 - fv))  # to the nearest side
GROUT, BEVEL = 0.03, 0.08
bevel = np.clip((edge - GROUT) / BEVEL, 0.0, 1.0)
bevel = bevel * bevel * (3 - 2 * bevel)  # smooth step
r2 = (fu - 0.5) ** 2 + (fv - 0.5) ** 2
dome = np.clip(1 - r2 / 0.3**2, 0.0, 1.0) ** 2
height = np.where(edge > GROUT, 0.6 * bevel + 0.4 * dome * bevel, 0.0)
height = height / height.max()

# Central differences, wrapping (the map repeats).
step = 1.0 / SIZE
dhdu = (np.roll(height, -1, axis=1) - np.roll(height, 1, axis=1)) / (2 * step) * DEPTH
dhdv = (np.roll(height, -1, axis=0) - np.roll(height, 1, axis=0)) / (2 * step) * DEPTH
# Up the image is -v, so the slope up the image is -dhdv.
n = np.stack([-dhdu, dhdv, np.ones_like(height)], axis=-1)
n /= np.linalg.norm(n, axis=-1, keepdims=True)
rgb = np.clip(np.round((n * 0.5 + 0.5) * 255), 0, 255).astype(np.uint8)
Image.fromarray(rgb, "RGB").save("assets/maps/tiles-normal.png", optimize=True)
Image.fromarray(np.round(height * 65535).astype(np.uint16)).save(
    "assets/maps/tiles-height.png", optimize=True
)
print("depth", DEPTH)
