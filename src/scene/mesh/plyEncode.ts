/**
 * TriangleMesh to binary little-endian PLY (float x y z, plus nx ny nz when
 * the mesh is smooth, plus u v when it has texture coordinates (`uvs`, as
 * they are: the PLY decoder and Mitsuba's `ply` shape read them as stored);
 * uchar/uint faces), for the Mitsuba exporter: Mitsuba's `ply` shape reads
 * it and shades smooth exactly when normals are present.
 */
import type { TriangleMesh } from '../types';

export function encodePly(mesh: TriangleMesh): Uint8Array {
  const vertexCount = mesh.positions.length / 3;
  const triangleCount = mesh.indices.length / 3;
  const smooth = mesh.normals !== null;
  const uvs = mesh.uvs ?? null;
  const header = [
    'ply',
    'format binary_little_endian 1.0',
    'comment written by pathtrace',
    `element vertex ${vertexCount}`,
    'property float x', 'property float y', 'property float z',
    ...(smooth ? ['property float nx', 'property float ny', 'property float nz'] : []),
    ...(uvs ? ['property float u', 'property float v'] : []),
    `element face ${triangleCount}`,
    'property list uchar uint vertex_indices',
    'end_header',
    '',
  ].join('\n');
  const headerBytes = new TextEncoder().encode(header);
  const vertexSize = (smooth ? 24 : 12) + (uvs ? 8 : 0);
  const out = new Uint8Array(headerBytes.length + vertexCount * vertexSize + triangleCount * 13);
  out.set(headerBytes);
  const view = new DataView(out.buffer);
  let offset = headerBytes.length;
  for (let v = 0; v < vertexCount; v++) {
    for (let k = 0; k < 3; k++, offset += 4) view.setFloat32(offset, mesh.positions[v * 3 + k], true);
    if (mesh.normals) for (let k = 0; k < 3; k++, offset += 4) view.setFloat32(offset, mesh.normals[v * 3 + k], true);
    if (uvs) for (let k = 0; k < 2; k++, offset += 4) view.setFloat32(offset, uvs[v * 2 + k], true);
  }
  for (let t = 0; t < triangleCount; t++) {
    view.setUint8(offset++, 3);
    for (let k = 0; k < 3; k++, offset += 4) view.setUint32(offset, mesh.indices[t * 3 + k], true);
  }
  return out;
}
