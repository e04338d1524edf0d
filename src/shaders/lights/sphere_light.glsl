// Spherical area lights, sampled uniformly inside the cone they subtend
// (solid-angle pdf), chosen uniformly among the lights.

struct LightCone {
  vec3 axis;              // unit vector towards the light's centre
  float oneMinusCosMax;   // 1 - cos of the cone's half angle; 0 = not visible
};

LightCone lightCone(vec3 x, vec4 sphere) {
  vec3 toCenter = sphere.xyz - x;
  float dist2 = dot(toCenter, toCenter);
  float r2 = sphere.w * sphere.w;
  // Inside (or on) the light: it emits outwards only, so it is invisible.
  if (dist2 <= r2) return LightCone(vec3(0.0, 0.0, 1.0), 0.0);
  float sin2Max = r2 / dist2;
  // 1 - sqrt(1 - s) without cancellation for small s.
  return LightCone(toCenter * inversesqrt(dist2), sin2Max / (1.0 + sqrt(1.0 - sin2Max)));
}

float lightSelectionPdf() { return 1.0 / float(lightCount()); }

// Density, in solid angle at x, of sampling a direction towards the light
// with geometry `sphere`.
float lightPdf(vec3 x, vec4 sphere) {
  LightCone cone = lightCone(x, sphere);
  if (cone.oneMinusCosMax <= 0.0) return 0.0;
  return lightSelectionPdf() * uniformConePdf(cone.oneMinusCosMax);
}

// Next-event estimation at a surface vertex: f * Le * cos / pdf, weighted by
// the power heuristic against BSDF sampling.
// u: .xy direction in the cone, .z choice of the light.
vec3 sampleDirectLight(Hit hit, mat3 frame, vec3 wo, Material m, vec3 u) {
  int count = lightCount();
  if (count == 0) return vec3(0.0);
  int light = min(int(u.z * float(count)), count - 1);
  vec4 sphere = lightGeometry(light);
  LightCone cone = lightCone(hit.position, sphere);
  if (cone.oneMinusCosMax <= 0.0) return vec3(0.0);
  float oneMinusCos = u.x * cone.oneMinusCosMax;
  vec3 wiWorld = basisAround(cone.axis) * sampleUniformCone(u.xy, cone.oneMinusCosMax);
  vec3 wi = wiWorld * frame;  // transpose(frame) * wiWorld: into the shading frame
  float bsdfPdf;
  vec3 f = evalMaterial(m, wo, wi, bsdfPdf);
  if (bsdfPdf <= 0.0) return vec3(0.0);
  bsdfPdf = guidedPdf(bsdfPdf, wiWorld);  // BSDF sampling is mixed with the caustic guides

  // Where the direction meets the light, from the cone's geometry:
  // t = d cos - sqrt(r^2 - d^2 sin^2) (a rim direction that misses by
  // rounding ends at the tangent point).
  vec3 toCenter = sphere.xyz - hit.position;
  float dist2 = dot(toCenter, toCenter);
  float cosTheta = 1.0 - oneMinusCos;
  float sin2Theta = oneMinusCos * (2.0 - oneMinusCos);
  float tLight = sqrt(dist2) * cosTheta - sqrt(max(0.0, sphere.w * sphere.w - dist2 * sin2Theta));
  vec3 origin = spawnRayOrigin(hit, wiWorld);
  if (occluded(origin, wiWorld, tLight, light)) return vec3(0.0);

  float pdf = lightSelectionPdf() * uniformConePdf(cone.oneMinusCosMax);
  return f * lightRadiance(light) * (powerHeuristic(pdf, bsdfPdf) / pdf);
}
