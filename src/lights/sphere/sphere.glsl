// Spheres as emitters: sampled uniformly inside the cone they subtend
// (solid-angle pdf), which is exact for every point outside the sphere.

struct LightCone {
  vec3 axis;              // unit vector towards the sphere's centre
  float oneMinusCosMax;   // 1 - cos of the cone's half angle; 0 = not visible
};

LightCone lightCone(vec3 x, vec4 sphere) {
  vec3 toCenter = sphere.xyz - x;
  float dist2 = dot(toCenter, toCenter);
  float r2 = sphere.w * sphere.w;
  // Inside (or on) the sphere: it emits outwards only, so it is invisible.
  if (dist2 <= r2) return LightCone(vec3(0.0, 0.0, 1.0), 0.0);
  float sin2Max = r2 / dist2;
  // 1 - sqrt(1 - s) without cancellation for small s.
  return LightCone(toCenter * inversesqrt(dist2), sin2Max / (1.0 + sqrt(1.0 - sin2Max)));
}

// Density, in solid angle at x, of a direction drawn towards the sphere.
float sphereEmitterPdf(vec3 x, vec4 sphere) {
  LightCone cone = lightCone(x, sphere);
  return pick(cone.oneMinusCosMax > 0.0, uniformConePdf(cone.oneMinusCosMax), 0.0);
}

// A direction from x towards the sphere (u: .x polar, .y azimuth), its
// density and the distance to the sphere along it.
vec3 sampleSphereEmitter(vec3 x, vec4 sphere, vec2 u, out float pdf, out float distance) {
  LightCone cone = lightCone(x, sphere);
  float oneMinusCos = u.x * cone.oneMinusCosMax;
  vec3 wi = basisAround(cone.axis) * sampleUniformCone(u, cone.oneMinusCosMax);
  pdf = pick(cone.oneMinusCosMax > 0.0, uniformConePdf(cone.oneMinusCosMax), 0.0);
  // Where the direction meets the sphere, from the cone's geometry:
  // t = d cos - sqrt(r^2 - d^2 sin^2) (a rim direction that misses by
  // rounding ends at the tangent point).
  vec3 toCenter = sphere.xyz - x;
  float dist2 = dot(toCenter, toCenter);
  float cosTheta = 1.0 - oneMinusCos;
  float sin2Theta = oneMinusCos * (2.0 - oneMinusCos);
  distance = sqrt(dist2) * cosTheta - sqrt(max(0.0, sphere.w * sphere.w - dist2 * sin2Theta));
  return wi;
}

// The light interface of a sphere emitter (a sphere light or an emissive
// sphere; see src/lights/kind.ts): the shadow ray ends on the sphere itself.
LightSample sphereLightSample(Emitter e, vec3 x, vec2 u) {
  SphereLight p = sphereLight(e);
  LightSample s;
  s.direction = sampleSphereEmitter(x, vec4(p.center, p.radius), u, s.pdf, s.distance);
  s.radiance = e.radiance;
  s.skipSphere = e.primitive;
  s.delta = false;
  return s;
}
