// Caustic guiding: light that reaches a rough surface through an ideal
// mirror sphere (a caustic) can only be found by BSDF sampling, which hits
// the light's small reflected image rarely and then with a large weight:
// fireflies. So at each rough vertex, "BSDF sampling" becomes a mixture:
// with probability GUIDE_PROBABILITY a direction is drawn uniformly in a cone
// around the mirror point that reflects the light towards the vertex, sized
// to cover the light's image in the convex mirror; otherwise the BSDF is
// sampled as usual. Every sample is weighted by the mixture's exact pdf, and
// the same pdf enters the MIS weights, so the estimate stays unbiased
// whatever the cone (a poor cone only wastes samples). The (mirror, light)
// pairs are chosen on the CPU per scene upload (src/render/packScene.ts).
//
// CAUSTIC_GUIDING selects between two programs compiled up front: with it,
// and without (for scenes with no guide; SwiftShader executes every line of
// a shader whatever the branches, so unused guiding would still cost).

#if CAUSTIC_GUIDING

// The guides of the current vertex: globals, and two named cones rather
// than an array (MAX_GUIDES is 2): SwiftShader copies arrays passed by value
// and indexes local arrays slowly, which cost more than the guiding itself.
vec4 guideCone0;         // xyz = unit axis, w = 1 - cos(half angle)
vec4 guideCone1;
int guidesHere;          // cones in use (0, 1 or 2)
float guideProbability;  // of drawing from the cones at this vertex

int guideCount() { return int(uCounts.w); }

// The cone towards the light's image in mirror `guide` as seen from x; the
// hemisphere around n when there is no sensible image (x or the light inside
// the mirror), which keeps the mixture a valid density everywhere.
vec4 guideCone(vec3 x, vec3 n, int guide) {
  vec4 ids = uGuides[guide];
  vec4 mirror = sphereGeometry(int(ids.x));
  vec4 light = lightGeometry(int(ids.y));
  vec3 toX = x - mirror.xyz;
  vec3 toLight = light.xyz - mirror.xyz;
  float distX = length(toX);
  float distLight = length(toLight);
  if (distX <= mirror.w * 1.0001 || distLight <= mirror.w + light.w) return vec4(n, 1.0);
  // Reflection point: its normal bisects the directions to x and the light.
  vec3 h = normalize(toX / distX + toLight / distLight);
  for (int k = 0; k < GUIDE_ITERATIONS; k++) {
    vec3 p = mirror.xyz + mirror.w * h;
    h = normalize(normalize(x - p) + normalize(light.xyz - p));
  }
  vec3 toP = mirror.xyz + mirror.w * h - x;
  float dx = length(toP);
  float dl = length(light.xyz - (mirror.xyz + mirror.w * h));
  // Paraxial convex mirror (focal length R / 2, sagittal R / (2 cos i) off
  // axis, the larger extent): the light's image and its depth behind p.
  float cosI = max(0.05, dot(h, -toP / dx));
  float focal = 0.5 * mirror.w / cosI;
  float image = light.w * focal / (dl + focal);
  float depth = dl * focal / (dl + focal);
  float s = clamp(GUIDE_MARGIN * image / (dx + depth), 3e-3, 0.5);
  float s2 = s * s;
  return vec4(toP / dx, s2 / (1.0 + sqrt(1.0 - s2)));
}

void buildGuides(vec3 x, vec3 n, Material m) {
  guidesHere = hasSmoothLobe(m) ? guideCount() : 0;
  // Rough (diffuse-like) vertices are guided most: a glossy lobe already
  // concentrates its samples and would lose more than it gains.
  guideProbability = guidesHere > 0 ? GUIDE_PROBABILITY * m.roughness : 0.0;
  guideCone0 = guideCone(x, n, 0);
  guideCone1 = guidesHere > 1 ? guideCone(x, n, 1) : guideCone0;
}

// Density (solid angle) of drawing the world direction w from the cones.
float conePdf(vec4 cone, vec3 w) {
  return 1.0 - dot(w, cone.xyz) <= cone.w ? uniformConePdf(cone.w) : 0.0;
}

float guidePdf(vec3 w) {
  if (guidesHere == 0) return 0.0;
  float pdf = conePdf(guideCone0, w) + (guidesHere > 1 ? conePdf(guideCone1, w) : 0.0);
  return pdf / float(guidesHere);
}

// The mixture pdf of the "BSDF sampling" technique, given the BSDF's own.
float guidedPdf(float bsdfPdf, vec3 w) {
  return (1.0 - guideProbability) * bsdfPdf + guideProbability * guidePdf(w);
}

// One direction of the mixture, weighted by its exact pdf. u: .xy direction,
// .z BSDF lobe, .w technique; choice: which cone.
BsdfSample sampleGuided(Material m, mat3 frame, vec3 wo, vec4 u, float choice) {
  BsdfSample s = BsdfSample(vec3(0.0), vec3(0.0), 0.0, false, false);
  if (wo.z <= 0.0) return s;
  bool guided = u.w < guideProbability;
  vec3 wiBsdf = sampleMaterialDirection(m, wo, u.xyz, s.isDelta);
  vec3 world = frame * wiBsdf;
  if (guided) {
    vec4 cone = choice * float(guidesHere) >= 1.0 ? guideCone1 : guideCone0;
    world = basisAround(cone.xyz) * sampleUniformCone(u.xy, cone.w);
    s.isDelta = false;
  }
  s.wi = guided ? world * frame : wiBsdf;
  if (s.isDelta) {
    // The mirror lobe is drawn with probability (1 - p)(1 - r).
    s.weight = m.color / (1.0 - guideProbability);
    s.valid = true;
    return s;
  }
  float bsdfPdf;
  vec3 f = evalMaterial(m, wo, s.wi, bsdfPdf);
  s.pdf = guidedPdf(bsdfPdf, world);
  s.valid = s.wi.z > 0.0 && s.pdf > 0.0;
  s.weight = s.valid ? f / s.pdf : vec3(0.0);
  return s;
}

#else

void buildGuides(vec3 x, vec3 n, Material m) {}
float guidedPdf(float bsdfPdf, vec3 w) { return bsdfPdf; }
BsdfSample sampleGuided(Material m, mat3 frame, vec3 wo, vec4 u, float choice) {
  return sampleMaterial(m, wo, u.xyz);
}

#endif
