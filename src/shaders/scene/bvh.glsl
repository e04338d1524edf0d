// Triangle BVH traversal (closest hit and any hit) and the surface at a hit.
// Packed by src/render/bvh/pack.ts, uploaded by src/render/bvhTextures.ts.
//
// uniform sampler2DArray uBvhNodes      RGBA32F, 2048 x 512 (one layer: fewer rows) x layers;
//   texel i at (i % 2048, (i / 2048) % 512, layer i / 2^20).
//   Node i = texels 2i, 2i+1: (min.xyz, a), (max.xyz, b).
//   Interior: b = 0, first child i + 1, second child a. Leaf: b = triangle count, a = first triangle.
// uniform sampler2DArray uBvhTriangles  the same layout. Triangle j = texels 3j .. 3j+2:
//   (v0.xyz, material), (v1.xyz, normals texel or -1 if flat), (v2.xyz, mesh index);
//   a smooth triangle's vertex normals n0 n1 n2 at its normals texel .. +2.
// Integers are stored as exact float values.
//
// Traversal: nearest child first with a fixed stack of BVH_STACK_SIZE (the
// build caps the depth at that), a conservative slab test, and the watertight
// ray-triangle test of Woop, Benthin and Wald (JCGT 2013), so a ray through a
// shared edge or vertex hits one of its triangles. Hits need 0 < t < tMax:
// the caller offsets ray origins.

// Compiled in only for scenes with meshes (HAS_MESHES; trace program variants).
#if HAS_MESHES

#ifndef BVH_TEXTURE_WIDTH_LOG2
#define BVH_TEXTURE_WIDTH_LOG2 11
#endif
#ifndef BVH_LAYER_ROWS_LOG2
#define BVH_LAYER_ROWS_LOG2 9
#endif
#ifndef BVH_STACK_SIZE
#define BVH_STACK_SIZE 32
#endif

uniform highp sampler2DArray uBvhNodes;
uniform highp sampler2DArray uBvhTriangles;

struct BvhHit {
  int triangle;     // BVH order; -1 when nothing was hit
  float t;
  vec2 barycentric; // weights of v1 and v2 (v0's is 1 - x - y)
};

struct BvhSurface {
  vec3 position;
  vec3 geometricNormal; // unit, from the counter-clockwise winding v0 v1 v2
  vec3 shadingNormal;   // interpolated vertex normal (smooth), else the geometric normal
  int material;
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

// Entry distance into node's box, or BVH_NO_HIT when the ray misses it before tMax.
float bvhBoxEntry(int node, vec3 origin, vec3 invDir, float tMax) {
  vec3 t0 = (bvhTexel(uBvhNodes, 2 * node).xyz - origin) * invDir;
  vec3 t1 = (bvhTexel(uBvhNodes, 2 * node + 1).xyz - origin) * invDir;
  vec3 near = min(t0, t1);
  vec3 far = max(t0, t1);
  float enter = max(max(near.x, near.y), max(near.z, 0.0));
  float exit = min(min(far.x, far.y), min(far.z, tMax));
  return enter <= exit * BVH_BOX_EXIT_SCALE ? enter : BVH_NO_HIT;
}

// The watertight test's per-ray transform: (p - origin) * shear = (x, y) in
// the plane across the ray, z along it scaled so that z = t on the ray.
mat3 bvhShear(vec3 dir) {
  vec3 a = abs(dir);
  int kz = a.x > a.y ? (a.x > a.z ? 0 : 2) : (a.y > a.z ? 1 : 2);
  int kx = kz == 2 ? 0 : kz + 1;
  int ky = kx == 2 ? 0 : kx + 1;
  vec3 ex = vec3(equal(ivec3(0, 1, 2), ivec3(kx)));
  vec3 ey = vec3(equal(ivec3(0, 1, 2), ivec3(ky)));
  vec3 ez = vec3(equal(ivec3(0, 1, 2), ivec3(kz)));
  float dz = dot(dir, ez);
  return mat3(ex - (dot(dir, ex) / dz) * ez, ey - (dot(dir, ey) / dz) * ez, ez / dz);
}

// Closest hit before tMax (anyHit false), or the first found (anyHit true: shadow rays).
bool bvhIntersect(vec3 origin, vec3 dir, float tMax, bool anyHit, out BvhHit hit) {
  hit = BvhHit(-1, tMax, vec2(0.0));
  // Zero direction components become huge (same sign): no 0 * inf = NaN in the slab test.
  vec3 invDir = (vec3(greaterThanEqual(dir, vec3(0.0))) * 2.0 - 1.0) / max(abs(dir), vec3(1e-30));
  mat3 shear = bvhShear(dir);
  int stack[BVH_STACK_SIZE];
  float stackT[BVH_STACK_SIZE];
  int sp = 0;
  int node = bvhBoxEntry(0, origin, invDir, tMax) < BVH_NO_HIT ? 0 : -1;
  while (node >= 0) {
    float a = bvhTexel(uBvhNodes, 2 * node).w;
    int count = int(bvhTexel(uBvhNodes, 2 * node + 1).w);
    int next = -1;
    if (count > 0) {
      for (int j = int(a); j < int(a) + count; j++) {
        vec3 A = (bvhTexel(uBvhTriangles, 3 * j).xyz - origin) * shear;
        vec3 B = (bvhTexel(uBvhTriangles, 3 * j + 1).xyz - origin) * shear;
        vec3 C = (bvhTexel(uBvhTriangles, 3 * j + 2).xyz - origin) * shear;
        vec3 e = vec3(C.x * B.y - C.y * B.x, A.x * C.y - A.y * C.x, B.x * A.y - B.y * A.x);
        float det = e.x + e.y + e.z;
        float t = dot(e, vec3(A.z, B.z, C.z)) / det;
        bool inside = !(any(lessThan(e, vec3(0.0))) && any(greaterThan(e, vec3(0.0))));
        if (inside && det != 0.0 && t > 0.0 && t < hit.t) {
          hit = BvhHit(j, t, e.yz / det);
          if (anyHit) return true;
        }
      }
    } else {
      int right = int(a);
      float tl = bvhBoxEntry(node + 1, origin, invDir, hit.t);
      float tr = bvhBoxEntry(right, origin, invDir, hit.t);
      bool leftFirst = tl <= tr;
      next = tl < BVH_NO_HIT ? (leftFirst ? node + 1 : right) : (tr < BVH_NO_HIT ? right : -1);
      if (max(tl, tr) < BVH_NO_HIT) {
        stack[sp] = leftFirst ? right : node + 1;
        stackT[sp] = max(tl, tr);
        sp++;
      }
    }
    // Pop the nearest pending subtree still closer than the best hit.
    while (next < 0 && sp > 0) {
      sp--;
      if (stackT[sp] <= hit.t) next = stack[sp];
    }
    node = next;
  }
  return hit.triangle >= 0;
}

bool bvhClosestHit(vec3 origin, vec3 dir, float tMax, out BvhHit hit) {
  return bvhIntersect(origin, dir, tMax, false, hit);
}

bool bvhAnyHit(vec3 origin, vec3 dir, float tMax) {
  BvhHit hit;
  return bvhIntersect(origin, dir, tMax, true, hit);
}

BvhSurface bvhSurface(BvhHit hit) {
  vec4 t0 = bvhTexel(uBvhTriangles, 3 * hit.triangle);
  vec4 t1 = bvhTexel(uBvhTriangles, 3 * hit.triangle + 1);
  vec4 t2 = bvhTexel(uBvhTriangles, 3 * hit.triangle + 2);
  vec3 b = vec3(1.0 - hit.barycentric.x - hit.barycentric.y, hit.barycentric);
  BvhSurface s;
  s.position = b.x * t0.xyz + b.y * t1.xyz + b.z * t2.xyz;
  s.geometricNormal = normalize(cross(t1.xyz - t0.xyz, t2.xyz - t0.xyz));
  s.shadingNormal = s.geometricNormal;
  if (t1.w >= 0.0) {
    int k = int(t1.w);
    vec3 n = b.x * bvhTexel(uBvhTriangles, k).xyz + b.y * bvhTexel(uBvhTriangles, k + 1).xyz + b.z * bvhTexel(uBvhTriangles, k + 2).xyz;
    // Opposite vertex normals can cancel: keep the face normal then.
    if (dot(n, n) > 1e-12) s.shadingNormal = normalize(n);
  }
  s.material = int(t0.w);
  s.mesh = int(t2.w);
  return s;
}

#endif
