/**
 * A glTF quad for the vertex-color tests, made with glTF-Transform: the
 * square |x|, |y| <= 1 in the plane z = 0, facing +z, as a grid of `grid` x
 * `grid` cells of two triangles each (default 1: two triangles), one
 * principled material (metallic 0, roughness 1, the given baseColorFactor).
 * With `colors`, COLOR_0 at each vertex is ((1 - x) / 2, (1 + x) / 2, 0):
 * red at x = -1, green at x = +1, and affine, so any triangulation
 * interpolates it to that everywhere. Vertex normals (a smooth mesh) unless
 * `flat`; TEXCOORD_0 (no texture reads it) with `uvs`: the four ways the BVH
 * stores a triangle's attributes.
 */
export async function colorQuadGlb(options: { colors: boolean; baseColorFactor: [number, number, number]; flat?: boolean; uvs?: boolean; grid?: number }): Promise<Uint8Array> {
  const { Document, WebIO } = await import('@gltf-transform/core');
  const doc = new Document();
  const buffer = doc.createBuffer();
  const accessor = (type: 'VEC2' | 'VEC3' | 'SCALAR', array: Float32Array<ArrayBuffer> | Uint32Array<ArrayBuffer>) => doc.createAccessor().setType(type).setArray(array).setBuffer(buffer);
  const n = options.grid ?? 1;
  const vertices: [number, number][] = [];
  for (let j = 0; j <= n; j++) for (let i = 0; i <= n; i++) vertices.push([-1 + (2 * i) / n, -1 + (2 * j) / n]);
  const indices: number[] = [];
  for (let j = 0; j < n; j++) {
    for (let i = 0; i < n; i++) {
      const v = j * (n + 1) + i;
      indices.push(v, v + 1, v + n + 2, v, v + n + 2, v + n + 1);
    }
  }
  const material = doc.createMaterial('quad').setBaseColorFactor([...options.baseColorFactor, 1]).setMetallicFactor(0).setRoughnessFactor(1);
  const prim = doc.createPrimitive()
    .setAttribute('POSITION', accessor('VEC3', Float32Array.from(vertices.flatMap(([x, y]) => [x, y, 0]))))
    .setIndices(accessor('SCALAR', Uint32Array.from(indices)))
    .setMaterial(material);
  if (!options.flat) prim.setAttribute('NORMAL', accessor('VEC3', Float32Array.from(vertices.flatMap(() => [0, 0, 1]))));
  if (options.uvs) prim.setAttribute('TEXCOORD_0', accessor('VEC2', Float32Array.from(vertices.flatMap(([x, y]) => [(x + 1) / 2, (1 - y) / 2]))));
  if (options.colors) prim.setAttribute('COLOR_0', accessor('VEC3', Float32Array.from(vertices.flatMap(([x]) => [(1 - x) / 2, (1 + x) / 2, 0]))));
  const scene = doc.createScene('scene').addChild(doc.createNode().setMesh(doc.createMesh('quad').addPrimitive(prim)));
  doc.getRoot().setDefaultScene(scene);
  return new WebIO().writeBinary(doc);
}
