// The material model of the scene format:
//   f = (1 - r) * Specular + r * Lambert, both tinted by color,
//   Specular = GGX conductor, alpha = r^2, separable Smith G, no Fresnel.
// All directions are in the local shading frame (+z = normal, wo = towards
// the viewer). The lobes are chosen with probabilities (1 - r) and r; the
// pdf of a direction is the mixture of both lobes' pdfs.

// Below SMOOTH_ALPHA (src/render/layout.ts) the GGX lobe is treated as an ideal mirror (as pbrt-v4
// does): its peak is then far narrower than a pixel's footprint, and the
// mirror is exact instead of a badly conditioned huge-D/tiny-pdf pair.

float specularAlpha(Material m) { return m.roughness * m.roughness; }
bool specularIsDelta(Material m) { return specularAlpha(m) < SMOOTH_ALPHA; }
// Whether light sampling can contribute: some lobe is not a Dirac delta.
bool hasSmoothLobe(Material m) { return m.roughness > 0.0; }

// Returns f(wo, wi) * cos(wi) of the non-delta lobes; `pdf` receives their
// mixture density of sampling wi.
vec3 evalMaterial(Material m, vec3 wo, vec3 wi, out float pdf) {
  pdf = 0.0;
  if (wo.z <= 0.0 || wi.z <= 0.0) return vec3(0.0);
  float r = m.roughness;
  vec3 f = m.color * (r * INV_PI * wi.z);
  pdf = r * INV_PI * wi.z;
  if (r < 1.0 && !specularIsDelta(m)) {
    float alpha = specularAlpha(m);
    vec3 h = normalize(wo + wi);
    float d = ggxD(h, alpha);
    float g1o = ggxG1(wo, alpha);
    // D G1(wo) G1(wi) / (4 cos wo cos wi), times cos wi.
    f += m.color * ((1.0 - r) * d * g1o * ggxG1(wi, alpha) / (4.0 * wo.z));
    pdf += (1.0 - r) * g1o * d / (4.0 * wo.z);
  }
  return f;
}

struct BsdfSample {
  vec3 wi;
  vec3 weight;    // f * cos / pdf
  float pdf;      // mixture pdf (0 for a delta lobe)
  bool isDelta;
  bool valid;
};

// Draws a direction from the lobe mixture (u.z picks the lobe, u.x the
// radius and `circle` = unitCircle(u.y) the angle of a point on the disk);
// `isDelta` tells that the ideal mirror was picked.
vec3 sampleMaterialDirection(Material m, vec3 wo, vec3 u, vec2 circle, out bool isDelta) {
  bool chooseSpecular = u.z >= m.roughness;
  isDelta = chooseSpecular && specularIsDelta(m);
  // One polar disk point serves both lobes (one sin/cos pair per bounce):
  // projected up it is cosine-distributed, warped it is a visible normal.
  float r2 = u.x;
  vec2 disk = sqrt(r2) * circle;
  vec3 h = isDelta ? vec3(0.0, 0.0, 1.0) : sampleGgxVisibleNormal(wo, specularAlpha(m), disk);
  return chooseSpecular ? reflect(-wo, h) : vec3(disk, sqrt(1.0 - r2));
}

vec3 sampleMaterialDirection(Material m, vec3 wo, vec3 u, out bool isDelta) {
  return sampleMaterialDirection(m, wo, u, unitCircle(u.y), isDelta);
}

BsdfSample sampleMaterial(Material m, vec3 wo, vec3 u) {
  BsdfSample s = BsdfSample(vec3(0.0), vec3(0.0), 0.0, false, false);
  if (wo.z <= 0.0) return s;
  s.wi = sampleMaterialDirection(m, wo, u, s.isDelta);
  if (s.isDelta) {
    // Ideal mirror: weight = (1 - r) color / (1 - r).
    s.weight = m.color;
    s.valid = true;
    return s;
  }
  vec3 f = evalMaterial(m, wo, s.wi, s.pdf);
  if (s.pdf <= 0.0) return s;
  s.weight = f / s.pdf;
  s.valid = true;
  return s;
}
