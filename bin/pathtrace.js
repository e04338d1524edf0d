#!/usr/bin/env node
// The `pathtrace` command. The CLI itself is built to dist/cli by `npm run build`.
let cli;
try {
  cli = await import('../dist/cli/main.js');
} catch (error) {
  if (error?.code === 'ERR_MODULE_NOT_FOUND' && String(error.message).includes('dist/cli/main.js')) {
    process.stderr.write('pathtrace: the CLI is not built (dist/cli/main.js is missing); run `npm run build` first\n');
    process.exit(1);
  }
  throw error;
}
await cli.main();
