// Trowbridge-Reitz (GGX) microfacet distribution in the local shading frame
// (+z = normal), isotropic, with the separable Smith shadowing term.

float ggxD(vec3 h, float alpha) {
  float a2 = alpha * alpha;
  float c2 = h.z * h.z;
  float d = c2 * (a2 - 1.0) + 1.0;
  return a2 / (PI * d * d);
}

// Smith G1 for direction v above the surface (v.z > 0):
// 2 cos / (cos + sqrt(alpha^2 sin^2 + cos^2)). Below it, pass vec3(v.xy, -v.z).
float ggxG1(vec3 v, float alpha) {
  float a2 = alpha * alpha;
  float c2 = v.z * v.z;
  float s2 = max(0.0, v.x * v.x + v.y * v.y);
  return 2.0 * v.z / (v.z + sqrt(a2 * s2 + c2));
}

// Sample a microfacet normal from the distribution of normals visible from
// wo (Heitz 2018, "Sampling the GGX Distribution of Visible Normals"), given
// a uniform point `disk` on the unit disk (shared with cosine sampling).
vec3 sampleGgxVisibleNormal(vec3 wo, float alpha, vec2 disk) {
  vec3 vh = normalize(vec3(alpha * wo.x, alpha * wo.y, wo.z));
  float lenSq = vh.x * vh.x + vh.y * vh.y;
  vec3 t1 = pick(lenSq > 0.0, vec3(-vh.y, vh.x, 0.0) * inversesqrt(lenSq), vec3(1.0, 0.0, 0.0));
  vec3 t2 = cross(vh, t1);
  float p1 = disk.x;
  float s = 0.5 * (1.0 + vh.z);
  float p2 = (1.0 - s) * sqrt(max(0.0, 1.0 - p1 * p1)) + s * disk.y;
  vec3 nh = p1 * t1 + p2 * t2 + sqrt(max(0.0, 1.0 - p1 * p1 - p2 * p2)) * vh;
  return normalize(vec3(alpha * nh.x, alpha * nh.y, max(1e-7, nh.z)));
}

// Smith G1 on either side of the surface.
float ggxG1Either(vec3 v, float alpha) { return ggxG1(vec3(v.xy, abs(v.z)), alpha); }
