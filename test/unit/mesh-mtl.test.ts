/**
 * OBJ materials from MTL files (scene format "Meshes in version 3"):
 * parseMtl maps each key to the principled material a scene with those
 * keys parses to, the map options -o/-s land in the mesh's turned-over
 * coordinates, `usemtl` groups become per-triangle indices (kept in step
 * with the degenerate triangles finalize drops) and a missing MTL is a
 * warning, not an error.
 */
import { readFileSync } from 'node:fs';
import { describe, expect, it } from 'vitest';
import { materialJson, materialSchema, normalizeMaterial, type PrincipledMaterial } from '../../src/materials/registry';
import { AssetError } from '../../src/scene/assetError';
import { decodeMesh } from '../../src/scene/mesh';
import { finalizeMesh } from '../../src/scene/mesh/finalize';
import { joinPath, parseMtl, uvOf } from '../../src/scene/mesh/mtl';
import { readMeshFile } from '../../src/node/readMesh';
import { transformUv } from '../../src/scene/texture/bitmapLookup';
import type { FileMaterials } from '../../src/scene/types';

const FIXTURES = new URL('../fixtures/meshes/', import.meta.url);
const text = (s: string) => new TextEncoder().encode(s);
/** The material a scene's `{"type": "principled", ...keys}` parses to. */
const principled = (keys: Record<string, unknown>): PrincipledMaterial =>
  normalizeMaterial(materialSchema('principled')!.parse({ type: 'principled', ...keys }) as Record<string, unknown>) as PrincipledMaterial;
const only = (mtl: string, path = 'a.mtl') => {
  const parsed = parseMtl(mtl, path);
  expect(parsed.materials.size).toBe(1);
  return { material: [...parsed.materials.values()][0], warnings: parsed.warnings };
};
const NO_UV = { offset: [0, 0], scale: [1, 1], rotation: 0 };

describe('parseMtl: each key as the principled key it names', () => {
  it('an empty block is the default principled material', () => {
    expect(only('newmtl plain\n').material).toEqual(principled({}));
  });

  it('Kd: the base color as given, clamped to [0, 1]; one number is grey', () => {
    expect(only('newmtl m\nKd 0.2 0.4 0.6').material).toEqual(principled({ baseColor: [0.2, 0.4, 0.6] }));
    expect(only('newmtl m\nKd 2 -1 0.5').material).toEqual(principled({ baseColor: [1, 0, 0.5] }));
    expect(only('newmtl m\nKd 0.3').material).toEqual(principled({ baseColor: [0.3, 0.3, 0.3] }));
  });

  it('map_Kd replaces Kd (texture scale 1)', () => {
    const { material } = only('newmtl m\nKd 0.2 0.4 0.6\nmap_Kd wood.png');
    expect(material).toEqual(principled({ baseColor: { image: 'wood.png' } }));
  });

  it('Pr, Pm and their maps (one channel, "r" by default; the map replaces the number)', () => {
    expect(only('newmtl m\nPr 0.25\nPm 0.75').material).toEqual(principled({ roughness: 0.25, metallic: 0.75 }));
    expect(only('newmtl m\nPr 7\nPm -2').material).toEqual(principled({ roughness: 1, metallic: 0 }));
    const { material } = only('newmtl m\nPr 0.25\nmap_Pr rough.png\nmap_Pm -imfchan b orm.png');
    expect(material).toEqual(principled({ roughness: { image: 'rough.png', channel: 'r' }, metallic: { image: 'orm.png', channel: 'b' } }));
  });

  it('Ke: emission with intensity 1 (above 1 kept); all zero: none; map_Ke: a textured emission color', () => {
    expect(only('newmtl m\nKe 2 1 0.5').material).toEqual(principled({ emission: { color: [2, 1, 0.5], intensity: 1 } }));
    expect(only('newmtl m\nKe 0 0 0').material.emission).toBeUndefined();
    const { material } = only('newmtl m\nKe 0 0 0\nmap_Ke glow.png');
    expect(material).toEqual(principled({ emission: { color: { image: 'glow.png' }, intensity: 1 } }));
    expect(material.emission?.texture?.image).toBe('glow.png');
  });

  it('map_Bump, bump and norm: the normal map, -bm its scale; norm wins over map_Bump', () => {
    expect(only('newmtl m\nmap_Bump -bm 0.4 n.png').material).toEqual(principled({ normalMap: { image: 'n.png', scale: 0.4 } }));
    expect(only('newmtl m\nbump n.png').material).toEqual(principled({ normalMap: { image: 'n.png', scale: 1 } }));
    expect(only('newmtl m\nnorm a.png\nmap_Bump b.png').material).toEqual(principled({ normalMap: { image: 'a.png', scale: 1 } }));
  });

  it('d, Tr (1 - d, only without d) and map_d (alpha of the map_Kd image, else "r")', () => {
    expect(only('newmtl m\nd 0.3').material).toEqual(principled({ opacity: 0.3 }));
    expect(only('newmtl m\nTr 0.25').material).toEqual(principled({ opacity: 0.75 }));
    expect(only('newmtl m\nTr 0.25\nd 0.5').material).toEqual(principled({ opacity: 0.5 }));
    expect(only('newmtl m\nmap_Kd c.png\nmap_d c.png').material.opacity).toEqual(principled({ opacity: { image: 'c.png', channel: 'a' } }).opacity);
    expect(only('newmtl m\nmap_Kd c.png\nmap_d mask.png').material.opacity).toEqual(principled({ opacity: { image: 'mask.png', channel: 'r' } }).opacity);
    expect(only('newmtl m\nmap_d -imfchan m mask.png').material.opacity).toEqual(principled({ opacity: { image: 'mask.png', channel: 'a' } }).opacity);
  });

  it('Ni: the ior, clamped to 4; at or below 1 ignored with a warning', () => {
    expect(only('newmtl m\nNi 1.45').material).toEqual(principled({ ior: 1.45 }));
    expect(only('newmtl m\nNi 9').material).toEqual(principled({ ior: 4 }));
    expect(only('newmtl m\nNi 1.005').material).toEqual(principled({ ior: 1.01 }));
    const placeholder = only('newmtl m\nNi 1');
    expect(placeholder.material).toEqual(principled({}));
    expect(placeholder.warnings.join('\n')).toMatch(/a\.mtl: material "m": Ni 1 .*ignored/);
  });

  it('keywords in any case; several materials; a name defined twice keeps its last block', () => {
    const parsed = parseMtl('newmtl a\nKD 1 0 0\nMAP_KD x.png\nnewmtl b b\nkd 0 1 0\nnewmtl a\nKd 0 0 1', 'a.mtl');
    expect([...parsed.materials.keys()]).toEqual(['a', 'b b']);
    expect(parsed.materials.get('a')).toEqual(principled({ baseColor: [0, 0, 1] }));
    expect(parsed.materials.get('b b')).toEqual(principled({ baseColor: [0, 1, 0] }));
  });
});

describe('parseMtl: map options and texture paths', () => {
  it('a material the principled schema refuses is the default one, with the schema\'s message', () => {
    const { material, warnings } = only(`newmtl long\nKd 0.1 0.2 0.3\nmap_Pr ${'x'.repeat(5000)}.png`);
    expect(material).toEqual(principled({}));
    expect(warnings).toEqual([expect.stringMatching(/^a\.mtl: material "long": roughness(\.image)?: .*: the default material$/)]);
  });

  it('-o and -s become the uv transform of the turned-over coordinates (w = 1 - v)', () => {
    const { material } = only('newmtl m\nmap_Kd -o 0.25 0.5 0 -s 2 4 1 c.png');
    const uv = (material as { baseColor: { uv: { offset: number[]; scale: number[]; rotation: number } } }).baseColor.uv;
    expect(uv).toEqual(uvOf({ offset: [0.25, 0.5], scale: [2, 4] }));
    // The file looks up (o_u + s_u u, o_v + s_v v) with v up from the bottom; the renderer
    // looks up transformUv((u, 1 - v)) with v' down from the top: the same texel.
    for (const [u, v] of [[0, 0], [1, 0], [0, 1], [0.3, 0.7], [-1.5, 2.25]]) {
      const [fu, fv] = [0.25 + 2 * u, 0.5 + 4 * v];
      const [mu, mv] = transformUv([u, 1 - v], uv as never);
      expect(mu).toBeCloseTo(fu, 12);
      expect(mv).toBeCloseTo(1 - fv, 12);
    }
    expect(uv).toEqual({ offset: [0.25, 1 - 4 - 0.5], scale: [2, 4], rotation: 0 });
  });

  it('one value of -o or -s is u alone (v: offset 0, scale 1); no options: the identity', () => {
    expect(uvOf({ offset: [0, 0], scale: [1, 1] })).toEqual(NO_UV);
    const { material } = only('newmtl m\nmap_Pr -o 0.5 -s 3 r.png');
    expect((material as { roughness: { uv: unknown } }).roughness.uv).toEqual({ offset: [0.5, 0], scale: [3, 1], rotation: 0 });
  });

  it('other options are ignored with a warning naming them; -imfchan on a color map too', () => {
    const { material, warnings } = only('newmtl m\nmap_Kd -clamp on -blendu off -mm 0 1 -imfchan r -t 1 2 -bm 3 c.png');
    expect(material).toEqual(principled({ baseColor: { image: 'c.png' } }));
    const all = warnings.join('\n');
    for (const option of ['-clamp on', '-blendu off', '-mm 0 1', '-imfchan r', '-t 1 2', '-bm 3']) expect(all).toContain(`option ${option} is ignored`);
    expect(all).toMatch(/^a\.mtl: line 2: map_Kd option -clamp/m);
  });

  it('an image name with spaces; a map without an image is ignored with a warning', () => {
    expect(only('newmtl m\nmap_Kd -s 2 2 my wood.png').material.baseColor).toMatchObject({ image: 'my wood.png' });
    const { material, warnings } = only('newmtl m\nKd 0.5 0.5 0.5\nmap_Kd -clamp');
    expect(material).toEqual(principled({ baseColor: [0.5, 0.5, 0.5] }));
    expect(warnings.join('\n')).toContain('names no image');
  });

  it('images relative to the MTL become relative to the OBJ (the MTL\'s folder joined in front)', () => {
    const { material } = only('newmtl m\nmap_Kd ..\\tex\\wood.png\nnorm ./n.png', 'mats/sub/a.mtl');
    expect(material.baseColor).toMatchObject({ image: 'mats/tex/wood.png' });
    expect((material as { normalMap: { image: string } }).normalMap.image).toBe('mats/sub/n.png');
    expect(joinPath('', '../up.png')).toBe('../up.png');
    expect(joinPath('a/', '../../up.png')).toBe('../up.png');
    expect(joinPath('a/', '/abs/x.png')).toBe('/abs/x.png');
  });

  it('ignored statements are listed once; unknown words are only counted', () => {
    const { warnings } = only('newmtl m\nKs 1 1 1\nNs 10\nKs 0 0 0\nillum 2\nroot:x:0:0\nfoo bar');
    expect(warnings).toContain('a.mtl: ignored (no principled equivalent): Ks, Ns, illum');
    expect(warnings).toContain('a.mtl: 2 line(s) with statements MTL does not define: ignored');
    expect(warnings.join('\n')).not.toContain('root');
  });

  it('bad numbers and statements before newmtl are warnings, never errors', () => {
    const parsed = parseMtl('Kd 1 0 0\nnewmtl m\nKd 1 x 0\nPr nan\nKd spectral a.rfl\nd', 'a.mtl');
    expect(parsed.materials.get('m')).toEqual(principled({}));
    expect(parsed.warnings.length).toBe(5);
  });
});

describe('OBJ with mtllib and usemtl', () => {
  const fixture = (name: string) => new Uint8Array(readFileSync(new URL(name, FIXTURES)));
  const resolveResource = async (uri: string) => fixture(decodeURIComponent(uri));
  const cube = () => decodeMesh(fixture('mtl-cube.obj'), 'mtl-cube.obj', { resolveResource });

  it('faces get their usemtl material; before any usemtl or unknown: the default; the degenerate triangle is dropped with its entry', async () => {
    const mesh = await cube();
    const fm = mesh.fileMaterials as FileMaterials;
    expect(mesh.indices.length / 3).toBe(12); // 13 triangles in the file, one of zero area
    expect(fm.triangles.length).toBe(12);
    expect(fm.materials.map((m) => m.name)).toEqual(['', 'red', 'brick']);
    expect([...fm.triangles]).toEqual([0, 0, 1, 1, 1, 1, 2, 2, 2, 2, 0, 0]);
    expect(fm.images.size).toBe(0);
    expect(fm.materials.every((m) => m.uvSet === 0 && !m.vertexColors)).toBe(true);
    expect(fm.materials[0].material).toEqual(principled({}));
    expect(fm.materials[1].material).toEqual(principled({ baseColor: [0.8, 0.1, 0.05], roughness: 0.3, metallic: 1, ior: 1.45 }));
    expect(fm.materials[2].material).toEqual(
      principled({
        baseColor: { image: 'mtl-cube/brick.png', uv: uvOf({ offset: [0.25, 0.5], scale: [2, 4] }) },
        normalMap: { image: 'mtl-cube/brick.png', scale: 0.5 },
        opacity: 0.75,
      }),
    );
    expect(mesh.warnings).toEqual([
      'mtl-cube/mtl-cube.mtl: ignored (no principled equivalent): Ka, Ks, Ns, illum',
      'usemtl "nowhere": no MTL file defines it: the default material',
    ]);
  });

  it('the triangles are those of the same file without materials', async () => {
    const plain = new TextDecoder().decode(fixture('mtl-cube.obj')).replace(/^(mtllib|usemtl).*$/gm, '');
    const without = await decodeMesh(text(plain), 'plain.obj');
    const mesh = await cube();
    expect(without.fileMaterials).toBeUndefined();
    expect(mesh.indices).toEqual(without.indices);
    expect(mesh.positions).toEqual(without.positions);
    expect(mesh.uvs).toEqual(without.uvs);
  });

  it('the CLI reader resolves the MTL beside the file', async () => {
    const mesh = await readMeshFile(new URL('mtl-cube.obj', FIXTURES).pathname);
    expect(mesh.fileMaterials?.materials.map((m) => m.name)).toEqual(['', 'red', 'brick']);
  });

  it('a missing MTL, or no resolver: a warning, no file materials, never an error', async () => {
    const missing = async (uri: string): Promise<Uint8Array> => {
      throw new Error(`no such file ${uri}`);
    };
    for (const options of [{ resolveResource: missing }, {}]) {
      const mesh = await decodeMesh(fixture('mtl-cube.obj'), 'mtl-cube.obj', options);
      expect(mesh.fileMaterials).toBeNull();
      expect(mesh.warnings).toEqual(['mtl-cube/mtl-cube.mtl not found: the default material']);
      expect(mesh.indices.length / 3).toBe(12);
    }
  });

  it('no mtllib or usemtl: no fileMaterials and no warnings (as before)', async () => {
    const mesh = await decodeMesh(fixture('uvquad.obj'), 'uvquad.obj', { resolveResource });
    expect('fileMaterials' in mesh).toBe(false);
    expect('warnings' in mesh).toBe(false);
  });

  it('usemtl without mtllib: a warning and no file materials', async () => {
    const mesh = await decodeMesh(text('v 0 0 0\nv 1 0 0\nv 0 1 0\nusemtl red\nf 1 2 3'), 'a.obj', { resolveResource });
    expect(mesh.fileMaterials).toBeNull();
    expect(mesh.warnings).toEqual(['usemtl without mtllib: the default material']);
  });

  it('an mtllib naming several files reads each; a name with spaces is tried whole first; names are URIs to the resolver', async () => {
    const files: Record<string, string> = { 'a.mtl': 'newmtl A\nKd 1 0 0', 'b.mtl': 'newmtl B\nKd 0 1 0', 'my mats.mtl': 'newmtl C\nKd 0 0 1' };
    const asked: string[] = [];
    const resolve = async (uri: string) => {
      asked.push(uri);
      const content = files[decodeURIComponent(uri)];
      if (content === undefined) throw new Error('no such file');
      return text(content);
    };
    const obj = 'mtllib a.mtl b.mtl\nmtllib my mats.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nusemtl B\nf 1 2 3\nusemtl C\nf 1 3 2\nusemtl A\nf 2 1 3';
    const mesh = await decodeMesh(text(obj), 'a.obj', { resolveResource: resolve });
    expect(mesh.fileMaterials?.materials.map((m) => m.name)).toEqual(['B', 'C', 'A']);
    expect([...mesh.fileMaterials!.triangles]).toEqual([0, 1, 2]);
    expect(mesh.warnings).toBeUndefined();
    expect(asked).toContain('my%20mats.mtl');
  });

  it('finalize refuses per-triangle materials that do not match the triangles', () => {
    const raw = { positions: [0, 0, 0, 1, 0, 0, 0, 1, 0], normals: null, indices: [0, 1, 2] };
    const material = { name: '', material: principled({}), uvSet: 0 as const, vertexColors: false };
    const fileMaterials = (triangles: number[]) => ({ materials: [material], triangles: Uint16Array.from(triangles), images: new Map() });
    expect(() => finalizeMesh({ ...raw, fileMaterials: fileMaterials([0, 0]) })).toThrow(AssetError);
    expect(() => finalizeMesh({ ...raw, fileMaterials: fileMaterials([1]) })).toThrow(/material 1, but the file has 1 materials/);
    expect([...finalizeMesh({ ...raw, fileMaterials: fileMaterials([0]) }).fileMaterials!.triangles]).toEqual([0]);
  });
});

describe('parseMtl never throws', () => {
  it('on random statements of MTL words, numbers and junk (seeded)', () => {
    let seed = 12345;
    const random = () => ((seed = (seed * 1103515245 + 12345) >>> 0) / 2 ** 32);
    const pick = <T>(items: readonly T[]) => items[Math.floor(random() * items.length)];
    const words = ['newmtl', 'Kd', 'Ke', 'Pr', 'Pm', 'd', 'Tr', 'Ni', 'map_Kd', 'map_Pr', 'map_d', 'map_Bump', 'norm', 'map_Ke', 'Ks', 'xyz'];
    const args = ['-o', '-s', '-bm', '-imfchan', '-clamp', '-mm', '-', '1', '-2.5', 'NaN', '1e400', 'on', 'm', 'a.png', '..\\b.png', '', '#'];
    for (let round = 0; round < 300; round++) {
      const lines = Array.from({ length: 1 + Math.floor(random() * 12) }, () => [pick(words), ...Array.from({ length: Math.floor(random() * 6) }, () => pick(args))].join(' '));
      const parsed = parseMtl(lines.join(random() < 0.5 ? '\n' : '\r\n'), 'x/y.mtl');
      for (const material of parsed.materials.values()) expect(principled(materialJson(material, 3))).toEqual(material); // a valid material of the scene format
    }
  });
});
