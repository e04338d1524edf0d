const int HIT_NONE = 0;
const int HIT_SPHERE = 1;
const int HIT_GROUND = 2;
const int HIT_LIGHT = 3;

struct Hit {
  float t;
  int kind;
  int index;      // sphere or light index
  vec3 position;
  vec3 normal;    // outward geometric normal of the surface
  float scale;    // size of the hit object, for the self-intersection offset
};

// Nearest t > 0 where the ray (unit direction) meets the sphere, or a value
// <= 0 (no hit). Branch-free: SwiftShader runs both sides of every branch.
// Computes the discriminant from the ray's closest approach to the centre
// (Haines et al., Ray Tracing Gems ch. 7) to stay accurate for large radii
// and distant spheres; the near root without cancellation: q = -b - sign(b) h
// and c / q.
float sphereHitT(vec3 origin, vec3 direction, vec4 sphere) {
  vec3 oc = origin - sphere.xyz;
  float b = dot(oc, direction);
  vec3 closest = oc - b * direction;
  float r2 = sphere.w * sphere.w;
  float h = r2 - dot(closest, closest);
  float s = sqrt(max(h, 0.0));
  float q = -b - (b >= 0.0 ? s : -s);
  float c = dot(oc, oc) - r2;
  float t1 = q != 0.0 ? c / q : 0.0;
  float tNear = min(q, t1);
  float tFar = max(q, t1);
  float t = tNear > 0.0 ? tNear : tFar;
  return h >= 0.0 ? t : -1.0;
}

// Nearest t in (0, tMax) where the ray (unit direction) meets the sphere, or INFINITY.
float intersectSphere(vec3 origin, vec3 direction, vec4 sphere, float tMax) {
  float t = sphereHitT(origin, direction, sphere);
  return (t > 0.0 && t < tMax) ? t : INFINITY;
}

float intersectGround(vec3 origin, vec3 direction, float tMax) {
  if (!groundEnabled() || direction.y == 0.0) return INFINITY;
  float t = (groundHeight() - origin.y) / direction.y;
  return (t > 0.0 && t < tMax) ? t : INFINITY;
}

Hit intersectScene(vec3 origin, vec3 direction) {
  // The loops keep only the distance and the object's index; the rest of
  // the hit is derived once afterwards.
  float tMin = INFINITY;
  int sphere = -1;
  for (int i = 0; i < sphereCount(); i++) {
    float t = sphereHitT(origin, direction, sphereGeometry(i));
    bool closer = t > 0.0 && t < tMin;
    tMin = closer ? t : tMin;
    sphere = closer ? i : sphere;
  }
  int light = -1;
  for (int i = 0; i < lightCount(); i++) {
    float t = sphereHitT(origin, direction, lightGeometry(i));
    bool closer = t > 0.0 && t < tMin;
    tMin = closer ? t : tMin;
    light = closer ? i : light;
  }
  float tGround = intersectGround(origin, direction, tMin);
  Hit hit;
  hit.t = min(tMin, tGround);
  hit.kind = tGround < tMin ? HIT_GROUND : light >= 0 ? HIT_LIGHT : sphere >= 0 ? HIT_SPHERE : HIT_NONE;
  hit.index = light >= 0 ? light : sphere;

  if (hit.kind == HIT_GROUND) {
    hit.position = origin + hit.t * direction;
    hit.position.y = groundHeight();  // exactly on the plane
    hit.normal = vec3(0.0, 1.0, 0.0);
    hit.scale = abs(groundHeight());
  } else if (hit.kind != HIT_NONE) {
    vec4 geometry = hit.kind == HIT_SPHERE ? sphereGeometry(hit.index) : lightGeometry(hit.index);
    vec3 p = origin + hit.t * direction;
    hit.normal = normalize(p - geometry.xyz);
    hit.position = geometry.xyz + geometry.w * hit.normal;  // re-project onto the surface
    hit.scale = geometry.w;
  }
  return hit;
}

// True when something blocks the segment from origin to origin + tMax * direction.
// `skipLight` is the light the segment ends on.
bool occluded(vec3 origin, vec3 direction, float tMax, int skipLight) {
  bool blocked = false;
  for (int i = 0; i < sphereCount(); i++) {
    float t = sphereHitT(origin, direction, sphereGeometry(i));
    blocked = blocked || (t > 0.0 && t < tMax);
  }
  for (int i = 0; i < lightCount(); i++) {
    float t = sphereHitT(origin, direction, lightGeometry(i));
    blocked = blocked || (i != skipLight && t > 0.0 && t < tMax);
  }
  return blocked || intersectGround(origin, direction, tMax) < tMax;
}

// Origin for a ray leaving `hit` into the side of `side` (a direction).
vec3 spawnRayOrigin(Hit hit, vec3 side) {
  vec3 n = dot(side, hit.normal) >= 0.0 ? hit.normal : -hit.normal;
  float offset = 4e-6 * (maxComponent(abs(hit.position)) + hit.scale) + 1e-6;
  return hit.position + n * offset;
}
