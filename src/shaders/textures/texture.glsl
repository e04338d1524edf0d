// Texture lookups (scene format "Textures"): exactly Mitsuba's `bitmap`
// (bilinear between texel centres, repeat, no mipmaps; the project's
// reference is src/scene/texture/bitmapLookup.ts, tested against Mitsuba).
// Images live in atlas pages of texture arrays, one per storage format
// (src/render/textures/atlas.ts); the filtering is done here on texelFetch
// results, so an sRGB texel is decoded before it is filtered (the format's
// rule: hardware may filter before decoding) and images need no gutters.
#if HAS_TEXTURES

#if HAS_TEXTURES_SRGB8
uniform highp sampler2DArray uTexturesSrgb8;
#endif
#if HAS_TEXTURES_LINEAR8
uniform highp sampler2DArray uTexturesLinear8;
#endif
#if HAS_TEXTURES_FLOAT
uniform highp sampler2DArray uTexturesFloat;
#endif

TextureRecord loadTexture(int i) { return readTextureRecord(TEXTURES_FIRST + i * TEXTURE_RECORD_TEXELS); }

// A texel of the atlas of `format` (0 srgb8, 1 linear8, 2 float): only the
// scene's formats are compiled in.
vec4 atlasTexel(int format, ivec3 p) {
  vec4 v = vec4(0.0);
#if HAS_TEXTURES_SRGB8
  if (format == 0) v = texelFetch(uTexturesSrgb8, p, 0);
#endif
#if HAS_TEXTURES_LINEAR8
  if (format == 1) v = texelFetch(uTexturesLinear8, p, 0);
#endif
#if HAS_TEXTURES_FLOAT
  if (format == 2) v = texelFetch(uTexturesFloat, p, 0);
#endif
  return v;
}

// The texel index i wrapped into [0, size) (Euclidean modulo: `repeat`).
ivec2 wrapTexel(vec2 i, vec2 size) {
  ivec2 w = ivec2(i - size * floor(i / size));
  return clamp(w, ivec2(0), ivec2(size) - 1);  // float rounding at the edge; non-finite uv
}

// The filtered RGBA of texture r at uv, after its uv transform.
vec4 textureTexels(TextureRecord r, vec2 uv) {
  vec3 h = vec3(uv, 1.0);
  vec2 st = vec2(dot(r.uRow.xyz, h), dot(r.vRow.xyz, h));
  vec2 size = r.size.xy;
  vec2 pos = st * size - 0.5;  // texel centres at (i + 0.5) / size
  // A non-finite position (a uv transform overflowing float32) would give NaN
  // weights: read at -0.5 instead, as the reference does.
  pos = mix(vec2(-0.5), pos, lessThan(abs(pos), vec2(1e38)));
  vec2 cell = floor(pos);
  vec2 w1 = pos - cell;
  vec2 w0 = 1.0 - w1;
  ivec2 i0 = wrapTexel(cell, size);
  ivec2 i1 = wrapTexel(cell + 1.0, size);
  int format = int(r.placement.x);
  int layer = int(r.placement.y);
  ivec2 origin = ivec2(r.placement.zw);
  vec4 v00 = atlasTexel(format, ivec3(origin + i0, layer));
  vec4 v10 = atlasTexel(format, ivec3(origin + ivec2(i1.x, i0.y), layer));
  vec4 v01 = atlasTexel(format, ivec3(origin + ivec2(i0.x, i1.y), layer));
  vec4 v11 = atlasTexel(format, ivec3(origin + i1, layer));
  return w0.y * (w0.x * v00 + w1.x * v10) + w1.y * (w0.x * v01 + w1.x * v11);
}

// A color input's texture: RGB (sRGB-decoded per texel for 8-bit images).
vec3 textureColor(int t, vec2 uv) { return textureTexels(loadTexture(t), uv).rgb; }

// A scalar input's texture: its channel as stored, then its cutoff (if any).
float textureScalar(int t, vec2 uv) {
  TextureRecord r = loadTexture(t);
  vec4 v = textureTexels(r, uv);
  int channel = int(r.size.z);
  // Selects of names only (see pick() in common/math.glsl).
  float zw = channel == 2 ? v.z : v.w;
  float yzw = channel == 1 ? v.y : zw;
  float x = channel == 0 ? v.x : yzw;
  float cutoff = r.size.w;
  float masked = x >= cutoff ? 1.0 : 0.0;
  return cutoff < 0.0 ? x : masked;
}

// A normal map's normal in its tangent frame: normalize((2 rgb - 1) * (s, s, 1)).
vec3 textureNormal(int t, vec2 uv) {
  TextureRecord r = loadTexture(t);
  vec3 n = (2.0 * textureTexels(r, uv).rgb - 1.0) * vec3(r.uRow.w, r.uRow.w, 1.0);
  float len = length(n);
  vec3 unit = n / len;  // a select of names (pick() is not in the texture kernels' chunks)
  return len > 0.0 ? unit : vec3(0.0, 0.0, 1.0);
}

#endif
