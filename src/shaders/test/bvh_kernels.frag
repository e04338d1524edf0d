// One ray per pixel through bvh.glsl, for test/browser/bvh-traversal.test.ts.
// uRays: RGBA32F in the BVH textures' layout, ray i at texels 2i (origin, tMax), 2i+1 (direction, unused).
uniform highp sampler2DArray uRays;
uniform int uMode; // 0 closest hit, 1 any hit, 2 surface at the closest hit, 3 uv at the closest hit from uRoot
uniform int uRoot; // mode 3: the root node of the group traversed (BVH_ROOT_NODE, or a shared group's)
uniform int uGridWidth;

out vec4 outValue;

void main() {
  int i = int(gl_FragCoord.y) * uGridWidth + int(gl_FragCoord.x);
  vec4 o = bvhTexel(uRays, 2 * i);
  vec3 dir = bvhTexel(uRays, 2 * i + 1).xyz;
  BvhHit hit;
  if (uMode == 1) {
    outValue = vec4(bvhAnyHit(o.xyz, dir, o.w) ? 1.0 : 0.0);
  } else if (uMode == 3) {
    bool found = bvhIntersect(uRoot, o.xyz, dir, o.w, false, hit);
    outValue = found ? vec4(bvhSurface(hit).uv, float(hit.triangle), hit.t) : vec4(0.0, 0.0, -1.0, 0.0);
  } else if (!bvhClosestHit(o.xyz, dir, o.w, hit)) {
    outValue = vec4(-1.0, 0.0, 0.0, 0.0);
  } else if (uMode == 0) {
    outValue = vec4(float(hit.triangle), hit.t, hit.barycentric);
  } else {
    BvhSurface s = bvhSurface(hit);
    outValue = vec4(s.shadingNormal, float(s.localMaterial));
  }
}
