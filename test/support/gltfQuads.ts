/**
 * A small .gltf with its .bin and two PNG images beside it, made with
 * glTF-Transform and pngjs: two unit quads side by side facing +z, the left
 * one's baseColor a red image, the right one's a blue image (matte).
 */
import { Document, NodeIO } from '@gltf-transform/core';
import { PNG } from 'pngjs';

/** A 4x4 PNG of one colour. */
function png(rgb: [number, number, number]): Uint8Array {
  const image = new PNG({ width: 4, height: 4 });
  for (let i = 0; i < 16; i++) image.data.set([...rgb, 255], 4 * i);
  return new Uint8Array(PNG.sync.write(image));
}

/** Two unit quads facing +z (left x in [-1.05, -0.05], right in [0.05, 1.05]), each with a textured matte material. */
export async function quadsGltf(): Promise<Record<string, Uint8Array>> {
  const doc = new Document();
  const buffer = doc.createBuffer().setURI('quads.bin');
  const mesh = doc.createMesh();
  for (const [x0, image, name] of [[-1.05, 'red.png', 'left'], [0.05, 'blue.png', 'right']] as const) {
    const texture = doc.createTexture(name).setImage(png(image === 'red.png' ? [255, 0, 0] : [0, 0, 255])).setMimeType('image/png').setURI(image);
    const material = doc.createMaterial(name).setMetallicFactor(0).setRoughnessFactor(1).setBaseColorTexture(texture);
    const positions = [x0, -0.5, 0, x0 + 1, -0.5, 0, x0 + 1, 0.5, 0, x0, 0.5, 0];
    const accessor = (type: 'VEC2' | 'VEC3' | 'SCALAR', array: Float32Array<ArrayBuffer> | Uint16Array<ArrayBuffer>) => doc.createAccessor().setType(type).setArray(array).setBuffer(buffer);
    const primitive = doc.createPrimitive()
      .setAttribute('POSITION', accessor('VEC3', new Float32Array(positions)))
      .setAttribute('NORMAL', accessor('VEC3', new Float32Array([0, 0, 1, 0, 0, 1, 0, 0, 1, 0, 0, 1])))
      .setAttribute('TEXCOORD_0', accessor('VEC2', new Float32Array([0, 1, 1, 1, 1, 0, 0, 0])))
      .setIndices(accessor('SCALAR', new Uint16Array([0, 1, 2, 0, 2, 3])))
      .setMaterial(material);
    mesh.addPrimitive(primitive);
  }
  doc.createScene().addChild(doc.createNode().setMesh(mesh));
  const { json, resources } = await new NodeIO().writeJSON(doc, { basename: 'quads' });
  return { 'quads.gltf': new TextEncoder().encode(JSON.stringify(json)), ...resources };
}
