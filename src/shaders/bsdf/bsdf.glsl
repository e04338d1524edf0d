// The BSDF interface, built on the generated dispatch (bsdfEval,
// bsdfSampleDirection, bsdfHasNonDeltaLobe, bsdfIsDelta, bsdfDeltaTint,
// bsdfAlbedo, bsdfGuideWeight: generated/bsdf_dispatch.glsl from
// src/materials/registry.ts; each kind's functions in src/materials/<kind>/).
// Directions are in the local shading frame (+z = the normal on the
// outside of the surface; wo = towards the viewer, possibly below for
// two-sided materials).

struct BsdfSample {
  vec3 wi;
  vec3 weight;    // f * |cos| / pdf
  float pdf;      // 0 for a Dirac delta lobe
  bool isDelta;
  bool valid;
};

BsdfSample bsdfSample(Bsdf b, vec3 wo, vec3 u, vec2 circle) {
  BsdfSample s;
  vec3 deltaWeight;
  s.wi = bsdfSampleDirection(b, wo, u, circle, s.isDelta, deltaWeight);
  vec3 f = bsdfEval(b, wo, s.wi, s.pdf);
  s.pdf = s.isDelta ? 0.0 : s.pdf;
  s.weight = pick(s.isDelta, deltaWeight, f / s.pdf);
  s.valid = s.wi != vec3(0.0) && (s.isDelta || (s.pdf > 0.0 && f != vec3(0.0)));
  return s;
}

BsdfSample bsdfSample(Bsdf b, vec3 wo, vec3 u) {
  return bsdfSample(b, wo, u, unitCircle(u.y));
}

// Whether paths continue from this material (emitter-only surfaces, the
// `lights`, reflect nothing).
bool bsdfScatters(Material m) { return materialType(m) != MATERIAL_EMITTER_ONLY; }
