// Triangle BVH traversal (closest hit and any hit) and the surface at a hit.
// Packed by src/render/bvh/pack.ts (the layout in full), uploaded by
// src/render/bvhTextures.ts.
//
// uniform sampler2DArray uBvh  RGBA32F, 2048 x 512 (one layer: fewer rows) x layers;
//   texel i at (i % 2048, (i / 2048) % 512, layer i / 2^20). Integers are exact float values
//   but for the nodes' codes (bit patterns of normal floats).
//   A node at texel q (the root: q = BVH_ROOT_NODE) holds its up to 4 children's boxes as
//     structure of arrays, one child per component: (min x), (max x), (min y), (max y),
//     (min z), (max z), then their codes: floatBitsToInt - BVH_CODE_BIAS = ref * 16 + count,
//     a leaf of `count` triangles from texel ref, or (count 0) the node at texel ref;
//     negative for an empty slot.
//   Triangle j (BVH order) = texels bvhTriangleTexel(j) .. + 2, 681 to a row (none straddles one):
//     (v0.xyz, local material), (v1.xyz, attributes), (v2.xyz, mesh index);
//     the material-table index is the mesh record's materialBase + local (scene/intersect.glsl);
//     attributes (read by bvhSurface only): -1 none; a >= 0 smooth, vertex normals n0 n1 n2
//     at a .. a + 2 and, when n0.w is 1, corner uvs at a + 3, a + 4; -2 - a flat with corner
//     uvs at a, a + 1. Corner uvs: (u0, v0, u1, v1), (u2, v2, colors, 0). Vertex colors
//     (HAS_VERTEX_COLORS only) follow the uvs (or a smooth triangle's normals when it has
//     none) when n1.w is 1 (smooth) or the uvs' `colors` is 1 (flat): (c0.rgb, 0), (c1.rgb, 0),
//     (c2.rgb, 0).
//
// Traversal, shaped for SwiftShader: it runs a pixel quad's 4 lanes in lock
// step through everything in the loop body, whatever each lane does (both
// sides of every branch; only a loop's back edge skips work), and a
// texelFetch is a call into its sampler routine. So each step of the one loop
// fetches the same 7 texels for every lane (one coordinate and constant
// offsets: no node or triangle pair straddles a row) and uses them as a 4-wide
// node (a lane with no triangles pending) or as the next two triangles of a
// leaf, both computed and one selected. Per step the 7 fetches are about a
// third of the cost, the 4 box tests a seventh, each triangle test a twelfth
// (bench/bvh-kernel-ab.ts; bench/results/wide-bvh-2026-12-06.md).
// A node step tests its children's boxes, sorts them by entry distance with a
// 5-comparator network of selects (farthest first, misses last) and writes all
// 4 on the stack from its top, counting the hit ones: the nearest is popped
// next, and leaves ride the stack as pending triangle ranges. A popped item
// farther than the best hit costs a step (no distances on the stack). The stack
// holds BVH_STACK_SIZE entries and 4 spare; wide.ts bounds its depth. A
// triangle step runs the watertight ray-triangle test of Woop, Benthin and
// Wald (JCGT 2013) twice, so a ray through a shared edge or vertex hits one of
// its triangles. The slab test is conservative. Hits need 0 < t < tMax: the
// caller offsets ray origins.

// Compiled in only for scenes with meshes (HAS_MESHES; trace program variants).
#if HAS_MESHES

#ifndef BVH_TEXTURE_WIDTH_LOG2
#define BVH_TEXTURE_WIDTH_LOG2 11
#endif
#ifndef BVH_LAYER_ROWS_LOG2
#define BVH_LAYER_ROWS_LOG2 9
#endif
#ifndef BVH_STACK_SIZE
#define BVH_STACK_SIZE 64
#endif
#ifndef BVH_ROW_TRIANGLES
#define BVH_ROW_TRIANGLES 681
#endif
#ifndef BVH_ROOT_NODE
#define BVH_ROOT_NODE 0
#endif
#ifndef BVH_FIRST_SLOT
#define BVH_FIRST_SLOT 3
#endif
#ifndef BVH_CODE_BIAS
#define BVH_CODE_BIAS 0x3f800000
#endif
#ifndef HAS_INSTANCES
#define HAS_INSTANCES 0
#endif
#ifndef HAS_VERTEX_COLORS
#define HAS_VERTEX_COLORS 0
#endif

uniform highp sampler2DArray uBvh;

struct BvhHit {
  int triangle;     // BVH order (texels bvhTriangleTexel(triangle) ..); -1 when nothing was hit
  float t;
  vec2 barycentric; // weights of v1 and v2 (v0's is 1 - x - y)
};

struct BvhSurface {
  vec3 position;
  vec3 geometricNormal; // unit, from the counter-clockwise winding v0 v1 v2
  vec3 shadingNormal;   // interpolated vertex normal (smooth), else the geometric normal
  vec2 uv;              // interpolated corner texture coordinates, (0, 0) without
  vec3 dpdu, dpdv;      // normal maps: the triangle's position derivatives along u and v (0 without uvs)
#if HAS_VERTEX_COLORS
  vec3 color;           // interpolated corner vertex colors (linear), white without
#endif
  int localMaterial;  // among the mesh's own: the table's is its MeshRecord.materialBase + this
  int mesh;
};

const float BVH_NO_HIT = 3.0e38;
// pbrt uses 1 + 2 gamma(3) (3.6e-7) so a box never loses a hit on its face to rounding;
// a few ulps more cover GPUs whose division is approximate.
const float BVH_BOX_EXIT_SCALE = 1.000001;

// A plain 2D texture BVH_TEXTURE_WIDTH wide (other per-triangle tables): texel i at (i % W, i / W).
vec4 bvhTexel(highp sampler2D map, int i) {
  return texelFetch(map, ivec2(i & ((1 << BVH_TEXTURE_WIDTH_LOG2) - 1), i >> BVH_TEXTURE_WIDTH_LOG2), 0);
}

vec4 bvhTexel(highp sampler2DArray map, int i) {
  const int columns = (1 << BVH_TEXTURE_WIDTH_LOG2) - 1;
  const int rows = (1 << BVH_LAYER_ROWS_LOG2) - 1;
  return texelFetch(map, ivec3(i & columns, (i >> BVH_TEXTURE_WIDTH_LOG2) & rows, i >> (BVH_TEXTURE_WIDTH_LOG2 + BVH_LAYER_ROWS_LOG2)), 0);
}

// The watertight test's per-ray transform: (p - origin) * shear = (x, y) in
// the plane across the ray, z along it scaled so that z = t on the ray.
mat3 bvhShear(vec3 dir) {
  vec3 a = abs(dir);
  // Ternaries of names and constants only (selects; see pick() in common/math.glsl).
  int kzFromX = a.x > a.z ? 0 : 2;
  int kzFromY = a.y > a.z ? 1 : 2;
  int kz = a.x > a.y ? kzFromX : kzFromY;
  int kzNext = kz + 1;
  int kx = kz == 2 ? 0 : kzNext;
  int kxNext = kx + 1;
  int ky = kx == 2 ? 0 : kxNext;
  vec3 ex = vec3(equal(ivec3(0, 1, 2), ivec3(kx)));
  vec3 ey = vec3(equal(ivec3(0, 1, 2), ivec3(ky)));
  vec3 ez = vec3(equal(ivec3(0, 1, 2), ivec3(kz)));
  float dz = dot(dir, ez);
  return mat3(ex - (dot(dir, ex) / dz) * ez, ey - (dot(dir, ey) / dz) * ez, ez / dz);
}

// The 7 texels from texel i (i % 2048 <= 2041: they share a row).
void bvhTexels7(int i, out vec4 t0, out vec4 t1, out vec4 t2, out vec4 t3, out vec4 t4, out vec4 t5, out vec4 t6) {
  const int columns = (1 << BVH_TEXTURE_WIDTH_LOG2) - 1;
  const int rows = (1 << BVH_LAYER_ROWS_LOG2) - 1;
  ivec3 at = ivec3(i & columns, (i >> BVH_TEXTURE_WIDTH_LOG2) & rows, i >> (BVH_TEXTURE_WIDTH_LOG2 + BVH_LAYER_ROWS_LOG2));
  t0 = texelFetch(uBvh, at, 0);
  t1 = texelFetchOffset(uBvh, at, 0, ivec2(1, 0));
  t2 = texelFetchOffset(uBvh, at, 0, ivec2(2, 0));
  t3 = texelFetchOffset(uBvh, at, 0, ivec2(3, 0));
  t4 = texelFetchOffset(uBvh, at, 0, ivec2(4, 0));
  t5 = texelFetchOffset(uBvh, at, 0, ivec2(5, 0));
  t6 = texelFetchOffset(uBvh, at, 0, ivec2(6, 0));
}

int bvhTriangleTexel(int j) {
  int slot = j + BVH_FIRST_SLOT;
  return (slot / BVH_ROW_TRIANGLES << BVH_TEXTURE_WIDTH_LOG2) + slot % BVH_ROW_TRIANGLES * 3;
}

// The watertight test's edge functions of triangle (v0, v1, v2) in ray space
// (the barycentric weights of v0, v1, v2 times det = e.x + e.y + e.z), and
// t * det in tScaled.
vec3 bvhEdges(vec3 v0, vec3 v1, vec3 v2, vec3 origin, mat3 shear, out float tScaled) {
  vec3 A = (v0 - origin) * shear;
  vec3 B = (v1 - origin) * shear;
  vec3 C = (v2 - origin) * shear;
  vec3 e = vec3(C.x * B.y - C.y * B.x, A.x * C.y - A.y * C.x, B.x * A.y - B.y * A.x);
  tScaled = dot(e, vec3(A.z, B.z, C.z));
  return e;
}

// t of the ray on triangle (v0, v1, v2) when it hits it, else -1.
float bvhTriangleT(vec3 v0, vec3 v1, vec3 v2, vec3 origin, mat3 shear) {
  float tScaled;
  vec3 e = bvhEdges(v0, v1, v2, origin, shear, tScaled);
  float det = e.x + e.y + e.z;
  float t = tScaled / det;
  bool inside = !(any(lessThan(e, vec3(0.0))) && any(greaterThan(e, vec3(0.0))));
  return inside && det != 0.0 && t > 0.0 ? t : -1.0;
}

// (a, ia) and (b, ib) in descending order of a (b first only when strictly
// farther): a comparator of the sorting network, selects only.
void bvhOrder(inout float a, inout int ia, inout float b, inout int ib) {
  bool swap = b > a;
  float farther = max(a, b), nearer = min(a, b);
  int first = swap ? ib : ia, second = swap ? ia : ib;
  a = farther;
  b = nearer;
  ia = first;
  ib = second;
}

// Closest hit before tMax (anyHit false), or the first found (anyHit true:
// shadow rays), in the BVH whose root node is `root` (BVH_ROOT_NODE, or a
// group's root: scene/instances.glsl). `dir` need not be unit: t is in its units.
// The traversal itself: the first texel of the closest triangle hit before
// `best` (or the first found, anyHit), -1 for none; `best` becomes its t.
// `shear` is bvhShear(dir).
// Items (the current one and the stack's): a node q >= 0, a leaf's pending
// triangles -2 - (texel * 16 + count) (texel: the next one's first), none -1.
// Every choice in the loop is a ternary of names and constants (a select,
// not an if/else: SwiftShader's compile time doubles with each if/else in a
// loop, see pick() in common/math.glsl), and there is no early exit.
int bvhFindTexel(int root, vec3 origin, vec3 dir, mat3 shear, bool anyHit, inout float best) {
  // Zero direction components become huge (same sign): no 0 * inf = NaN in the slab test.
  vec3 invDir = (vec3(greaterThanEqual(dir, vec3(0.0))) * 2.0 - 1.0) / max(abs(dir), vec3(1e-30));
  const int columnMask = (1 << BVH_TEXTURE_WIDTH_LOG2) - 1;
  const int lastColumn = 3 * BVH_ROW_TRIANGLES - 3;
  int bestTexel = -1;
  // A node step writes its 4 children at sp .. sp + 3 (the hit ones count).
  int stack[BVH_STACK_SIZE + 4];
  int sp = 0;
  int item = root;
  do {
    bool isTriangle = item < -1;
    int leaf = -2 - item;
    int leafTexel = leaf >> 4;
    int texel = isTriangle ? leafTexel : item;
    vec4 t0, t1, t2, t3, t4, t5, t6;
    bvhTexels7(texel, t0, t1, t2, t3, t4, t5, t6);

    // As triangles: the next two of the leaf (the barycentrics: bvhHitAt). A
    // row's last triangle's pair is the row's zero padding: never hit.
    int count = leaf & 15;
    float tA = bvhTriangleT(t0.xyz, t1.xyz, t2.xyz, origin, shear);
    float tB = bvhTriangleT(t3.xyz, t4.xyz, t5.xyz, origin, shear);
    bool foundA = isTriangle && tA > 0.0 && tA < best;
    best = foundA ? tA : best;
    bool foundB = isTriangle && count >= 2 && tB > 0.0 && tB < best;
    best = foundB ? tB : best;
    int texelB = texel + 3;
    int texelA = foundA ? texel : bestTexel;
    bestTexel = foundB ? texelB : texelA;
    bool found = foundA || foundB;
    // The leaf's rest: 6 texels on, or the next row's first after a row's last two (or last one).
    int column = texel & columnMask;
    int nextRow = (texel | columnMask) + 1;
    int nextPair = texel + 6;
    int nextTexel = column >= lastColumn - 3 ? nextRow : nextPair;
    int tested = column == lastColumn ? 1 : 2;
    int left = count - tested;
    int rest = -2 - (nextTexel << 4 | left);
    int triangleItem = left > 0 ? rest : -1;

    // As a node: the 4 children's boxes (texels 0 .. 5: min x, max x, min y, ..)
    // and codes (6: ref * 16 + count, count 0 for a node; negative: an empty slot).
    vec4 x0 = (t0 - origin.x) * invDir.x, x1 = (t1 - origin.x) * invDir.x;
    vec4 y0 = (t2 - origin.y) * invDir.y, y1 = (t3 - origin.y) * invDir.y;
    vec4 z0 = (t4 - origin.z) * invDir.z, z1 = (t5 - origin.z) * invDir.z;
    vec4 enter = max(max(min(x0, x1), min(y0, y1)), max(min(z0, z1), vec4(0.0)));
    vec4 exit = min(min(max(x0, x1), max(y0, y1)), min(max(z0, z1), vec4(best)));
    ivec4 code = floatBitsToInt(t6) - BVH_CODE_BIAS;
    vec4 inBox = vec4(lessThanEqual(enter, exit * BVH_BOX_EXIT_SCALE));
    vec4 used = vec4(greaterThanEqual(code, ivec4(0)));
    float isNode = isTriangle ? 0.0 : 1.0;
    vec4 hit = inBox * used * isNode;
    // Sort keys: the entry distance, -1 for a child not hit (sorted last).
    vec4 d = mix(vec4(-1.0), enter, greaterThan(hit, vec4(0.0)));
    ivec4 ref = code >> 4, n = code & 15;
    ivec4 leaves = -2 - code;
    float d0 = d.x, d1 = d.y, d2 = d.z, d3 = d.w;
    int i0 = n.x > 0 ? leaves.x : ref.x, i1 = n.y > 0 ? leaves.y : ref.y;
    int i2 = n.z > 0 ? leaves.z : ref.z, i3 = n.w > 0 ? leaves.w : ref.w;
    bvhOrder(d0, i0, d1, i1);
    bvhOrder(d2, i2, d3, i3);
    bvhOrder(d0, i0, d2, i2);
    bvhOrder(d1, i1, d3, i3);
    bvhOrder(d1, i1, d2, i2);
    int hits = int(dot(hit, vec4(1.0)));
    // All 4 written, the hit ones (the farthest deepest) kept; the nearest is
    // popped next. On a triangle step the writes land above the top.
    stack[sp] = i0;
    stack[sp + 1] = i1;
    stack[sp + 2] = i2;
    stack[sp + 3] = i3;
    sp += hits;
    item = isTriangle ? triangleItem : -1;

    // A shadow ray is done at its first hit.
    bool done = anyHit && found;
    item = done ? -1 : item;
    sp = done ? 0 : sp;
    // Nothing to visit next: pop.
    bool pop = item == -1 && sp > 0;
    int top = stack[max(sp - 1, 0)];
    item = pop ? top : item;
    sp -= pop ? 1 : 0;
  } while (item != -1);
  return bestTexel;
}

// The hit on the triangle at `texel` (-1: none) at distance t: its index and
// barycentrics, computed once after the traversal (kept per step, they cost
// SwiftShader's compiler 0.8 s more for the trace shader).
BvhHit bvhHitAt(int texel, float t, vec3 origin, mat3 shear) {
  int triangleIndex = (texel >> BVH_TEXTURE_WIDTH_LOG2) * BVH_ROW_TRIANGLES + (texel & ((1 << BVH_TEXTURE_WIDTH_LOG2) - 1)) / 3 - BVH_FIRST_SLOT;
  int at = max(texel, 0);
  vec4 v0 = bvhTexel(uBvh, at), v1 = bvhTexel(uBvh, at + 1), v2 = bvhTexel(uBvh, at + 2);
  float tScaled;
  vec3 e = bvhEdges(v0.xyz, v1.xyz, v2.xyz, origin, shear, tScaled);
  int index = texel < 0 ? -1 : triangleIndex;
  return BvhHit(index, t, e.yz / (e.x + e.y + e.z));
}

bool bvhIntersect(int root, vec3 origin, vec3 dir, float tMax, bool anyHit, out BvhHit hit) {
  mat3 shear = bvhShear(dir);
  float best = tMax;
  int texel = bvhFindTexel(root, origin, dir, shear, anyHit, best);
  hit = bvhHitAt(texel, best, origin, shear);
  return texel >= 0;
}

bool bvhClosestHit(vec3 origin, vec3 dir, float tMax, out BvhHit hit) {
  return bvhIntersect(BVH_ROOT_NODE, origin, dir, tMax, false, hit);
}

bool bvhAnyHit(vec3 origin, vec3 dir, float tMax) {
  BvhHit hit;
  return bvhIntersect(BVH_ROOT_NODE, origin, dir, tMax, true, hit);
}

#if HAS_INSTANCES
// v / |v|, and 0 for 0 (a zero vertex normal stays zero, as applyMatrix keeps it).
vec3 bvhUnitOrZero(vec3 v) {
  float l2 = dot(v, v);
  vec3 unit = v * inversesqrt(l2);
  return l2 > 0.0 ? unit : vec3(0.0);
}
#endif

// The surface at a hit. With instancing, `normalMatrix` takes the normals
// into world space (the instance's; identity for the world group), each
// vertex normal renormalized before interpolation as a world-space copy's
// are (src/scene/mesh/transform.ts applyMatrix), so an instance shades as
// its copy would; the position stays in the triangle's space.
#if HAS_NORMAL_MAPS
// dp/du and dp/dv of a triangle with edges e1, e2 and texture-coordinate
// edges d1, d2 (pbrt's Triangle::InteractionFromIntersection); zero when
// its coordinates are degenerate (a normal map then keeps the normal).
void bvhPositionDerivatives(vec3 e1, vec3 e2, vec2 d1, vec2 d2, out vec3 dpdu, out vec3 dpdv) {
  float det = d1.x * d2.y - d1.y * d2.x;
  float reciprocal = 1.0 / det;
  float inv = abs(det) > 1e-20 ? reciprocal : 0.0;
  dpdu = (d2.y * e1 - d1.y * e2) * inv;
  dpdv = (d1.x * e2 - d2.x * e1) * inv;
}
#endif

BvhSurface bvhSurface(BvhHit hit, mat3 normalMatrix) {
  int texel = bvhTriangleTexel(hit.triangle);
  vec4 t0 = bvhTexel(uBvh, texel);
  vec4 t1 = bvhTexel(uBvh, texel + 1);
  vec4 t2 = bvhTexel(uBvh, texel + 2);
  vec3 b = vec3(1.0 - hit.barycentric.x - hit.barycentric.y, hit.barycentric);
  BvhSurface s;
  s.position = b.x * t0.xyz + b.y * t1.xyz + b.z * t2.xyz;
  vec3 faceNormal = cross(t1.xyz - t0.xyz, t2.xyz - t0.xyz);
#if HAS_INSTANCES
  faceNormal = normalMatrix * faceNormal;
#endif
  s.geometricNormal = normalize(faceNormal);
  s.shadingNormal = s.geometricNormal;
  int attributes = int(t1.w);
  bool textured = attributes <= -2;
#if HAS_VERTEX_COLORS
  bool colored = false;
  int colorTexel = 0;
#endif
  if (t1.w >= 0.0) {
    int k = int(t1.w);
    vec4 first = bvhTexel(uBvh, k);
    textured = first.w > 0.0;
    vec4 second = bvhTexel(uBvh, k + 1);
    vec3 n0 = first.xyz, n1 = second.xyz, n2 = bvhTexel(uBvh, k + 2).xyz;
#if HAS_VERTEX_COLORS
    colored = second.w > 0.0;
    colorTexel = k + 3 + (textured ? 2 : 0);
#endif
#if HAS_INSTANCES
    n0 = bvhUnitOrZero(normalMatrix * n0);
    n1 = bvhUnitOrZero(normalMatrix * n1);
    n2 = bvhUnitOrZero(normalMatrix * n2);
#endif
    vec3 n = b.x * n0 + b.y * n1 + b.z * n2;
    // Opposite vertex normals can cancel: keep the face normal then.
    if (dot(n, n) > 1e-12) s.shadingNormal = normalize(n);
  }
  // Per-corner data in the triangle's own space: an instance's transform leaves them alone.
  s.uv = vec2(0.0);
  s.dpdu = vec3(0.0);
  s.dpdv = vec3(0.0);
  if (textured) {
    int smoothUvs = attributes + 3, flatUvs = -2 - attributes;
    int k = attributes >= 0 ? smoothUvs : flatUvs;
    vec4 uv01 = bvhTexel(uBvh, k);
    vec4 uv2Texel = bvhTexel(uBvh, k + 1);
    vec2 uv2 = uv2Texel.xy;
    s.uv = b.x * uv01.xy + b.y * uv01.zw + b.z * uv2;
#if HAS_NORMAL_MAPS
    bvhPositionDerivatives(t1.xyz - t0.xyz, t2.xyz - t0.xyz, uv01.zw - uv01.xy, uv2 - uv01.xy, s.dpdu, s.dpdv);
#endif
#if HAS_VERTEX_COLORS
    colored = colored || (attributes <= -2 && uv2Texel.z > 0.0);
    int flatColors = k + 2;
    colorTexel = attributes >= 0 ? colorTexel : flatColors;
#endif
  }
#if HAS_VERTEX_COLORS
  s.color = vec3(1.0);
  if (colored) {
    s.color = b.x * bvhTexel(uBvh, colorTexel).rgb + b.y * bvhTexel(uBvh, colorTexel + 1).rgb + b.z * bvhTexel(uBvh, colorTexel + 2).rgb;
  }
#endif
  s.localMaterial = int(t0.w);
  s.mesh = int(t2.w);
  return s;
}

BvhSurface bvhSurface(BvhHit hit) { return bvhSurface(hit, mat3(1.0)); }

#endif
