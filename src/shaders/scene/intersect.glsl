// Closest-hit and any-hit queries over every shape of the scene (spheres,
// whose records include the sphere lights; the rectangle and disk lights
// of the planar-light table; the ground plane; the triangles of
// meshes through the BVH of scene/bvh.glsl, instanced or not:
// scene/instances.glsl). A Hit does not depend on the kind of shape: the
// integrator sees a point, normals and a material, and asks the light
// interface (lights/lights.glsl) how likely light sampling was to find the hit.

const int HIT_NONE = 0;
const int HIT_SPHERE = 1;
const int HIT_GROUND = 2;
const int HIT_TRIANGLE = 3;
const int HIT_PLANAR = 4;

struct Hit {
  float t;
  int kind;
  vec3 position;
  vec3 normal;      // shading normal, on the outside of the surface: it decides the side
  vec3 geometricNormal;  // offsets spawned rays (equal to `normal` but on smooth meshes)
  vec2 uv;          // texture coordinates: triangles' interpolated from their corners ((0, 0)
                    // without), the ground's world (x, z), spheres' (0, 0)
  vec4 tangent;     // normal maps: xyz along increasing u, w = 1 or -1 so that
                    // cross(normal, xyz) * w points up the image (toward decreasing v);
                    // xyz 0 without texture coordinates
  float scale;      // size of the hit object, for the self-intersection offset
#if HAS_VERTEX_COLORS
  vec3 color;       // triangles: their corners' vertex colors interpolated (white without); others white
#endif
  vec4 geometry;    // the sphere hit: [center, radius]; a planar light: [slot, emitter tag, 0, 0]
  int material;     // index into the material table
  int emitter;      // its slot in the emitter table (-1: it does not emit; the sky: the map's)
  float emitterDensity; // triangles: the mesh's density per unit area once light sampling picked it
                        // (lights/mesh_emitter.glsl); 1 for the others
};

// Nearest t > 0 where the ray (unit direction) meets the sphere, or
// INFINITY. Computes the discriminant from the ray's closest approach to the
// centre (Haines et al., Ray Tracing Gems ch. 7) to stay accurate for large
// radii and distant spheres; the near root without cancellation:
// q = -b - sign(b) h and c / q. Outside the sphere (c > 0) the roots share
// their sign and c / q is the nearer; inside, the positive root is the
// larger. (An exactly tangent ray through b = 0 gives 0 / 0: a miss.)
//
// Branch-free, like the other code run once per object: SwiftShader runs
// both sides of every branch under lane masks, and merging values after an
// if costs masked stores; a select costs less.
float sphereHitT(vec3 origin, vec3 direction, vec4 sphere) {
  vec3 oc = origin - sphere.xyz;
  float b = dot(oc, direction);
  vec3 closest = oc - b * direction;
  float r2 = sphere.w * sphere.w;
  float h = r2 - dot(closest, closest);
  float s = sqrt(max(h, 0.0));
  float q = -b - pick(b >= 0.0, s, -s);
  float c = dot(oc, oc) - r2;
  float t1 = c / q;
  float t = pick(c > 0.0, t1, max(q, t1));
  t = t > 0.0 ? t : INFINITY;
  return h >= 0.0 ? t : INFINITY;
}

// Nearest t > 0 where the ray meets the ground plane, or INFINITY (also for
// rays parallel to it: their t is NaN or infinite).
float groundHitT(vec3 origin, vec3 direction) {
  float t = (groundHeight() - origin.y) / direction.y;
  t = t > 0.0 ? t : INFINITY;
  t = t < INFINITY ? t : INFINITY;
  return groundEnabled() ? t : INFINITY;
}

// How far outside the sphere the segment from origin to
// origin + tMax * direction (unit) stays: squared distance of its closest
// point to the centre minus the squared radius; negative when it passes
// through. No root is solved (no sqrt, no division): the segment starts
// spawnRayOrigin's offset outside its own surface, which this resolves
// (the offset is about 30 ulps of |oc|^2).
float segmentClearance(vec3 origin, vec3 direction, float tMax, vec4 sphere) {
  vec3 oc = origin - sphere.xyz;
  float tClosest = clamp(-dot(oc, direction), 0.0, tMax);
  vec3 closest = oc + tClosest * direction;
  return dot(closest, closest) - sphere.w * sphere.w;
}

#if HAS_PLANAR_LIGHTS
// The range of planar lights whose bounding spheres the segment from
// origin to origin + tMax * direction passes through (first,
// last; empty when first > last), found through their groups' spheres
// (render/planarGroups.ts). Only those get the shape's test. A loop costs
// what its longest lane in the quad needs (SwiftShader skips a loop's body
// only when no lane is in it, never a masked if's): here the groups, the
// members of the lane's range of groups, then its range of lights.
// (Ranges rather than bit masks of candidates: the same speed, less code.)
vec2 planarCandidates(vec3 origin, vec3 direction, float tMax) {
  int count = planarLightCount();
  vec2 groups = vec2(1e4, -1.0);
  for (int g = 0; g < (count + PLANAR_GROUP_SIZE - 1) / PLANAR_GROUP_SIZE; g++) {
    bool near = segmentClearance(origin, direction, tMax, planarGroupBound(g)) < 0.0;
    groups = pick(near, vec2(min(groups.x, float(g)), float(g)), groups);
  }
  vec2 range = vec2(1e4, -1.0);
  int last = min(count, (int(groups.y) + 1) * PLANAR_GROUP_SIZE);
  for (int i = int(groups.x) * PLANAR_GROUP_SIZE; i < last; i++) {
    bool near = segmentClearance(origin, direction, tMax, planarLightBound(i)) < 0.0;
    range = pick(near, vec2(min(range.x, float(i)), float(i)), range);
  }
  return range;
}

// Nearest t > 0 where the ray meets the planar light's shape, or INFINITY
// (also for rays parallel to its plane: t is then NaN or infinite, and so
// is the point, which no inside test accepts). Branch-free (see sphereHitT).
float planarHitT(vec3 origin, vec3 direction, PlanarLight l) {
  vec3 n = cross(l.u, l.v);
  float t = dot(l.center - origin, n) / dot(direction, n);
  vec3 d = origin + t * direction - l.center;
  vec2 ab = vec2(dot(d, l.u) / dot(l.u, l.u), dot(d, l.v) / dot(l.v, l.v));
  t = t > 0.0 && planarLightInside(l.kind, ab) ? t : INFINITY;
  return t < INFINITY ? t : INFINITY;
}

// The hit's surface on planar light `i` at distance t: its normal is the
// side it emits to (emitted() counts emission only against the normal).
void planarLightHit(inout Hit hit, vec3 origin, vec3 direction, int i, float t) {
  PlanarLight l = loadPlanarLight(i);
  hit.t = t;
  hit.kind = HIT_PLANAR;
  hit.position = origin + t * direction;
  hit.normal = normalize(cross(l.u, l.v));
  hit.geometricNormal = hit.normal;
  hit.uv = vec2(0.0);
  hit.tangent = vec4(0.0, 0.0, 0.0, 1.0);
  hit.scale = 0.0;
  hit.geometry = vec4(float(i), float(l.kind), 0.0, 0.0);
  hit.material = l.material;
  hit.emitter = l.emitter;
  hit.emitterDensity = 1.0;
}
#endif

Hit intersectScene(vec3 origin, vec3 direction) {
  // The loop keeps only the distance and the sphere's index; the rest of
  // the hit is derived once afterwards.
  float tSphere = INFINITY;
  int sphere = 0;
  for (int i = 0; i < sphereCount(); i++) {
    float t = sphereHitT(origin, direction, sphereGeometry(i));
    sphere = t < tSphere ? i : sphere;
    tSphere = min(t, tSphere);
  }
  float tGround = groundHitT(origin, direction);

  bool isGround = tGround < tSphere;
  Hit hit;
  hit.t = min(tSphere, tGround);
  int surfaceKind = isGround ? HIT_GROUND : HIT_SPHERE;
  hit.kind = hit.t == INFINITY ? HIT_NONE : surfaceKind;

  // Both surfaces are derived and the right one selected (see sphereHitT).
  SphereRecord record = loadSphere(sphere);
  vec4 geometry = sphereGeometry(sphere);
  vec3 p = origin + hit.t * direction;
  vec3 sphereNormal = normalize(p - geometry.xyz);
  vec3 spherePosition = geometry.xyz + geometry.w * sphereNormal;  // re-projected onto the surface
  vec3 groundPosition = vec3(p.x, groundHeight(), p.z);            // exactly on the plane
  hit.normal = isGround ? vec3(0.0, 1.0, 0.0) : sphereNormal;
  hit.position = isGround ? groundPosition : spherePosition;
  hit.scale = pick(isGround, abs(groundHeight()), geometry.w);
  hit.geometry = geometry;
  hit.material = pick(isGround, groundMaterial(), record.material);
  int skyEmitter = environmentEmitter();
  int surfaceEmitter = isGround ? -1 : record.emitter;
  hit.emitter = hit.kind == HIT_NONE ? skyEmitter : surfaceEmitter;
  hit.emitterDensity = 1.0;
  hit.geometricNormal = hit.normal;
  hit.uv = isGround ? groundPosition.xz : vec2(0.0);
  hit.tangent = vec4(isGround ? vec3(1.0, 0.0, 0.0) : vec3(0.0), 1.0);  // the ground: u = x, v = z
#if HAS_VERTEX_COLORS
  hit.color = vec3(1.0);  // planar lights keep it
#endif
#if HAS_PLANAR_LIGHTS
  // As for spheres: the loop keeps the nearest distance and slot only.
  float tPlanar = INFINITY;
  int planar = 0;
  vec2 range = planarCandidates(origin, direction, hit.t);
  for (int i = int(range.x); i <= int(range.y); i++) {
    float t = planarHitT(origin, direction, loadPlanarLight(i));
    planar = t < tPlanar ? i : planar;
    tPlanar = min(t, tPlanar);
  }
  if (tPlanar < hit.t) planarLightHit(hit, origin, direction, planar, tPlanar);
#endif
#if HAS_MESHES
  MeshHit triangle;
  if (meshClosestHit(origin, direction, hit.t, triangle)) {
    BvhSurface s = meshSurface(triangle);
    hit.t = triangle.triangle.t;
    hit.kind = HIT_TRIANGLE;
    hit.position = s.position;
    hit.normal = s.shadingNormal;
    hit.geometricNormal = s.geometricNormal;
    hit.uv = s.uv;
#if HAS_VERTEX_COLORS
    hit.color = s.color;
#endif
#if HAS_NORMAL_MAPS
    // glTF's rule: the bitangent points up the image, also on a mirrored chart.
    hit.tangent = vec4(s.dpdu, dot(cross(s.shadingNormal, s.dpdu), s.dpdv) > 0.0 ? -1.0 : 1.0);
#endif
    hit.scale = 0.0;
    MeshRecord mesh = loadMesh(s.mesh);
    hit.material = mesh.materialBase + s.localMaterial;
    hit.emitter = mesh.emitter;
    hit.emitterDensity = mesh.inverseArea;
  }
#endif
  return hit;
}

// True when something blocks the segment from origin to origin + tMax *
// direction. Every surface blocks, glass included (as in Mitsuba's path
// tracer: light through glass is found by BSDF sampling only). `skipSphere`
// is the sphere the segment ends on (-1: none).
bool occluded(vec3 origin, vec3 direction, float tMax, int skipSphere) {
  float clearance = INFINITY;
  for (int i = 0; i < sphereCount(); i++) {
    float c = segmentClearance(origin, direction, tMax, sphereGeometry(i));
    clearance = min(clearance, i == skipSphere ? INFINITY : c);
  }
  bool blocked = clearance < 0.0 || groundHitT(origin, direction) < tMax;
#if HAS_PLANAR_LIGHTS
  vec2 range = planarCandidates(origin, direction, tMax);
  for (int i = int(range.x); i <= int(range.y); i++) blocked = blocked || planarHitT(origin, direction, loadPlanarLight(i)) < tMax;
#endif
#if HAS_MESHES
  blocked = blocked || meshAnyHit(origin, direction, tMax);
#endif
  return blocked;
}

// Origin for a ray leaving `hit` into the side of `side` (a direction).
vec3 spawnRayOrigin(Hit hit, vec3 side) {
  vec3 n = pick(dot(side, hit.geometricNormal) >= 0.0, hit.geometricNormal, -hit.geometricNormal);
  float offset = 4e-6 * (maxComponent(abs(hit.position)) + hit.scale) + 1e-6;
  return hit.position + n * offset;
}
