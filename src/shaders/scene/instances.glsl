// Mesh queries of the scene: closest hit, any hit and the surface at a hit,
// over the BVH groups of src/render/bvh/groups.ts.
//
// Without shared files (HAS_INSTANCES 0) there is one group, in world space:
// these are the BVH's own queries. With them, every group is reached through
// the instance table (scene/layout.glsl): the world group once, with an
// identity transform, and a shared file's group once per mesh naming it. A
// query visits the instances in turn, each with the ray taken into its
// object space (origin and direction through the 3x4 world-to-object
// matrix, the direction not renormalized, so t stays the world ray's and one
// running closest t bounds them all). One call site of the traversal, in the
// loop: SwiftShader compiles a second inlined traversal at great cost.
// Within an instance the watertight test sees one transformed ray for every
// triangle, so shared edges stay closed.

#if HAS_MESHES

struct MeshHit {
  BvhHit triangle;
  int instance;  // index into the instance table (0 without instancing)
};

#if HAS_INSTANCES

InstanceRecord loadInstance(int i) { return readInstanceRecord(i * INSTANCE_RECORD_TEXELS); }

vec3 instancePoint(vec4 x, vec4 y, vec4 z, vec3 p) { return vec3(dot(x.xyz, p) + x.w, dot(y.xyz, p) + y.w, dot(z.xyz, p) + z.w); }
vec3 instanceVector(vec4 x, vec4 y, vec4 z, vec3 v) { return vec3(dot(x.xyz, v), dot(y.xyz, v), dot(z.xyz, v)); }

// The ray in instance i's object space (the world-to-object rows only: the
// loop reads 3 of the record's texels, not all 7).
void instanceRay(int i, vec3 origin, vec3 dir, out vec3 o, out vec3 d) {
  int first = i * INSTANCE_RECORD_TEXELS;
  vec4 x = instanceTexel(first + INSTANCE_RECORD_TO_OBJECT_X_TEXEL);
  vec4 y = instanceTexel(first + INSTANCE_RECORD_TO_OBJECT_Y_TEXEL);
  vec4 z = instanceTexel(first + INSTANCE_RECORD_TO_OBJECT_Z_TEXEL);
  o = instancePoint(x, y, z, origin);
  d = instanceVector(x, y, z, dir);
}

// Each instance's traversal finds only a texel and t; the barycentrics are
// computed once, for the closest instance's ray (bvhHitAt), not per instance.
bool meshIntersect(vec3 origin, vec3 dir, float tMax, bool anyHit, out MeshHit hit) {
  float best = tMax;
  int bestTexel = -1;
  int bestInstance = -1;
  vec3 o, d;
  for (int i = 0; i < uInstanceCount; i++) {
    instanceRay(i, origin, dir, o, d);
    int root = int(instanceTexel(i * INSTANCE_RECORD_TEXELS + INSTANCE_RECORD_ROOT_TEXEL).x);
    int texel = bvhFindTexel(root, o, d, bvhShear(d), anyHit, best);
    bestTexel = texel >= 0 ? texel : bestTexel;
    bestInstance = texel >= 0 ? i : bestInstance;
    if (anyHit && texel >= 0) break;
  }
  hit.instance = bestInstance;
  if (anyHit) {
    hit.triangle = BvhHit(-1, best, vec2(0.0));
  } else {
    instanceRay(max(bestInstance, 0), origin, dir, o, d);
    hit.triangle = bvhHitAt(bestTexel, best, o, bvhShear(d));
  }
  return bestInstance >= 0;
}

// The surface in world space: the point by the object-to-world matrix,
// normals by the inverse transpose of its linear part, which is the
// transpose of the world-to-object matrix's (scales are positive: no
// mirroring), vertex normals renormalized each as a copy's (bvhSurface).
BvhSurface meshSurface(MeshHit hit) {
  InstanceRecord r = loadInstance(hit.instance);
  mat3 normalMatrix = mat3(r.toObjectX.xyz, r.toObjectY.xyz, r.toObjectZ.xyz);  // columns: the transpose
  BvhSurface s = bvhSurface(hit.triangle, normalMatrix);
  s.position = instancePoint(r.toWorldX, r.toWorldY, r.toWorldZ, s.position);
#if HAS_NORMAL_MAPS
  mat3 toWorld = transpose(mat3(r.toWorldX.xyz, r.toWorldY.xyz, r.toWorldZ.xyz));
  s.dpdu = toWorld * s.dpdu;
  s.dpdv = toWorld * s.dpdv;
#endif
  s.mesh = r.mesh >= 0 ? r.mesh : s.mesh;
  return s;
}

#else

bool meshIntersect(vec3 origin, vec3 dir, float tMax, bool anyHit, out MeshHit hit) {
  hit.instance = 0;
  return bvhIntersect(BVH_ROOT_NODE, origin, dir, tMax, anyHit, hit.triangle);
}

BvhSurface meshSurface(MeshHit hit) { return bvhSurface(hit.triangle); }

#endif

bool meshClosestHit(vec3 origin, vec3 dir, float tMax, out MeshHit hit) { return meshIntersect(origin, dir, tMax, false, hit); }

bool meshAnyHit(vec3 origin, vec3 dir, float tMax) {
  MeshHit hit;
  return meshIntersect(origin, dir, tMax, true, hit);
}

#endif
