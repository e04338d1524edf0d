// Scene data, packed by src/render/packScene.ts in the layout of
// src/render/layout/scene.ts. Its structs and readers (Material,
// SphereRecord, Emitter, Header: read<Name>(firstTexel)) are generated into
// the chunk after this one; scene/access.glsl names what the rest reads.

// The tables, one texel per vec4, running on from row to row (rows of
// SCENE_ROW_TEXELS = 2^SCENE_ROW_BITS texels): in SwiftShader a texelFetch costs
// far less than a dynamically indexed (per-lane, bounds-checked) uniform read.
uniform highp sampler2D uSceneData;
vec4 sceneData(int texel) { return texelFetch(uSceneData, ivec2(texel & (SCENE_ROW_TEXELS - 1), texel >> SCENE_ROW_BITS), 0); }

// Per-scene constants, read with constant indices only.
layout(std140) uniform SceneBlock {
  vec4 uHeader[HEADER_TEXELS];
  vec4 uGuides[MAX_GUIDES * GUIDE_VEC4S];  // mirror and light geometry (lights/caustic_guide.glsl)
};
vec4 headerTexel(int i) { return uHeader[i]; }

#if HAS_INSTANCES
// The instance table (src/render/bvh/groups.ts), uploaded with the BVH
// (src/render/passes/assetTextures.ts): InstanceRecord r at texels
// r * INSTANCE_RECORD_TEXELS .., uInstanceCount records.
uniform highp sampler2D uInstances;
uniform int uInstanceCount;
vec4 instanceTexel(int texel) { return texelFetch(uInstances, ivec2(texel, 0), 0); }
#endif
