// The npm library: one ES module with the shaders inlined.
import { resolve } from 'node:path';
import { defineConfig } from 'vite';

export default defineConfig({
  build: {
    outDir: 'dist/lib',
    emptyOutDir: true,
    target: 'es2022',
    lib: {
      entry: resolve(import.meta.dirname, 'src/index.ts'),
      formats: ['es'],
      fileName: () => 'pathtrace.js',
    },
    rollupOptions: { external: ['gl-matrix', 'zod'] },
  },
});
