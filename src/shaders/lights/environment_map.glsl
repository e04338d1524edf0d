// Environment map: radiance lookup and importance sampling.
//
// Uniforms (set by src/render/environmentTextures.ts):
//   uEnvironmentMap          RGB32F, W x H: texel (x, y) = column x of row y,
//                            row 0 at the zenith (EnvironmentImage order).
//   uEnvironmentMarginal     RGBA32F, R x 1 (R = max(H - 1, 1) rows of cells):
//                            alias table over the rows of cells.
//   uEnvironmentConditional  RGBA32F, W x R: one alias table per row of cells.
//                            Alias texels are (keep probability, alias index,
//                            probability of this entry, probability of the
//                            alias entry); see src/scene/envmap/distribution.ts.
//   uEnvironmentRotation     vec2 (cos, sin) of the map's rotation about +y.
//   uEnvironmentIntensity    float, multiplies the radiance.
//
// Mapping (scene format = Mitsuba 3's envmap): a world direction d is turned
// by -rotation about +y into the map's frame, then u = 0.5 + atan2(-x, z) /
// (2 pi), v = acos(y) / pi. Lookup is bilinear between column centres
// (i + 0.5) / W, wrapping, and rows at j / (H - 1), clamped; every texel is
// read with texelFetch (no filtering, no float-filtering extension).
//
// Sampling draws a cell of the bilinear patches (corners: two adjacent
// columns, two adjacent rows) with probability proportional to its mean
// luminance times its solid angle, then a uniform point of the cell in
// (u, v): the solid-angle pdf is pdfUv / (2 pi^2 sin theta). Constant time:
// one texel fetch per dimension (alias tables), none of them in a loop.
//
// Compiled in only for scenes with a map (HAS_ENV_MAP): the trace program
// variants of src/render/passes/trace.ts.

#if HAS_ENV_MAP

uniform highp sampler2D uEnvironmentMap;
uniform highp sampler2D uEnvironmentMarginal;
uniform highp sampler2D uEnvironmentConditional;
uniform vec2 uEnvironmentRotation;
uniform float uEnvironmentIntensity;

// World direction -> map frame (rotation about +y by -rotation).
vec3 environmentToMap(vec3 d) {
  float c = uEnvironmentRotation.x;
  float s = uEnvironmentRotation.y;
  return vec3(c * d.x - s * d.z, d.y, s * d.x + c * d.z);
}

// Map frame -> world direction (rotation about +y by rotation).
vec3 environmentToWorld(vec3 m) {
  float c = uEnvironmentRotation.x;
  float s = uEnvironmentRotation.y;
  return vec3(c * m.x + s * m.z, m.y, -s * m.x + c * m.z);
}

vec2 environmentUv(vec3 worldDir) {
  vec3 m = environmentToMap(worldDir);
  // atan(0, 0) is undefined in GLSL: straight up or down, any u will do.
  bool pole = m.x == 0.0 && m.z == 0.0;
  float u = pick(pole, 0.5, 0.5 + atan(-m.x, m.z) * (0.5 * INV_PI));
  return vec2(u, acos(clamp(m.y, -1.0, 1.0)) * INV_PI);
}

vec3 environmentLookup(vec2 uv) {
  ivec2 size = textureSize(uEnvironmentMap, 0);
  float x = uv.x * float(size.x) - 0.5;
  float x0 = floor(x);
  float tx = x - x0;
  int c0 = int(x0) % size.x;
  c0 += c0 < 0 ? size.x : 0;
  int c1 = pick(c0 + 1 == size.x, 0, c0 + 1);
  float y = clamp(uv.y, 0.0, 1.0) * float(size.y - 1);
  int r0 = min(int(y), max(size.y - 2, 0));
  float ty = pick(size.y > 1, y - float(r0), 0.0);
  int r1 = min(r0 + 1, size.y - 1);
  vec3 top = mix(texelFetch(uEnvironmentMap, ivec2(c0, r0), 0).rgb, texelFetch(uEnvironmentMap, ivec2(c1, r0), 0).rgb, tx);
  vec3 bottom = mix(texelFetch(uEnvironmentMap, ivec2(c0, r1), 0).rgb, texelFetch(uEnvironmentMap, ivec2(c1, r1), 0).rgb, tx);
  return mix(top, bottom, ty);
}

// Radiance arriving from (travelling against) the unit world direction worldDir.
vec3 environmentRadiance(vec3 worldDir) {
  return uEnvironmentIntensity * environmentLookup(environmentUv(worldDir));
}

// Alias-table draw in row `row` of `table` (n entries) from u in [0, 1):
// (entry index, u remapped to [0, 1) inside the entry, probability of the entry).
vec3 drawAlias(highp sampler2D table, int row, int n, float u) {
  float x = u * float(n);
  int i = min(int(x), n - 1);
  float f = min(x - float(i), 1.0);
  vec4 entry = texelFetch(table, ivec2(i, row), 0);
  bool keep = f < entry.x;
  float t = pick(keep, f / entry.x, (f - entry.x) / max(1.0 - entry.x, 1e-30));
  return pick(keep, vec3(float(i), t, entry.z), vec3(entry.y, min(t, 1.0), entry.w));
}

// Jacobian of (u, v) on the unit square -> solid angle: 2 pi^2 sin(theta).
float environmentSolidAnglePdf(float pdfUv, float sinTheta) {
  return pick(sinTheta > 0.0, pdfUv / (2.0 * PI * PI * sinTheta), 0.0);
}

// A world direction drawn from the map's distribution; pdf = its solid-angle density.
vec3 sampleEnvironment(vec2 u, out float pdf) {
  ivec2 cells = textureSize(uEnvironmentConditional, 0);
  vec3 row = drawAlias(uEnvironmentMarginal, 0, cells.y, u.y);
  vec3 column = drawAlias(uEnvironmentConditional, int(row.x), cells.x, u.x);
  float mapU = fract((column.x + column.y + 0.5) / float(cells.x));
  float cosTheta = cos(PI * (row.x + row.y) / float(cells.y));
  // sin(theta) as environmentPdf computes it from the direction, so that
  // both give the same pdf for it (MIS weights compare the two).
  float sinTheta = sqrt(max(0.0, 1.0 - cosTheta * cosTheta));
  float phi = 2.0 * PI * (mapU - 0.5);
  pdf = environmentSolidAnglePdf(row.z * column.z * float(cells.x * cells.y), sinTheta);
  return environmentToWorld(vec3(-sinTheta * sin(phi), cosTheta, sinTheta * cos(phi)));
}

// Solid-angle density with which sampleEnvironment draws the unit world direction worldDir.
float environmentPdf(vec3 worldDir) {
  ivec2 cells = textureSize(uEnvironmentConditional, 0);
  vec2 uv = environmentUv(worldDir);
  float shifted = fract(uv.x - 0.5 / float(cells.x));
  int column = min(int(shifted * float(cells.x)), cells.x - 1);
  int row = clamp(int(uv.y * float(cells.y)), 0, cells.y - 1);
  float pdfUv = texelFetch(uEnvironmentMarginal, ivec2(row, 0), 0).z
    * texelFetch(uEnvironmentConditional, ivec2(column, row), 0).z * float(cells.x * cells.y);
  // Rotation about +y keeps y: sin(theta) straight from the direction.
  return environmentSolidAnglePdf(pdfUv, sqrt(max(0.0, 1.0 - worldDir.y * worldDir.y)));
}

#endif
