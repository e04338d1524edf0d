// The light interface: every emitter (the `lights` of every kind,
// src/lights/; emissive spheres, the environment map, emissive meshes)
// sits in one table and is picked in proportion to its power (an alias
// table, src/render/aliasTable.ts). The integrator calls
// sampleLight and lightPdf and never knows which kind of emitter it holds.

// u: .xy the point on the emitter, .z the choice of emitter.
LightSample sampleLight(vec3 x, vec3 u) {
  int count = emitterCount();
  float scaled = u.z * float(count);
  int slot = clamp(int(scaled), 0, max(count - 1, 0));
  EmitterChoice choice = loadEmitterChoice(slot);
  float f = scaled - float(slot);
  bool keep = f < choice.aliasThreshold;
  Emitter e = loadEmitter(keep ? slot : choice.alias);
  // The sphere is the default kind (every program has it); the others override its sample.
  LightSample s = sphereLightSample(e, x, u.xy);
#if HAS_ENV_MAP
  if (e.kind == EMITTER_ENVIRONMENT) {
    s.direction = sampleEnvironment(u.xy, s.pdf);
    s.distance = INFINITY;
    s.radiance = environmentRadiance(s.direction);
    s.skipSphere = -1;
  }
#endif
#if HAS_EMISSIVE_MESHES
  if (e.kind == EMITTER_MESH) {
    // What is left of u.z after the alias draw, uniform again, picks the triangle.
    float rest = pick(keep, f / choice.aliasThreshold, (f - choice.aliasThreshold) / max(1.0 - choice.aliasThreshold, 1e-30));
    s.direction = sampleMeshEmitter(x, e, vec3(u.xy, min(rest, 0.99999994)), s.pdf, s.distance, s.radiance);
    // The shadow ray stops short of the triangle it aims at.
    s.distance *= 0.9999;
    s.skipSphere = -1;
  }
#endif
  sampleLightKind(e, x, u.xy, s);
  s.pdf = pick(count > 0, e.pdf * s.pdf, 0.0);
  return s;
}

// Density of sampleLight drawing, from x, the direction towards `hit`
// (`direction`, unit, from x).
float lightPdf(vec3 x, vec3 direction, Hit hit) {
  float pdf = pick(hit.kind == HIT_SPHERE, hit.emitterPdf * sphereEmitterPdf(x, hit.geometry), 0.0);
#if HAS_ENV_MAP
  pdf = pick(hit.kind == HIT_NONE, environmentEmitterPdf() * environmentPdf(direction), pdf);
#endif
#if HAS_EMISSIVE_MESHES
  pdf = pick(hit.kind == HIT_TRIANGLE, meshEmitterPdf(direction, hit), pdf);
#endif
#if HAS_PLANAR_LIGHTS
  pdf = pick(hit.kind == HIT_PLANAR, planarLightPdf(x, direction, hit), pdf);
#endif
  return pdf;
}

// Radiance arriving along `direction` from an escaped ray: the map, or the
// constant sky (which light sampling never picks: weighted 1 by emitted()).
vec3 escapedRadiance(vec3 direction) {
#if HAS_ENV_MAP
  return environmentRadiance(direction);
#else
  return constantEnvironment();
#endif
}
