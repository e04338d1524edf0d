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

// Nearest t in (0, tMax) where the ray (unit direction) meets the sphere, or
// INFINITY. Computes the discriminant from the ray's closest approach to the
// centre (Haines et al., Ray Tracing Gems ch. 7) to stay accurate for large
// radii and distant spheres.
float intersectSphere(vec3 origin, vec3 direction, vec4 sphere, float tMax) {
  vec3 oc = origin - sphere.xyz;
  float b = dot(oc, direction);
  vec3 closest = oc - b * direction;
  float h = sphere.w * sphere.w - dot(closest, closest);
  if (h < 0.0) return INFINITY;
  h = sqrt(h);
  // Near root without cancellation: -b - sign(b) h and c / that.
  float q = -b - (b >= 0.0 ? h : -h);
  float c = dot(oc, oc) - sphere.w * sphere.w;
  float t0 = q;
  float t1 = q != 0.0 ? c / q : 0.0;
  float tNear = min(t0, t1);
  float tFar = max(t0, t1);
  float t = tNear > 0.0 ? tNear : tFar;
  return (t > 0.0 && t < tMax) ? t : INFINITY;
}

float intersectGround(vec3 origin, vec3 direction, float tMax) {
  if (!groundEnabled() || direction.y == 0.0) return INFINITY;
  float t = (groundHeight() - origin.y) / direction.y;
  return (t > 0.0 && t < tMax) ? t : INFINITY;
}

Hit intersectScene(vec3 origin, vec3 direction) {
  Hit hit;
  hit.t = INFINITY;
  hit.kind = HIT_NONE;
  hit.index = -1;
  for (int i = 0; i < sphereCount(); i++) {
    float t = intersectSphere(origin, direction, sphereGeometry(i), hit.t);
    if (t < hit.t) { hit.t = t; hit.kind = HIT_SPHERE; hit.index = i; }
  }
  for (int i = 0; i < lightCount(); i++) {
    float t = intersectSphere(origin, direction, lightGeometry(i), hit.t);
    if (t < hit.t) { hit.t = t; hit.kind = HIT_LIGHT; hit.index = i; }
  }
  float tGround = intersectGround(origin, direction, hit.t);
  if (tGround < hit.t) { hit.t = tGround; hit.kind = HIT_GROUND; }

  if (hit.kind == HIT_GROUND) {
    hit.position = origin + hit.t * direction;
    hit.position.y = groundHeight();  // exactly on the plane
    hit.normal = vec3(0.0, 1.0, 0.0);
    hit.scale = abs(groundHeight());
  } else if (hit.kind != HIT_NONE) {
    vec4 sphere = hit.kind == HIT_SPHERE ? sphereGeometry(hit.index) : lightGeometry(hit.index);
    vec3 p = origin + hit.t * direction;
    hit.normal = normalize(p - sphere.xyz);
    hit.position = sphere.xyz + sphere.w * hit.normal;  // re-project onto the surface
    hit.scale = sphere.w;
  }
  return hit;
}

// True when something blocks the segment from origin to origin + tMax * direction.
// `skipLight` is the light the segment ends on.
bool occluded(vec3 origin, vec3 direction, float tMax, int skipLight) {
  for (int i = 0; i < sphereCount(); i++) {
    if (intersectSphere(origin, direction, sphereGeometry(i), tMax) < tMax) return true;
  }
  for (int i = 0; i < lightCount(); i++) {
    if (i != skipLight && intersectSphere(origin, direction, lightGeometry(i), tMax) < tMax) return true;
  }
  return intersectGround(origin, direction, tMax) < tMax;
}

// Origin for a ray leaving `hit` into the side of `side` (a direction).
vec3 spawnRayOrigin(Hit hit, vec3 side) {
  vec3 n = dot(side, hit.normal) >= 0.0 ? hit.normal : -hit.normal;
  float offset = 4e-6 * (maxComponent(abs(hit.position)) + hit.scale) + 1e-6;
  return hit.position + n * offset;
}
