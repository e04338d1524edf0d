// Scene data, packed by src/render/packScene.ts. The array sizes and the
// field offsets are #defines generated from src/render/layout.ts.
layout(std140) uniform SceneBlock {
  vec4 uSpheres[MAX_SPHERES * SPHERE_VEC4S];
  vec4 uLights[MAX_LIGHTS * LIGHT_VEC4S];
  vec4 uGround[GROUND_VEC4S];
  vec4 uEnvironment;   // rgb = radiance of escaping rays
  vec4 uCounts;        // x = spheres, y = lights, z = ground enabled (0/1), w = caustic guides
  vec4 uGuides[MAX_GUIDES * GUIDE_VEC4S];  // mirror and light geometry (lights/caustic_guide.glsl)
};

// The same data as a texture (row 0, one texel per vec4) for the dynamically
// indexed arrays: in SwiftShader a texelFetch costs far less than a
// dynamically indexed (per-lane, bounds-checked) uniform-block read.
uniform highp sampler2D uSceneData;
vec4 sceneData(int vec4Index) { return texelFetch(uSceneData, ivec2(vec4Index, 0), 0); }

struct Material {
  vec3 color;
  float roughness;
};

int sphereCount() { return int(uCounts.x); }
int lightCount() { return int(uCounts.y); }
bool groundEnabled() { return uCounts.z > 0.5; }

// Texels (sceneData) of a sphere's or a light's fields.
int sphereTexel(int i, int field) { return BLOCK_SPHERES + i * SPHERE_VEC4S + field; }
int lightTexel(int i, int field) { return BLOCK_LIGHTS + i * LIGHT_VEC4S + field; }

vec4 sphereGeometry(int i) { return sceneData(sphereTexel(i, SPHERE_GEOMETRY)); }
vec4 lightGeometry(int i) { return sceneData(lightTexel(i, LIGHT_GEOMETRY)); }
vec3 lightRadiance(int i) { return sceneData(lightTexel(i, LIGHT_RADIANCE)).rgb; }
float groundHeight() { return uGround[GROUND_GEOMETRY].x; }

// The material of a sphere or, when `isSphere` is false, of the ground
// (selected as vectors: GLSL ES has no ?: on structures).
Material surfaceMaterial(bool isSphere, int sphere) {
  vec4 m = isSphere ? sceneData(sphereTexel(sphere, SPHERE_MATERIAL)) : uGround[GROUND_MATERIAL];
  return Material(m.rgb, m.a);
}
