// What next-event estimation gets from a light (lights/lights.glsl's
// sampleLight, and each light kind's <type>LightSample: src/lights/kind.ts).

struct LightSample {
  vec3 direction;   // world, unit, from x towards the emitter
  float distance;   // to the emitter along `direction` (INFINITY: unbounded)
  vec3 radiance;    // arriving at x (a delta light: its intensity / d^2 or its irradiance)
  float pdf;        // solid angle at x, emitter choice included; 0 = no sample; a delta light: the choice alone
  int skipSphere;   // the sphere the shadow ray ends on (-1: none)
  bool delta;       // a Dirac delta (point, spot, directional): no MIS, BSDF sampling never finds it
};
