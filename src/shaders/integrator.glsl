// Unidirectional path tracing with next-event estimation and multiple
// importance sampling (pbrt-v4's PathIntegrator, reduced to this scene model).
//
// Russian roulette is a switch (RUSSIAN_ROULETTE, PathTracerOptions), off by
// default: SwiftShader runs the four pixels of a quad in lock step and a
// loop iterates until its last lane is done, so terminating a path early
// rarely saves time there, while the 1/q reweighting adds variance
// (measured: relMSE at equal spp 12-28% lower without it, same path rate).
// On a GPU whose warps retire early it can pay off.
uniform int uMaxBounces;

vec3 traceRadiance(vec3 origin, vec3 direction) {
  vec3 radiance = vec3(0.0);
  vec3 throughput = vec3(1.0);
  // The previous scattering event, for MIS on emitters found by BSDF sampling.
  bool previousDelta = true;
  float previousPdf = 0.0;
  vec3 previousPosition = origin;

  for (int depth = 0; ; depth++) {
    Hit hit = intersectScene(origin, direction);

    // Escaped: the environment's constant radiance.
    if (hit.kind == HIT_NONE) {
      radiance += throughput * uEnvironment.rgb;
      break;
    }
    // Emitter: add its radiance (outward side only), MIS-weighted against
    // light sampling at the previous vertex; lights reflect nothing.
    if (hit.kind == HIT_LIGHT) {
      if (dot(direction, hit.normal) < 0.0) {
        float weight = previousDelta ? 1.0
          : powerHeuristic(previousPdf, lightPdf(previousPosition, hit.index));
        radiance += throughput * lightRadiance(hit.index) * weight;
      }
      break;
    }
    // Terminate path if maximum depth reached.
    if (depth >= uMaxBounces) break;

    Material material = groundMaterial();
    if (hit.kind == HIT_SPHERE) material = sphereMaterial(hit.index);
    vec3 normal = dot(direction, hit.normal) < 0.0 ? hit.normal : -hit.normal;
    mat3 frame = basisAround(normal);
    vec3 wo = -direction * frame;

    // Random numbers of this bounce: light sample, BSDF sample.
    rngSetDimension(RNG_CAMERA_DIMENSIONS + uint(depth) * RNG_BOUNCE_DIMENSIONS);
    vec4 uLight = rand4();
    vec4 uBsdf = rand4();
#if LOW_DISCREPANCY
    if (depth == 0) {
      uLight.xy = ldLight();
      uBsdf.xy = ldBsdf();
    }
#endif

    // Caustic guides at this vertex (see lights/caustic_guide.glsl).
    buildGuides(hit.position, normal, material);

    // Sample illumination from lights to find path contribution.
    if (hasSmoothLobe(material)) {
      radiance += throughput * sampleDirectLight(hit, frame, wo, material, uLight.xyz);
    }

    // Sample BSDF (mixed with the caustic guides) to get new path direction.
    BsdfSample bs = sampleGuided(material, frame, wo, uBsdf, uLight.w);
    if (!bs.valid) break;
    throughput *= bs.weight;
    previousDelta = bs.isDelta;
    previousPdf = bs.pdf;
    previousPosition = hit.position;
    direction = frame * bs.wi;
    origin = spawnRayOrigin(hit, direction);

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

  }
  return radiance;
}
