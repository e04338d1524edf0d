// Emissive meshes as emitters: light sampling picks a mesh (lights.glsl),
// then one of its triangles in proportion to its area (an
// alias table per mesh in uEmissiveTriangles, src/render/passes/assetTextures.ts),
// then a uniform point on the triangle. So a point has the density, per unit
// area, of the mesh's MeshRecord.inverseArea = 1 / area(mesh) (times the choice of the mesh), turned
// into solid angle at x by distance^2 / |cos| at the light, the cosine taken
// against the SHADING normal, as Mitsuba 3 does (Mesh::sample_position and
// DirectionSample put the interpolated vertex normal in ds.n, and
// Shape::sample_direction / pdf_direction divide by |dot(d, ds.n)|). On a
// smooth mesh that is not the true density (the geometric normal's cosine
// would be), so Mitsuba's light samples are weighted by
// |cos shading| / |cos geometric|; the format defines the image as what
// Mitsuba renders ("the shading normal decides ... the cosines"), so we do
// the same, in both the sample's density and meshEmitterPdf (the MIS weight
// of a BSDF-sampled hit). Flat meshes are unaffected (the two normals agree).
// The triangle emits towards the side its shading normal faces (the
// format's one-sided emission).
//
// uEmissiveTriangles: RGBA32F, BVH_TEXTURE_WIDTH wide; slot s at
// (s % W, s / W) = (BVH triangle, alias threshold, alias slot, ratio): a
// textured emission picks triangles by power (records.ts emissionMeans),
// so a point's density is the area density times `ratio` (the triangle's
// share of the power over its share of the area). The sample reports the
// area density (the one meshEmitterPdf gives a BSDF-sampled hit, so the
// two strategies' MIS weights still sum to one) and its radiance over
// `ratio`: f Le / p is unchanged, the weights stay consistent.
//
// Compiled in only for scenes with emissive meshes (HAS_EMISSIVE_MESHES).

#if HAS_EMISSIVE_MESHES

uniform highp sampler2D uEmissiveTriangles;

// A point on mesh emitter e seen from x: its direction, distance, emitted
// radiance towards x and solid-angle density (emitter choice excluded).
// u: .xy the point on the triangle, .z the choice of triangle.
vec3 sampleMeshEmitter(vec3 x, Emitter e, vec3 u, out float pdf, out float distance, out vec3 radiance) {
  float scaled = u.z * float(e.count);
  int k = min(int(scaled), e.count - 1);
  vec4 slot = bvhTexel(uEmissiveTriangles, e.first + k);
  if (scaled - float(k) >= slot.y) slot = bvhTexel(uEmissiveTriangles, e.first + int(slot.z));
  int triangle = int(slot.x);
  float s = sqrt(u.x);
  BvhSurface surface = bvhSurface(BvhHit(triangle, 0.0, vec2(s * (1.0 - u.y), s * u.y)));
  vec3 toLight = surface.position - x;
  distance = length(toLight);
  vec3 direction = toLight / distance;
  float cosLight = abs(dot(direction, surface.shadingNormal));
  pdf = pick(cosLight > 0.0, loadMesh(e.primitive).inverseArea * distance * distance / cosLight, 0.0);
#if HAS_TEXTURED_EMISSION || HAS_SEE_THROUGH
  // The radiance at the point (a textured emission's texture), seen where
  // the surface is opaque: times its opacity (the format's o * Le, which a
  // BSDF-sampled hit sees as a pass-through with probability 1 - o).
  Material m = loadMaterial(loadMesh(e.primitive).materialBase + surface.localMaterial);
  vec3 emitted = surfaceEmission(m, surface.uv) * materialOpacity(m, surface.uv) / slot.w;
#else
  vec3 emitted = e.radiance;
#endif
  radiance = dot(direction, surface.shadingNormal) < 0.0 ? emitted : vec3(0.0);
  return direction;
}

// Density of light sampling drawing `direction` from x towards the
// triangle `hit` (its emitterDensity is the mesh's inverseArea), once it picked the mesh.
float meshEmitterPdf(vec3 direction, Hit hit) {
  float cosLight = abs(dot(direction, hit.normal));  // the shading normal (see above)
  return pick(cosLight > 0.0, hit.emitterDensity * hit.t * hit.t / cosLight, 0.0);
}

#endif
