// What next-event estimation gets from a light (lights/lights.glsl's
// sampleLight, and each light kind's <type>LightSample: src/lights/kind.ts).

struct LightSample {
  vec3 direction;   // world, unit, from x towards the emitter
  float distance;   // to the emitter along `direction` (INFINITY: unbounded)
  vec3 radiance;    // arriving at x (a delta light: its intensity / d^2 or its irradiance)
  float pdf;        // solid angle at x, emitter choice included; 0 = no sample; a delta light: the choice alone
  int skipSphere;   // the sphere the shadow ray ends on (-1: none)
  bool delta;       // a Dirac delta (the delta kinds): no MIS, BSDF sampling never finds it
};

// A Dirac delta at `position` seen from x: intensity I gives I / d^2 at distance d
// (the point light; the spot multiplies in its falloff).
LightSample positionLightSample(vec3 position, vec3 intensity, vec3 x) {
  LightSample s;
  vec3 toLight = position - x;
  float d2 = dot(toLight, toLight);
  s.distance = sqrt(d2);
  s.direction = toLight / s.distance;
  s.radiance = intensity / d2;
  s.pdf = d2 > 0.0 ? 1.0 : 0.0;
  s.skipSphere = -1;
  s.delta = true;
  return s;
}
