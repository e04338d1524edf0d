/**
 * Object to world for meshes: `translate * Rz * Ry * Rx * scale` (degrees,
 * world axes), normals by the inverse transpose; checked on hand-worked
 * cases and, with fast-check, against the defining property of a normal
 * (it stays perpendicular to the transformed surface and on its outer side).
 */
import fc from 'fast-check';
import { describe, expect, it } from 'vitest';
import { applyMatrix, inverseAffine, meshToWorldMatrix, transformMesh } from '../../src/scene/mesh/transform';

const apply = (m: Float64Array, p: number[]) => Array.from(applyMatrix(m, p, null).positions);
const close = (a: number[], b: number[]) => a.forEach((v, i) => expect(Math.abs(v - b[i])).toBeLessThan(1e-12));

describe('meshToWorldMatrix', () => {
  it('applies scale, then x, y, z rotations, then the translation', () => {
    // Rx(90): y -> z; then Ry(90): z -> x.
    close(apply(meshToWorldMatrix({ rotation: [90, 90, 0] }), [0, 1, 0]), [1, 0, 0]);
    // Rz(90) last: x -> y.
    close(apply(meshToWorldMatrix({ rotation: [0, 0, 90] }), [1, 0, 0]), [0, 1, 0]);
    close(apply(meshToWorldMatrix({ rotation: [0, 90, 90] }), [0, 0, 1]), [0, 1, 0]);
    close(apply(meshToWorldMatrix({ position: [1, 2, 3], scale: [2, 3, 4] }), [1, 1, 1]), [3, 5, 7]);
    close(apply(meshToWorldMatrix({ position: [1, 0, 0], rotation: [0, 0, 90], scale: 2 }), [1, 0, 0]), [1, 2, 0]);
  });

  it('keeps normals perpendicular to the transformed surface, on the same side (fast-check)', () => {
    const angle = fc.double({ min: -360, max: 360, noNaN: true });
    const positive = fc.double({ min: 0.05, max: 20, noNaN: true });
    fc.assert(
      fc.property(fc.tuple(angle, angle, angle), fc.tuple(positive, positive, positive), (rotation, scale) => {
        const mesh = { positions: Float32Array.of(0, 0, 0, 1, 0.2, 0, 0.3, 1, 0), normals: Float32Array.of(0, 0, 1, 0, 0, 1, 0, 0, 1), indices: Uint32Array.of(0, 1, 2) };
        const world = transformMesh(mesh, { position: [1, -2, 3], rotation, scale });
        const p = world.positions;
        const e1 = [0, 1, 2].map((k) => p[3 + k] - p[k]);
        const e2 = [0, 1, 2].map((k) => p[6 + k] - p[k]);
        const cross = [e1[1] * e2[2] - e1[2] * e2[1], e1[2] * e2[0] - e1[0] * e2[2], e1[0] * e2[1] - e1[1] * e2[0]];
        const length = Math.hypot(...cross);
        const n = Array.from(world.normals!.subarray(0, 3));
        expect(Math.abs(Math.hypot(...n) - 1)).toBeLessThan(1e-6);
        const cos = (n[0] * cross[0] + n[1] * cross[1] + n[2] * cross[2]) / length;
        expect(cos).toBeGreaterThan(1 - 1e-4);
      }),
    );
  });

  it('a mirroring transform flips the winding so faces keep pointing along their normals', () => {
    const mesh = { positions: Float32Array.of(0, 0, 0, 1, 0, 0, 0, 1, 0), normals: null, indices: Uint32Array.of(0, 1, 2) };
    const mirror = Float64Array.of(-1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1);
    expect(applyMatrix(mirror, mesh.positions, null).mirrored).toBe(true);
    expect(Array.from(transformMesh(mesh, { scale: 1 }).indices)).toEqual([0, 1, 2]);
  });
});

describe('inverseAffine', () => {
  it('takes every point back where the matrix took it (instances: world to object)', () => {
    const angle = fc.double({ min: -360, max: 360, noNaN: true });
    const factor = fc.double({ min: 0.01, max: 100, noNaN: true });
    const coordinate = fc.double({ min: -100, max: 100, noNaN: true });
    fc.assert(
      fc.property(fc.tuple(coordinate, coordinate, coordinate), fc.tuple(angle, angle, angle), fc.tuple(factor, factor, factor), fc.tuple(coordinate, coordinate, coordinate), (position, rotation, scale, p) => {
        const m = meshToWorldMatrix({ position, rotation, scale });
        const back = apply(inverseAffine(m), apply(m, p));
        back.forEach((v, k) => expect(Math.abs(v - p[k])).toBeLessThan(1e-9 * (1 + Math.abs(p[k])) * Math.max(...scale) / Math.min(...scale)));
      }),
    );
  });
});
