// Stage 4: image textures, a reflectance that varies over a surface. A hit carries texture
// coordinates (u, v) (common/hit.h: a mesh's interpolated, a sphere's latitude and longitude); the
// texture maps them to a colour. Conventions (common/scene.h): u runs right and v runs UP, so
// (0, 0) is the image's bottom-left corner and (1, 1) its top-right; texel (i, j) (column i, row j
// from the top) covers u in [i / W, (i + 1) / W] and v in [1 - (j + 1) / H, 1 - j / H], its value
// taken at its centre.
//
// Outside [0, 1]^2 the wrap mode decides: `repeat` tiles the image (u and u + 1 look alike), `clamp`
// extends its edge texels. `nearest` returns the texel that covers (u, v); `bilinear` blends the
// four texels whose centres surround it, weighted by the distances to them (x = u W - 1/2 in texel
// centres' coordinates, fx its fraction):
//     c = lerp(lerp(c00, c10, fx), lerp(c01, c11, fx), fy),   lerp(a, b, f) = a + f (b - a),
// exact where the four are equal (b - a = 0), so a one-colour texture returns its colour bit for bit.
#pragma once

#include "common/scene.h"

namespace rt {

// Task stage4.texture.wrap. Texel index i (any integer) brought into [0, n) by the wrap mode:
// repeat is i mod n, never negative; clamp is the nearest of 0 and n - 1.
int wrap_texel(int i, int n, TextureWrap wrap);

// Task stage4.texture.lookup. The texture's value at (u, v), by its filter and wrap mode.
Color texture_lookup(const ImageTexture& texture, Vec2 uv);

}  // namespace rt
