// Accessors of the packed scene (scene/layout.glsl and the generated records).

int sphereCount() { return readHeader(0).sphereCount; }
int emitterCount() { return readHeader(0).emitterCount; }
bool groundEnabled() { return readHeader(0).groundEnabled != 0; }
float groundHeight() { return readHeader(0).groundHeight; }
int groundMaterial() { return readHeader(0).groundMaterial; }
vec3 constantEnvironment() { return readHeader(0).environment; }
int environmentEmitter() { return readHeader(0).environmentEmitter; }
int planarLightCount() { return readHeader(0).planarLightCount; }

int sphereTexel(int i, int field) { return SPHERES_FIRST + i * SPHERE_RECORD_TEXELS + field; }
// center.xyz, radius; in row 0 (layout/scene.ts), so the row is a constant.
vec4 sphereGeometry(int i) { return texelFetch(uSceneData, ivec2(SPHERE_GEOMETRY_FIRST + i, 0), 0); }
SphereRecord loadSphere(int i) { return readSphereRecord(sphereTexel(i, 0)); }
Material loadMaterial(int i) { return readMaterial(MATERIALS_FIRST + i * MATERIAL_TEXELS); }
Emitter loadEmitter(int i) { return readEmitter(EMITTERS_FIRST + i * EMITTER_TEXELS); }
MeshRecord loadMesh(int i) { return readMeshRecord(MESHES_FIRST + i * MESH_RECORD_TEXELS); }
// center.xyz, radius of a sphere around planar light i; in row 0 like sphereGeometry.
vec4 planarLightBound(int i) { return texelFetch(uSceneData, ivec2(PLANAR_BOUNDS_FIRST + i, 0), 0); }
// center.xyz, radius of a sphere around planar lights [PLANAR_GROUP_SIZE * g, PLANAR_GROUP_SIZE * (g + 1)).
vec4 planarGroupBound(int g) { return texelFetch(uSceneData, ivec2(PLANAR_GROUPS_FIRST + g, 0), 0); }
PlanarLight loadPlanarLight(int i) { return readPlanarLight(PLANAR_LIGHTS_FIRST + i * PLANAR_LIGHT_TEXELS); }
