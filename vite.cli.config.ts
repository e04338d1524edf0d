/**
 * Builds the command line for Node: `vite build --config vite.cli.config.ts`
 * -> dist/cli/main.js (ESM). An SSR build, so Node built-ins and the package's
 * dependencies (commander, playwright-core, pngjs, ...) stay external imports
 * resolved from node_modules at run time; only our own source is bundled.
 *
 * The session module is imported lazily by main.ts and lands in its own chunk
 * beside main.js, so `import.meta.url` of every CLI chunk is in dist/cli and
 * dist/web is found at `../web` from any of them.
 */
import { existsSync, readFileSync } from 'node:fs';
import { builtinModules } from 'node:module';
import { defineConfig } from 'vite';

const entries: Record<string, string> = { main: 'src/cli/main.ts' };
// `npm run bench` runs dist/cli/bench.js: build it here when its source exists.
for (const candidate of ['bench/bench.ts', 'src/cli/bench.ts']) {
  if (existsSync(candidate)) {
    entries.bench = candidate;
    break;
  }
}

const pkg = JSON.parse(readFileSync(new URL('./package.json', import.meta.url), 'utf8')) as { dependencies?: Record<string, string> };
const dependencies = Object.keys(pkg.dependencies ?? {});
const external = [
  ...builtinModules,
  ...builtinModules.map((name) => `node:${name}`),
  ...dependencies,
  new RegExp(`^(${dependencies.map((d) => d.replace(/[.*+?^${}()|[\]\\/]/g, '\\$&')).join('|')})/`),
];

export default defineConfig({
  // Nothing from public/ belongs next to the CLI.
  publicDir: false,
  build: {
    ssr: true,
    outDir: 'dist/cli',
    emptyOutDir: true,
    target: 'node20',
    minify: false,
    sourcemap: true,
    rolldownOptions: {
      input: entries,
      external,
      output: {
        format: 'es',
        entryFileNames: '[name].js',
        chunkFileNames: '[name]-[hash].js',
      },
    },
  },
  ssr: {
    target: 'node',
    external: dependencies,
  },
});
