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

bool scatters(Hit hit) { return hit.kind == HIT_SPHERE || hit.kind == HIT_GROUND; }

// Radiance leaving the hit towards the ray's origin that only BSDF sampling
// finds: the sky for an escaped ray; a light's emission (outward side only),
// MIS-weighted against light sampling at the previous vertex (unless that
// vertex scattered through a Dirac delta); nothing for other surfaces.
vec3 emitted(Hit hit, vec3 direction, vec3 previousPosition, bool previousDelta, float previousPdf) {
  float weight = previousDelta ? 1.0 : powerHeuristic(previousPdf, lightPdf(previousPosition, hit.geometry));
  vec3 light = dot(direction, hit.normal) < 0.0 ? lightRadiance(hit.index) * weight : vec3(0.0);
  return hit.kind == HIT_NONE ? uEnvironment.rgb : hit.kind == HIT_LIGHT ? light : vec3(0.0);
}

// The rest of a path whose camera ray hit `hit` (see scatters), given the
// radiance it has seen so far.
vec3 traceRadiance(vec3 direction, Hit hit, vec3 radiance) {
  vec3 throughput = vec3(1.0);

  for (int depth = 0; ; depth++) {
    Material material = surfaceMaterial(hit.kind == HIT_SPHERE, hit.index);
    vec3 normal = dot(direction, hit.normal) < 0.0 ? hit.normal : -hit.normal;
    mat3 frame = basisAround(normal);
    vec3 wo = -direction * frame;

    // Random numbers of this bounce: light sample, BSDF sample.
    rngSetDimension(RNG_CAMERA_DIMENSIONS + uint(depth) * RNG_BOUNCE_DIMENSIONS);
    vec4 uLight = rand4();
    vec4 uBsdf = rand4();
#if LOW_DISCREPANCY
    uLight.xy = depth == 0 ? ldLight() : uLight.xy;
    uBsdf.xy = depth == 0 ? ldBsdf() : uBsdf.xy;
#endif

    // Caustic guides at this vertex (see lights/caustic_guide.glsl).
    buildGuides(hit.position, normal, material);

    // Light arriving directly from a light source (next-event estimation).
    vec3 direct = sampleDirectLight(hit, frame, wo, material, uLight.xyz);
    radiance += throughput * (hasSmoothLobe(material) ? direct : vec3(0.0));

    // Sample the BSDF (mixed with the caustic guides) for the next direction.
    BsdfSample bs = sampleGuided(material, frame, wo, uBsdf, uLight.w);
    if (!bs.valid) break;
    throughput *= bs.weight;

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
    hit = intersectScene(spawnRayOrigin(hit, direction), direction);
    radiance += throughput * emitted(hit, direction, position, bs.isDelta, bs.pdf);
    // Decided here, not at the top: a lane that leaves at the back edge
    // spares the quad a whole masked pass through the body.
    if (depth + 1 >= uMaxBounces || !scatters(hit)) break;
  }
  return radiance;
}
