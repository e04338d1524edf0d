/**
 * Fixture for the principled material's furnace test
 * (src/materials/principled/principled.test.ts): Mitsuba 3's own
 * directional albedo of principled BSDFs, through our exporter's BSDF, from
 * outside (theta < 90) and, for transmitting ones, from inside the solid
 * (theta > 90). Writes the cases with their Mitsuba XML, then runs
 * scripts/mitsuba-albedo.py (needs `pip install mitsuba`), which adds
 * Mitsuba's albedo at each view angle.
 *   npx tsx scripts/make-principled-furnace.ts
 */
import { execFileSync } from 'node:child_process';
import { writeFileSync } from 'node:fs';
import { materialBsdf, normalizeMaterial, materialSchema } from '../src/materials/registry';
import { serializeXml } from '../src/scene/mitsubaXml';

const OUTSIDE = [0, 45, 75];
const CASES: { material: Record<string, unknown>; thetas: number[] }[] = [
  { material: { type: 'principled' }, thetas: OUTSIDE },
  { material: { type: 'principled', baseColor: [1, 0.78, 0.34], metallic: 1, roughness: 0.3 }, thetas: OUTSIDE },
  { material: { type: 'principled', baseColor: [0.75, 0.3, 0.2], metallic: 0.3, roughness: 0.4, specTint: 0.5 }, thetas: OUTSIDE },
  { material: { type: 'principled', baseColor: [0.05, 0.15, 0.6], roughness: 0.6, clearcoat: 1, clearcoatGloss: 0.8 }, thetas: OUTSIDE },
  { material: { type: 'principled', baseColor: [0.5, 0.2, 0.6], roughness: 0.9, sheen: 1, sheenTint: 0.5 }, thetas: OUTSIDE },
  { material: { type: 'principled', baseColor: [0.9, 0.95, 1], roughness: 0.3, specTrans: 1, ior: 1.45 }, thetas: [...OUTSIDE, 120, 150] },
  {
    material: { type: 'principled', baseColor: [0.6, 0.5, 0.4], metallic: 0.2, roughness: 0.5, ior: 1.6, specTint: 0.3, specTrans: 0.5, sheen: 0.5, clearcoat: 0.5, clearcoatGloss: 0.3 },
    thetas: [...OUTSIDE, 135],
  },
];

const out = CASES.map(({ material: input, thetas }) => {
  const material = normalizeMaterial(materialSchema(input.type)!.parse(input) as Record<string, unknown>);
  const lines: string[] = [];
  serializeXml(materialBsdf(material), 0, lines);
  return { material: input, xml: lines.join('\n'), thetas };
});
const path = new URL('../test/fixtures/furnace-principled/cases.json', import.meta.url);
writeFileSync(path, JSON.stringify(out, null, 2));
execFileSync('python3', [new URL('./mitsuba-albedo.py', import.meta.url).pathname, path.pathname], { stdio: 'inherit' });
