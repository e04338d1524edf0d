// Unidirectional path tracing with next-event estimation and multiple
// importance sampling (pbrt-v4's PathIntegrator, reduced to this scene model).
uniform int uMaxBounces;

// Russian roulette starts after this many scattering events.
const int ROULETTE_DEPTH = 3;
// Russian roulette only for paths whose throughput fell below this.
const float ROULETTE_THRESHOLD = 0.95;

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

    // Sample illumination from lights to find path contribution.
    if (hasSmoothLobe(material)) {
      radiance += throughput * sampleDirectLight(hit, frame, wo, material);
    }

    // Sample BSDF to get new path direction.
    BsdfSample bs = sampleMaterial(material, wo, rand4().xyz);
    if (!bs.valid) break;
    throughput *= bs.weight;
    previousDelta = bs.isDelta;
    previousPdf = bs.pdf;
    previousPosition = hit.position;
    direction = frame * bs.wi;
    origin = spawnRayOrigin(hit, direction);

    // Possibly terminate the path with Russian roulette (unbiased: survivors
    // are reweighted by 1 / q). Paths that kept nearly all their energy are
    // not played: rounding makes a white Lambert weight 0.99999994, and
    // killing such paths would only add noise (the white furnace).
    float q = maxComponent(throughput);
    if (depth + 1 >= ROULETTE_DEPTH && q < ROULETTE_THRESHOLD) {
      if (rand4().x >= q) break;
      throughput /= q;
    }
  }
  return radiance;
}
