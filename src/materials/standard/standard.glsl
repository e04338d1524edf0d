// The standard material (scene format version 1):
//   f = (1 - r) * Specular + r * Lambert, both tinted by color,
//   Specular = GGX microfacet mirror, alpha = r^2, separable Smith G, no Fresnel.
// One-sided, as in Mitsuba: seen from below its surface (wo.z <= 0) it
// reflects nothing. The lobes are chosen with probabilities (1 - r) and r;
// the pdf of a direction is the mixture of both lobes' pdfs.
//
// Below DELTA_ALPHA the GGX lobe is treated as an ideal mirror (as pbrt-v4
// does): its peak is then far narrower than a pixel's footprint, and the
// mirror is exact instead of a badly conditioned huge-D/tiny-pdf pair.

float standardAlpha(StandardParams m) { return m.roughness * m.roughness; }
// The specular lobe is an ideal mirror (and light sampling still sees the diffuse one).
bool standardHasDeltaLobe(StandardParams m) { return standardAlpha(m) < DELTA_ALPHA; }

// f(wo, wi) * cos(wi) of the non-delta lobes; `pdf` receives their mixture
// density of sampling wi.
vec3 standardEval(Bsdf b, vec3 wo, vec3 wi, out float pdf) {
  StandardParams m = standardParams(b);
  pdf = 0.0;
  if (wo.z <= 0.0 || wi.z <= 0.0) return vec3(0.0);
  float r = m.roughness;
  vec3 f = m.color * (r * INV_PI * wi.z);
  pdf = r * INV_PI * wi.z;
  if (r < 1.0 && !standardHasDeltaLobe(m)) {
    float alpha = standardAlpha(m);
    vec3 h = normalize(wo + wi);
    float d = ggxD(h, alpha);
    float g1o = ggxG1(wo, alpha);
    // D G1(wo) G1(wi) / (4 cos wo cos wi), times cos wi.
    f += m.color * ((1.0 - r) * d * g1o * ggxG1(wi, alpha) / (4.0 * wo.z));
    pdf += (1.0 - r) * g1o * d / (4.0 * wo.z);
  }
  return f;
}

// Draws a direction from the lobe mixture (u.z picks the lobe, u.x the
// radius and `circle` = unitCircle(u.y) the angle of a point on the disk).
// For the ideal mirror, `isDelta` is set and `deltaWeight` = f cos / pdf
// (the (1 - r) of the lobe cancels its choice).
vec3 standardSampleDirection(Bsdf b, vec3 wo, vec3 u, vec2 circle, out bool isDelta, out vec3 deltaWeight) {
  StandardParams m = standardParams(b);
  bool chooseSpecular = u.z >= m.roughness;
  isDelta = chooseSpecular && standardHasDeltaLobe(m);
  deltaWeight = m.color;
  // One polar disk point serves both lobes (one sin/cos pair per bounce):
  // projected up it is cosine-distributed, warped it is a visible normal.
  float r2 = u.x;
  vec2 disk = sqrt(r2) * circle;
  vec3 h = pick(isDelta, vec3(0.0, 0.0, 1.0), sampleGgxVisibleNormal(wo, standardAlpha(m), disk));
  vec3 wi = pick(chooseSpecular, reflect(-wo, h), vec3(disk, sqrt(1.0 - r2)));
  return wo.z > 0.0 ? wi : vec3(0.0);
}

// Light sampling can contribute where some lobe is not a Dirac delta.
bool standardHasNonDeltaLobe(Bsdf b) { return standardParams(b).roughness > 0.0; }
// A mirror for the guide buffers: its specular lobe is a delta (the diffuse
// weight r < sqrt(DELTA_ALPHA) that it may still have is neglected there).
bool standardIsDelta(Bsdf b) { return standardHasDeltaLobe(standardParams(b)); }
// The guide buffers: a mirror's tint, a surface's color.
vec3 standardDeltaTint(Bsdf b, vec3 wo, vec3 wi) { return standardParams(b).color; }
vec3 standardAlbedo(Bsdf b) { return standardParams(b).color; }
// The caustic guides may take over the diffuse weight's share of "BSDF
// sampling" (a glossy lobe already concentrates its samples; an ideal
// mirror is not guided at all).
float standardGuideWeight(Bsdf b) { return standardParams(b).roughness; }
