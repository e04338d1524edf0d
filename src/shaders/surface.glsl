// The surface step (pbrt-v4's SurfaceInteraction and Material::GetBSDF):
// what a hit is as a point of a surface, and its material evaluated there
// into the BSDF's parameters. The integrator and the guide-buffer pass see
// only a Surface and a Bsdf, whatever the shape and the material's kind.

struct Surface {
  vec3 position;
  vec3 normal;           // shading normal, on the outside of the surface
  vec3 geometricNormal;
  // Texture coordinates (the hit's): the ground's are world (x, z) (the
  // format's rule); spheres have none (0); a mesh's are its file's, from its
  // triangles' corners (0 when the file has none).
  vec2 uv;
  // Normal maps: xyz along increasing u, cross(normal, xyz) * w up the image.
  vec4 tangent;
#if HAS_VERTEX_COLORS
  // The hit's vertex color (white but on meshes whose material multiplies by it).
  vec3 color;
#endif
};

Surface surfaceAt(Hit hit) {
  Surface s;
  s.position = hit.position;
  s.normal = hit.normal;
  s.geometricNormal = hit.geometricNormal;
  s.uv = hit.uv;
  s.tangent = hit.tangent;
#if HAS_VERTEX_COLORS
  s.color = hit.color;
#endif
  return s;
}

// The material at the surface point: the record's constants, times their
// textures where an input has one (the generated applyMaterialTextures),
// times the vertex color where the kind takes one (glTF's baseColorFactor x
// baseColorTexture x COLOR_0: the generated applyVertexColor).
Bsdf evalMaterial(Material m, Surface s) {
  Bsdf b = bsdfFromRecord(m);
#if HAS_TEXTURES
  applyMaterialTextures(b, m, s.uv);
#endif
#if HAS_VERTEX_COLORS
  applyVertexColor(b, s.color);
#endif
  return b;
}

// The radiance the material emits at uv (a textured emission's texture read there).
vec3 surfaceEmission(Material m, vec2 uv) {
#if HAS_SURFACE_INPUTS
  return materialEmissionAt(m, uv);
#else
  return materialEmission(m);
#endif
}

// The normal the BSDF's frame is built around: a two-sided material seen
// from behind shades as from the front (Mitsuba's `twosided`).
vec3 facingNormal(Surface s, Bsdf b, vec3 direction) {
  return pick(b.twoSided && dot(direction, s.normal) > 0.0, -s.normal, s.normal);
}

// The shading normal after the material's normal map (exactly Mitsuba's
// `normalmap` adapter at its defaults, as the format spells it out), with
// what the adapter needs at each direction (normalMapFactor).
struct ShadingNormal {
  vec3 normal;  // perturbed (the BSDF's frame is built around it)
  vec3 base;    // the unperturbed facing normal
  float a2;     // the shadow-terminator term's a^2 (0: no normal map)
};

ShadingNormal shadingNormal(Material m, Surface s, vec3 facing, vec3 toViewer) {
  ShadingNormal r;
  r.normal = facing;
  r.base = facing;
  r.a2 = 0.0;
#if HAS_NORMAL_MAPS
  // An if without an else: its two paths differ in length, so SwiftShader's
  // compile does not double on it (an if/else, or ternaries of computed
  // values, would: see pick() in common/math.glsl; on 2026-12-02 this block
  // written as such ternaries made textured.json compile in 47 s, not 13 s).
  int t = materialNormalMap(m);
  vec3 x = s.tangent.xyz - s.normal * dot(s.normal, s.tangent.xyz);
  if (t >= 0 && dot(x, x) > 0.0) {
    vec3 n = textureNormal(t, s.uv);
    x = normalize(x);
    // The frame of the front side; from behind only z turns over (twosided),
    // so the tilt along the surface is kept.
    vec3 y = cross(s.normal, x) * s.tangent.w;
    vec3 p = normalize(n.x * x + n.y * y + n.z * facing);
    // flip_invalid_normals: the viewer below the perturbed hemisphere mirrors
    // the normal's tangential part.
    vec3 flipped = normalize(2.0 * dot(p, facing) * facing - p);
    p = dot(toViewer, p) <= 0.0 ? flipped : p;
    float c = clamp(dot(p, facing), 1e-6, 1.0);
    r.normal = p;
    r.a2 = min(0.125 * (1.0 - c * c) / (c * c), 1.0);
  }
#endif
  return r;
}

// The adapter's factor for light arriving from (or leaving toward) wi:
// zero when wi lies on opposite sides of the perturbed and unperturbed
// normals, else Estevez et al.'s shadow-terminator term
// 2 / (1 + sqrt(1 + a2 tan^2 theta)), theta wi's angle to the unperturbed normal.
float normalMapFactor(ShadingNormal n, vec3 wi) {
#if HAS_NORMAL_MAPS
  float c = dot(wi, n.base);
  float c2 = max(c * c, 1e-12);
  float term = 2.0 / (1.0 + sqrt(1.0 + n.a2 * (1.0 - c2) / c2));
  return c * dot(wi, n.normal) > 0.0 ? term : 0.0;
#else
  return 1.0;
#endif
}
