// The BSDF interface: one dispatch on the material type each. Directions
// are in the local shading frame (+z = the normal on the outside of the
// surface; wo = towards the viewer, possibly below for two-sided materials).
//
// Code of a material type that the scene does not use is compiled out
// (HAS_DIELECTRIC): SwiftShader runs every branch of a switch under lane
// masks, so unused types would still cost their full price. The program
// variants are chosen per scene (src/render/passes/trace.ts).

struct BsdfSample {
  vec3 wi;
  vec3 weight;    // f * |cos| / pdf
  float pdf;      // 0 for a Dirac delta lobe
  bool isDelta;
  bool valid;
};

// f(wo, wi) |cos wi| of the non-delta lobes; `pdf` receives the density of
// bsdfSampleDirection drawing wi.
vec3 bsdfEval(Material m, vec3 wo, vec3 wi, out float pdf) {
#if HAS_DIELECTRIC
  if (m.type == MATERIAL_DIELECTRIC) return dielectricEval(m, wo, wi, pdf);
#endif
  return standardEval(m, wo, wi, pdf);
}

float bsdfPdf(Material m, vec3 wo, vec3 wi) {
  float pdf;
  bsdfEval(m, wo, wi, pdf);
  return pdf;
}

// Draws a direction (u.z picks a lobe; u.x and `circle` = unitCircle(u.y)
// a point on the disk, shared with the caustic guides' cone); a Dirac delta
// sets `isDelta` and its weight f |cos| / pdf. The zero vector: no sample.
vec3 bsdfSampleDirection(Material m, vec3 wo, vec3 u, vec2 circle, out bool isDelta, out vec3 deltaWeight) {
#if HAS_DIELECTRIC
  if (m.type == MATERIAL_DIELECTRIC) return dielectricSampleDirection(m, wo, u, circle, isDelta, deltaWeight);
#endif
  return standardSampleDirection(m, wo, u, circle, isDelta, deltaWeight);
}

BsdfSample bsdfSample(Material m, vec3 wo, vec3 u, vec2 circle) {
  BsdfSample s;
  vec3 deltaWeight;
  s.wi = bsdfSampleDirection(m, wo, u, circle, s.isDelta, deltaWeight);
  vec3 f = bsdfEval(m, wo, s.wi, s.pdf);
  s.pdf = s.isDelta ? 0.0 : s.pdf;
  s.weight = s.isDelta ? deltaWeight : f / s.pdf;
  s.valid = s.wi != vec3(0.0) && (s.isDelta || (s.pdf > 0.0 && f != vec3(0.0)));
  return s;
}

BsdfSample bsdfSample(Material m, vec3 wo, vec3 u) {
  return bsdfSample(m, wo, u, unitCircle(u.y));
}

// Whether light sampling can contribute: some lobe is not a Dirac delta.
bool bsdfHasNonDeltaLobe(Material m) {
#if HAS_DIELECTRIC
  if (m.type == MATERIAL_DIELECTRIC) return dielectricHasNonDeltaLobe(m);
#endif
  return m.type == MATERIAL_STANDARD && standardHasNonDeltaLobe(m);
}

// Whether paths continue from this material (emitter-only surfaces, the
// `lights`, reflect nothing).
bool bsdfScatters(Material m) { return m.type != MATERIAL_EMITTER_ONLY; }

// How much the caustic guides may take over "BSDF sampling" here: the
// diffuse weight of a standard material (a glossy lobe already concentrates
// its samples; an ideal mirror is not guided at all), nothing for glass.
float bsdfGuideWeight(Material m) { return m.type == MATERIAL_STANDARD ? m.roughness : 0.0; }
