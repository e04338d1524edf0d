/**
 * Fixture for the conductor's furnace test (src/materials/conductor/conductor.test.ts):
 * Mitsuba 3's own directional albedo of rough conductors, through our
 * exporter's BSDF. Writes the cases with their Mitsuba XML, then runs
 * scripts/mitsuba-albedo.py (needs `pip install mitsuba`), which adds
 * Mitsuba's albedo at each view angle.
 *   npx tsx scripts/make-conductor-furnace.ts
 */
import { execFileSync } from 'node:child_process';
import { writeFileSync } from 'node:fs';
import { materialBsdf, normalizeMaterial, materialSchema } from '../src/materials/registry';
import { serializeXml } from '../src/scene/mitsubaXml';

const CASES = [
  { type: 'conductor', metal: 'Au', roughness: 0.3 },
  { type: 'conductor', metal: 'Cu', roughness: 0.7 },
  { type: 'conductor', metal: 'none', roughness: 1 },
  { type: 'conductor', eta: [0.2, 0.9, 1.1], k: [3.9, 2.45, 2.1], roughness: 0.5, color: [1, 0.9, 0.8] },
];
const THETAS = [0, 45, 75];

const out = CASES.map((input) => {
  const material = normalizeMaterial(materialSchema(input.type)!.parse(input) as Record<string, unknown>);
  const lines: string[] = [];
  serializeXml(materialBsdf(material), 0, lines);
  return { material: input, xml: lines.join('\n'), thetas: THETAS };
});
const path = new URL('../test/fixtures/furnace-conductor/cases.json', import.meta.url);
writeFileSync(path, JSON.stringify(out, null, 2));
execFileSync('python3', [new URL('./mitsuba-albedo.py', import.meta.url).pathname, path.pathname], { stdio: 'inherit' });
