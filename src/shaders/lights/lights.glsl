// The light interface: every emitter (the `lights` of every kind,
// src/lights/; emissive spheres, the environment map, emissive meshes)
// sits in one table. Next-event estimation picks one by where the shading
// point is: the grid cell holding it has its own alias table, weighed by
// the irradiance each emitter can give there (render/lightChoice.ts);
// outside the grid, the global table picks by power. The integrator calls
// sampleLight and lightPdf and never knows which kind of emitter it holds.
//
// uLightChoice: RGBA32F, LIGHT_CHOICE_WIDTH wide; entry i of table t at
// texel t * emitterCount() + i: (alias threshold, alias, probability of
// emitter i, probability of the alias), both in table t.

uniform highp sampler2D uLightChoice;

vec4 lightChoiceTexel(int i) {
  return texelFetch(uLightChoice, ivec2(i & (LIGHT_CHOICE_WIDTH - 1), i >> LIGHT_CHOICE_WIDTH_LOG2), 0);
}

// The table of the grid cell holding x, or the global one.
int lightChoiceTable(vec3 x) {
  Header h = readHeader(0);
  vec3 g = (x - h.lightChoiceOrigin) * h.lightChoiceScale;
  bool inside = all(greaterThanEqual(g, vec3(0.0))) && all(lessThan(g, h.lightChoiceCells));
  ivec3 c = ivec3(clamp(g, vec3(0.0), max(h.lightChoiceCells - 1.0, vec3(0.0))));
  ivec3 cells = ivec3(h.lightChoiceCells);
  int cell = c.x + cells.x * (c.y + cells.y * c.z);
  return inside ? cell : h.lightChoiceGlobal;
}

// The probability that sampleLight, at x, picks emitter `emitter` (0 for -1: not an emitter).
float lightChoicePdf(vec3 x, int emitter) {
  float p = lightChoiceTexel(lightChoiceTable(x) * emitterCount() + max(emitter, 0)).z;
  return emitter >= 0 ? p : 0.0;
}

// u: .xy the point on the emitter, .z the choice of emitter.
LightSample sampleLight(vec3 x, vec3 u) {
  int count = emitterCount();
  float scaled = u.z * float(count);
  int slot = clamp(int(scaled), 0, max(count - 1, 0));
  vec4 entry = lightChoiceTexel(lightChoiceTable(x) * count + slot);
  float f = scaled - float(slot);
  bool keep = f < entry.x;
  int alias = int(entry.y);
  int chosen = keep ? slot : alias;
  float choicePdf = keep ? entry.z : entry.w;
  Emitter e = loadEmitter(chosen);
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
    float rest = pick(keep, f / entry.x, (f - entry.x) / max(1.0 - entry.x, 1e-30));
    s.direction = sampleMeshEmitter(x, e, vec3(u.xy, min(rest, 0.99999994)), s.pdf, s.distance, s.radiance);
    // The shadow ray stops short of the triangle it aims at.
    s.distance *= 0.9999;
    s.skipSphere = -1;
  }
#endif
  sampleLightKind(e, x, u.xy, s);
  s.pdf = pick(count > 0, choicePdf * s.pdf, 0.0);
  return s;
}

// Density of sampleLight drawing, from x, the direction towards `hit`
// (`direction`, unit, from x): the choice of its emitter at x times the
// density of the emitter's own sample.
float lightPdf(vec3 x, vec3 direction, Hit hit) {
  float pdf = pick(hit.kind == HIT_SPHERE, sphereEmitterPdf(x, hit.geometry), 0.0);
#if HAS_ENV_MAP
  pdf = pick(hit.kind == HIT_NONE, environmentPdf(direction), pdf);
#endif
#if HAS_EMISSIVE_MESHES
  pdf = pick(hit.kind == HIT_TRIANGLE, meshEmitterPdf(direction, hit), pdf);
#endif
#if HAS_PLANAR_LIGHTS
  pdf = pick(hit.kind == HIT_PLANAR, planarLightPdf(x, direction, hit), pdf);
#endif
  return lightChoicePdf(x, hit.emitter) * pdf;
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
