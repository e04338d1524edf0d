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
};

Surface surfaceAt(Hit hit) {
  Surface s;
  s.position = hit.position;
  s.normal = hit.normal;
  s.geometricNormal = hit.geometricNormal;
  s.uv = hit.uv;
  return s;
}

// The material at the surface point: the one place where textures and
// normal maps are read (today every parameter is the record's constant).
Bsdf evalMaterial(Material m, Surface s) {
  return bsdfFromRecord(m);
}

// The normal the BSDF's frame is built around: a two-sided material seen
// from behind shades as from the front (Mitsuba's `twosided`).
vec3 facingNormal(Surface s, Bsdf b, vec3 direction) {
  return b.twoSided && dot(direction, s.normal) > 0.0 ? -s.normal : s.normal;
}
