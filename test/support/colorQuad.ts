/**
 * A glTF quad for the vertex-color tests, made with glTF-Transform: the
 * square |x|, |y| <= 1 in the plane z = 0, facing +z (vertex normals), two
 * triangles, one principled material (metallic 0, roughness 1, the given
 * baseColorFactor). With `colors`, COLOR_0 is red at x = -1 and green at
 * x = +1: any triangulation interpolates it to ((1 - x) / 2, (1 + x) / 2, 0).
 * Vertex normals (a smooth mesh) unless `flat`; TEXCOORD_0 (no texture reads
 * it) with `uvs`: the four ways the BVH stores a triangle's attributes.
 */
export async function colorQuadGlb(options: { colors: boolean; baseColorFactor: [number, number, number]; flat?: boolean; uvs?: boolean }): Promise<Uint8Array> {
  const { Document, WebIO } = await import('@gltf-transform/core');
  const doc = new Document();
  const buffer = doc.createBuffer();
  const accessor = (type: 'VEC2' | 'VEC3' | 'SCALAR', array: Float32Array<ArrayBuffer> | Uint16Array<ArrayBuffer>) => doc.createAccessor().setType(type).setArray(array).setBuffer(buffer);
  const corners = [[-1, -1], [1, -1], [1, 1], [-1, 1]];
  const material = doc.createMaterial('quad').setBaseColorFactor([...options.baseColorFactor, 1]).setMetallicFactor(0).setRoughnessFactor(1);
  const prim = doc.createPrimitive()
    .setAttribute('POSITION', accessor('VEC3', Float32Array.from(corners.flatMap(([x, y]) => [x, y, 0]))))
    .setIndices(accessor('SCALAR', Uint16Array.from([0, 1, 2, 0, 2, 3])))
    .setMaterial(material);
  if (!options.flat) prim.setAttribute('NORMAL', accessor('VEC3', Float32Array.from(corners.flatMap(() => [0, 0, 1]))));
  if (options.uvs) prim.setAttribute('TEXCOORD_0', accessor('VEC2', Float32Array.from(corners.flatMap(([x, y]) => [(x + 1) / 2, (1 - y) / 2]))));
  if (options.colors) prim.setAttribute('COLOR_0', accessor('VEC3', Float32Array.from(corners.flatMap(([x]) => (x < 0 ? [1, 0, 0] : [0, 1, 0])))));
  const scene = doc.createScene('scene').addChild(doc.createNode().setMesh(doc.createMesh('quad').addPrimitive(prim)));
  doc.getRoot().setDefaultScene(scene);
  return new WebIO().writeBinary(doc);
}
