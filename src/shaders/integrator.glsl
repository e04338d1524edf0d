// Unidirectional path tracing with next-event estimation and multiple
// importance sampling (pbrt-v4's PathIntegrator, reduced to this scene model).
//
// Shaped for SwiftShader, which runs the lanes of a pixel quad in lock step
// and executes both sides of every branch under lane masks: only a loop's
// back edge really skips work (when no lane continues). So the loop body is
// one scattering event that ends by finding the next vertex, adding what it
// emits and deciding there whether the path goes on, so that the back edge
// is taken only when some lane has a surface to scatter from. A path that
// escapes to the sky costs one intersection, not one more (masked) pass
// through the whole body (measured: bench/shader-ab.ts).
//
// Russian roulette is a switch (RUSSIAN_ROULETTE, PathTracerOptions), off by
// default: a loop iterates until its last lane is done, so terminating a path
// early rarely saves time on SwiftShader, while the 1/q reweighting adds
// variance (measured: relMSE at equal spp 12-28% lower without it, same
// path rate). On a GPU whose warps retire early it can pay off.
uniform int uMaxBounces;

// The closest surface along a ray that stops it, and its material. On
// SwiftShader every call of intersectScene inlines a whole BVH traversal,
// and a shader's compile time grows faster than its size: so each of these
// functions has exactly one call site of it, in a loop where the scene has
// see-through surfaces (measured: a second call site in the pass-through
// and the shadow loops made a cut-out scene's program compile 10-20x
// slower).
#if HAS_SEE_THROUGH
// Most see-through surfaces a ray or a shadow ray passes before it counts
// as blocked (a bound for the loops; beyond it the estimate loses energy).
const int SEE_THROUGH_STEPS = 16;

// A hit on a see-through material (opacity o < 1) lets the ray pass with
// probability 1 - o: the next hit along the same ray replaces it. Not a
// bounce (Mitsuba's volpath), so a cut-out costs no path depth; emission
// is then seen with probability o, which is the format's o * Le.
Hit traceThrough(vec3 origin, vec3 direction, uint depth, out Material material) {
  Hit hit;
  for (int i = 0; i < SEE_THROUGH_STEPS; i++) {
    hit = intersectScene(origin, direction);
    material = loadMaterial(hit.material);
    if (hit.kind == HIT_NONE) break;
    float o = materialOpacity(material, hit.uv);
    if (o >= 1.0 || randEvent(depth * uint(SEE_THROUGH_STEPS) + uint(i)) < o) break;
    origin = spawnRayOrigin(hit, direction);
  }
  return hit;
}

// The fraction of light a shadow ray carries through see-through surfaces
// before tMax: the product of their 1 - opacity (0: blocked). Closest hits
// only (no any-hit query: one traversal call site, see above).
float shadowTransmittance(vec3 origin, vec3 direction, float tMax, int skipSphere) {
  float transmitted = 1.0;
  for (int i = 0; i < SEE_THROUGH_STEPS; i++) {
    Hit h = intersectScene(origin, direction);
    // A blocker at or past tMax is the light itself (the any-hit test's rounding).
    if (h.kind == HIT_NONE || h.t >= tMax * 0.9999) return transmitted;
    transmitted *= 1.0 - materialOpacity(loadMaterial(h.material), h.uv);
    if (transmitted <= 0.0) return 0.0;
    tMax -= h.t;
    origin = spawnRayOrigin(h, direction);
  }
  return 0.0;
}
#else
Hit traceThrough(vec3 origin, vec3 direction, uint depth, out Material material) {
  Hit hit = intersectScene(origin, direction);
  material = loadMaterial(hit.material);
  return hit;
}
float shadowTransmittance(vec3 origin, vec3 direction, float tMax, int skipSphere) {
  return occluded(origin, direction, tMax, skipSphere) ? 0.0 : 1.0;
}
#endif

bool scatters(Hit hit, Material material) { return hit.kind != HIT_NONE && bsdfScatters(material); }

// Radiance leaving the hit towards the ray's origin: the sky for an escaped
// ray; the surface's emission (outside only), MIS-weighted against light
// sampling at the previous vertex (unless that vertex scattered through a
// Dirac delta).
vec3 emitted(Hit hit, Material material, vec3 direction, vec3 previousPosition, bool previousDelta, float previousPdf) {
  float weight = pick(previousDelta, 1.0, powerHeuristic(previousPdf, lightPdf(previousPosition, direction, hit)));
  vec3 surface = pick(dot(direction, hit.normal) < 0.0, surfaceEmission(material, hit.uv), vec3(0.0));
  return pick(hit.kind == HIT_NONE, escapedRadiance(direction), surface) * weight;
}

// Next-event estimation at a surface vertex: f * Le * |cos| / pdf of one
// light sample, weighted by the power heuristic against BSDF sampling.
// u: .xy the point on the emitter, .z the choice of emitter.
vec3 sampleDirectLight(Hit hit, mat3 frame, vec3 wo, Bsdf bsdf, ShadingNormal shading, vec3 u) {
  LightSample light = sampleLight(hit.position, u);
  vec3 wi = light.direction * frame;  // transpose(frame) * direction: into the shading frame
  float bsdfPdf;
  vec3 f = bsdfEval(bsdf, wo, wi, bsdfPdf) * normalMapFactor(shading, light.direction);
  vec3 contribution = vec3(0.0);
  // An if without an else, and one return (see pick() in common/math.glsl).
  if (light.pdf > 0.0 && bsdfPdf > 0.0) {
    bsdfPdf = guidedPdf(bsdfPdf, light.direction);  // BSDF sampling is mixed with the caustic guides
    vec3 origin = spawnRayOrigin(hit, light.direction);
    float transmitted = shadowTransmittance(origin, light.direction, light.distance, light.skipSphere);
    // A Dirac delta light is found by this technique alone: no MIS.
    float weight = pick(light.delta, 1.0, powerHeuristic(light.pdf, bsdfPdf));
    contribution = f * light.radiance * (transmitted * weight / light.pdf);
  }
  return contribution;
}

// The rest of a path whose camera ray hit `hit` (see scatters), given the
// radiance it has seen so far. The shading frame's +z is the outside of
// the surface: one-sided materials see wo.z < 0 from inside and scatter
// nothing; a solid's boundary (glass) scatters on both sides; two-sided
// materials turn the frame towards the viewer (facingNormal).
vec3 traceRadiance(vec3 direction, Hit hit, Material material, vec3 radiance) {
  vec3 throughput = vec3(1.0);

  for (int depth = 0; ; depth++) {
    // The material evaluated at the surface point, in its shading frame.
    Surface surface = surfaceAt(hit);
    Bsdf bsdf = evalMaterial(material, surface);
    ShadingNormal shading = shadingNormal(material, surface, facingNormal(surface, bsdf, direction), -direction);
    vec3 normal = shading.normal;
    mat3 frame = basisAround(normal);
    vec3 wo = -direction * frame;

    // Random numbers of this bounce: light sample, BSDF sample.
    rngSetDimension(RNG_CAMERA_DIMENSIONS + uint(depth) * RNG_BOUNCE_DIMENSIONS);
    vec4 uLight = rand4();
    vec4 uBsdf = rand4();
#if LOW_DISCREPANCY
    uLight.xy = pick(depth == 0, ldLight(), uLight.xy);
    uBsdf.xy = pick(depth == 0, ldBsdf(), uBsdf.xy);
#endif

    // Caustic guides at this vertex (see lights/caustic_guide.glsl).
    buildGuides(hit.position, normal, bsdf);

    // Light arriving directly from an emitter (next-event estimation).
    vec3 direct = sampleDirectLight(hit, frame, wo, bsdf, shading, uLight.xyz);
    radiance += throughput * (bsdfHasNonDeltaLobe(bsdf) ? direct : vec3(0.0));

    // Sample the BSDF (mixed with the caustic guides) for the next direction.
    BsdfSample bs = sampleGuided(bsdf, frame, wo, uBsdf, uLight.w);
    if (!bs.valid) break;
    throughput *= bs.weight * normalMapFactor(shading, frame * bs.wi);

#if RUSSIAN_ROULETTE
    // Possibly terminate the path (unbiased: survivors are reweighted by
    // 1 / q). Paths that kept nearly all their energy are not played:
    // rounding makes a white Lambert weight 0.99999994, and killing such
    // paths would only add noise (the white furnace).
    float q = maxComponent(throughput);
    if (depth + 1 >= ROULETTE_DEPTH && q < ROULETTE_THRESHOLD) {
      if (rand4().x >= q) break;
      throughput /= q;
    }
#endif

    // The next vertex, and what it emits towards this one.
    vec3 position = hit.position;
    direction = frame * bs.wi;
    hit = traceThrough(spawnRayOrigin(hit, direction), direction, uint(depth + 1), material);
    radiance += throughput * emitted(hit, material, direction, position, bs.isDelta, bs.pdf);
    // Decided here, not at the top: a lane that leaves at the back edge
    // spares the quad a whole masked pass through the body.
    if (depth + 1 >= uMaxBounces || !scatters(hit, material)) break;
  }
  return radiance;
}
