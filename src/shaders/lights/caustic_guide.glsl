// Caustic guiding: light that reaches a rough surface through an ideal
// mirror sphere (a caustic) can only be found by BSDF sampling, which hits
// the light's small reflected image rarely and then with a large weight:
// fireflies. So at each rough vertex, "BSDF sampling" becomes a mixture:
// with probability GUIDE_PROBABILITY a direction is drawn uniformly in a cone
// around the mirror point that reflects the light towards the vertex, sized
// to cover the light's image in the convex mirror; otherwise the BSDF is
// sampled as usual. Every sample is weighted by the mixture's exact pdf, and
// the same pdf enters the MIS weights, so the estimate stays unbiased
// whatever the cone (a poor cone only wastes samples). The mixture is built
// on the BSDF interface (bsdfSampleDirection, bsdfEval): no lobe weight is
// written here. The (mirror, emitting sphere) pairs are chosen on the CPU
// per scene upload (src/render/causticGuides.ts).
//
// CAUSTIC_GUIDES (0, 1 or 2) is the number of guides compiled in: one
// program per count (src/render/passes/trace.ts), because SwiftShader executes
// every line of a shader whatever the branches, so an unused cone would
// still cost its full construction at every vertex.

#if CAUSTIC_GUIDES > 0

// The guides of the current vertex, as globals and named cones rather than
// an array: SwiftShader copies arrays passed by value and indexes local
// arrays slowly. xyz = unit axis, w = 1 - cos(half angle).
vec4 guideCone0;
#if CAUSTIC_GUIDES > 1
vec4 guideCone1;
#endif
float guideProbability;  // of drawing from the cones at this vertex

// The cone towards the light's image in mirror `guide` as seen from x; the
// hemisphere around n when there is no sensible image (x or the light inside
// the mirror), which keeps the mixture a valid density everywhere.
vec4 guideCone(vec3 x, vec3 n, int guide) {
  vec4 mirror = uGuides[guide * GUIDE_VEC4S + GUIDE_MIRROR];
  vec4 light = uGuides[guide * GUIDE_VEC4S + GUIDE_LIGHT];
  vec3 toX = x - mirror.xyz;
  vec3 toLight = light.xyz - mirror.xyz;
  float distX = length(toX);
  float distLight = length(toLight);
  bool sensible = distX > mirror.w * 1.0001 && distLight > mirror.w + light.w;
  // Reflection point: its normal bisects the directions to x and the light;
  // one fixed-point step from the bisector seen from the centre.
  vec3 h = normalize(toX / distX + toLight / distLight);
  vec3 p = mirror.xyz + mirror.w * h;
  h = normalize(normalize(x - p) + normalize(light.xyz - p));
  p = mirror.xyz + mirror.w * h;
  vec3 toP = p - x;
  float dx = length(toP);
  float dl = length(light.xyz - p);
  // Paraxial convex mirror (focal length R / 2, sagittal R / (2 cos i) off
  // axis, the larger extent): the light's image and its depth behind p.
  float cosI = max(0.05, dot(h, -toP / dx));
  float focal = 0.5 * mirror.w / cosI;
  float image = light.w * focal / (dl + focal);
  float depth = dl * focal / (dl + focal);
  float s = clamp(GUIDE_MARGIN * image / (dx + depth), 3e-3, 0.5);
  float s2 = s * s;
  return pick(sensible, vec4(toP / dx, s2 / (1.0 + sqrt(1.0 - s2))), vec4(n, 1.0));
}

void buildGuides(vec3 x, vec3 n, Bsdf b) {
  guideProbability = GUIDE_PROBABILITY * bsdfGuideWeight(b);
  guideCone0 = guideCone(x, n, 0);
#if CAUSTIC_GUIDES > 1
  guideCone1 = guideCone(x, n, 1);
#endif
}

// Density (solid angle) of drawing the world direction w from a cone.
float conePdf(vec4 cone, vec3 w) {
  return pick(1.0 - dot(w, cone.xyz) <= cone.w, uniformConePdf(cone.w), 0.0);
}

// ... from the cones, each chosen with equal probability.
float guidePdf(vec3 w) {
#if CAUSTIC_GUIDES > 1
  return 0.5 * (conePdf(guideCone0, w) + conePdf(guideCone1, w));
#else
  return conePdf(guideCone0, w);
#endif
}

// The mixture pdf of the "BSDF sampling" technique, given the BSDF's own.
float guidedPdf(float bsdfPdf, vec3 w) {
  return (1.0 - guideProbability) * bsdfPdf + guideProbability * guidePdf(w);
}

// One direction of the mixture, weighted by its exact pdf. u: .xy direction
// (both techniques share its angle, so one sin/cos pair serves), .z BSDF
// lobe, .w technique; choice: which cone. Branch-free: both directions are
// drawn and one is selected.
BsdfSample sampleGuided(Bsdf m, mat3 frame, vec3 wo, vec4 u, float choice) {
  vec2 circle = unitCircle(u.y);
  bool isDelta;
  vec3 deltaWeight;
  vec3 wiBsdf = bsdfSampleDirection(m, wo, u.xyz, circle, isDelta, deltaWeight);
#if CAUSTIC_GUIDES > 1
  vec4 cone = choice >= 0.5 ? guideCone1 : guideCone0;
#else
  vec4 cone = guideCone0;
#endif
  vec3 worldGuide = basisAround(cone.xyz) * sampleUniformCone(u.x, circle, cone.w);
  bool guided = u.w < guideProbability;

  BsdfSample s;
  s.wi = pick(guided, worldGuide * frame, wiBsdf);
  s.isDelta = isDelta && !guided;
  float bsdfPdf;
  vec3 f = bsdfEval(m, wo, s.wi, bsdfPdf);
  vec3 worldWi = pick(guided, worldGuide, frame * wiBsdf);
  s.pdf = pick(s.isDelta, 0.0, guidedPdf(bsdfPdf, worldWi));
  // A delta lobe is drawn only when the guides are not: (1 - p) as often.
  s.weight = pick(s.isDelta, deltaWeight / (1.0 - guideProbability), f / s.pdf);
  s.valid = s.wi != vec3(0.0) && (s.isDelta || (s.pdf > 0.0 && f != vec3(0.0)));
  return s;
}

#else

void buildGuides(vec3 x, vec3 n, Bsdf b) {}
float guidedPdf(float bsdfPdf, vec3 w) { return bsdfPdf; }
BsdfSample sampleGuided(Bsdf m, mat3 frame, vec3 wo, vec4 u, float choice) {
  return bsdfSample(m, wo, u.xyz);
}

#endif
