/**
 * Export a scene JSON as a Mitsuba 3 XML scene.
 *   npx tsx bench/mitsuba/export.ts SCENE.json OUT.xml [--spp N] [--seed N] [--width W --height H]
 */
import { readFileSync, writeFileSync } from 'node:fs';
import { toMitsubaXml, type MitsubaExportOptions } from '../../src/scene/mitsuba';
import { parseSceneText, SceneError } from '../../src/scene/schema';

function usage(): never {
  console.error('usage: export.ts SCENE.json OUT.xml [--spp N] [--seed N] [--width W] [--height H]');
  process.exit(2);
}

function main(argv: string[]): void {
  const positional: string[] = [];
  const opts: MitsubaExportOptions = {};
  for (let i = 0; i < argv.length; i++) {
    const arg = argv[i];
    const key = { '--spp': 'spp', '--seed': 'seed', '--width': 'width', '--height': 'height' }[arg] as
      | 'spp' | 'seed' | 'width' | 'height'
      | undefined;
    if (key) {
      const value = Number(argv[++i]);
      if (!Number.isInteger(value) || value < 0) usage();
      opts[key] = value;
    } else if (arg.startsWith('-')) usage();
    else positional.push(arg);
  }
  if (positional.length !== 2) usage();
  const [input, output] = positional;
  let scene;
  try {
    scene = parseSceneText(readFileSync(input, 'utf8'));
  } catch (error) {
    if (!(error instanceof SceneError)) throw error;
    console.error(`${input}:\n${error.message}`);
    process.exit(1);
  }
  writeFileSync(output, toMitsubaXml(scene, opts));
}

main(process.argv.slice(2));
