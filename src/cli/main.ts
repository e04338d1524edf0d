/**
 * The `pathtrace` command line: render, scene, validate and export-mitsuba.
 *
 * `run(argv, options)` is the whole program as a function: it never calls
 * process.exit, prints nothing but what its streams are given, and returns the
 * exit code (0 ok, 2 bad arguments / invalid scene / bad output path,
 * 1 rendering failure). Tests inject a fake session module; the real one
 * (src/node/session.ts, which drives headless Chromium) is imported lazily so
 * `validate` never loads Playwright.
 */
import { Command, CommanderError, Option } from 'commander';
import { pathToFileURL } from 'node:url';
import pkg from '../../package.json';
import { DEFAULT_SPP } from './args';
import { enableCompileCache } from './compileCache';
import { mark } from '../node/timing';
import { describeError, EXIT_USAGE, oneLine } from './errors';
import { exportMitsubaCommand, type RawExportOptions } from './exportMitsuba';
import type { ProgressStream } from './progress';
import { sceneCommand, type RawSceneOptions } from './model';
import { renderCommand, type SessionModule } from './render';
import { MODEL_IMAGE } from '../scene/modelScene';
import { validateCommand, type TextSink } from './validate';

export interface RunOptions {
  stdout?: TextSink;
  /** Progress bar (only when isTTY), summary and error lines go here. */
  stderr?: ProgressStream;
  env?: NodeJS.ProcessEnv;
  /** Directory for the default PNG; default: the current directory. */
  cwd?: string;
  /** Loads the Chromium session module; tests pass a fake. */
  loadSession?: () => Promise<SessionModule>;
  /** Clock in seconds, for tests. */
  now?: () => number;
}

const defaultLoadSession = (): Promise<SessionModule> => {
  // Playwright is most of the CLI's start-up: compile it from V8's cache.
  enableCompileCache();
  return import('../node/session');
};

const CAMERA_HELP = "model files: look through the glTF file's camera N (default: its first) instead of the framed default camera";
const ENV_HELP = 'model files: light with this environment map (.hdr, .exr; intensity 1) instead of the bundled studio map, or none: a uniform white sky';

function buildProgram(io: Required<Pick<RunOptions, 'stdout' | 'stderr'>>, options: RunOptions): Command {
  const program = new Command('pathtrace')
    .description('Headless WebGL2 path tracer: renders scene JSON files through Chromium.')
    .version(pkg.version, '-V, --version')
    .exitOverride()
    .configureOutput({
      writeOut: (text) => void io.stdout.write(text),
      writeErr: (text) => void io.stderr.write(text),
      // Commander's own errors (unknown option, missing argument): one line.
      outputError: (text, write) => write(`${oneLine(text)}\n`),
    });

  const loadSession = async (): Promise<SessionModule> => {
    try {
      return await (options.loadSession ?? defaultLoadSession)();
    } catch (error) {
      throw Object.assign(new Error(`cannot load the renderer: ${(error as Error)?.message ?? error}`), { cause: error });
    }
  };

  program
    .command('render')
    .description('render a scene, or a model file in a default scene, to a PNG (tone-mapped sRGB) and optionally a PFM (linear radiance)')
    .argument('<scene>', 'scene file (JSON, scene format version 1 to 3), or a model file (.glb, .gltf, .obj, .ply) to render in a default scene')
    .option('-o, --output <file>', 'PNG output (default: SCENE basename .png in the current directory)')
    .option('--hdr <file>', 'also write linear radiance as PFM')
    .option('--spp <n>', `samples per pixel (default: ${DEFAULT_SPP})`)
    .addOption(new Option('--time <seconds>', 'render for this long instead of a sample count (at least 1 spp)'))
    .option('--seed <n>', 'random seed, a non-negative integer (default: 0)')
    .option('--width <px>', "image width (default: the scene's; alone, keeps the scene's aspect)")
    .option('--height <px>', "image height (default: the scene's; alone, keeps the scene's aspect)")
    .option('--exposure <ev>', 'exposure in stops: displayed = radiance * 2^ev (default: 0)')
    .option('--tonemap <name>', 'tone-mapping operator, e.g. none, aces (default: none)')
    .option('--adaptive', 'adaptive sampling: after 4 spp, spend the samples where the image is noisiest (8x8-pixel cells); --spp is then the mean per pixel')
    .option('--denoise', "denoise the final image with Open Image Denoise's network: the PNG and --hdr are the denoised image")
    .option('--aov <albedo.pfm,normal.pfm>', "also write the denoiser's guides as PFM: albedo (linear, [0,1]) and normal ([-1,1], zero for the sky)")
    .option('--camera [n]', CAMERA_HELP)
    .option('--env <file|none>', ENV_HELP)
    .action(async (scene: string, raw: Record<string, string | undefined>) => {
      mark('cli loaded');
      const session = await loadSession();
      await renderCommand(scene, raw, { session, stderr: io.stderr, cwd: options.cwd, now: options.now });
    });

  program
    .command('scene')
    .description('print the scene `render MODEL` renders for a model file (JSON; paths relative to the current directory, or to -o)')
    .argument('<model>', 'model file: .glb, .gltf, .obj or .ply')
    .option('-o, --output <file>', 'write the scene here instead of stdout (its paths relative to this file)')
    .option('--width <px>', `image width (default: ${MODEL_IMAGE.width}; alone, keeps ${MODEL_IMAGE.width}:${MODEL_IMAGE.height})`)
    .option('--height <px>', `image height (default: ${MODEL_IMAGE.height}; alone, keeps ${MODEL_IMAGE.width}:${MODEL_IMAGE.height})`)
    .option('--camera [n]', CAMERA_HELP)
    .option('--env <file|none>', ENV_HELP)
    .action(async (model: string, raw: RawSceneOptions) => {
      await sceneCommand(model, raw, { stdout: io.stdout, stderr: io.stderr, cwd: options.cwd });
    });

  program
    .command('validate')
    .description('check a scene file; prints one `path: message` line per problem')
    .argument('<scene>', 'scene file (JSON)')
    .action(async (scene: string) => {
      await validateCommand(scene, io.stdout);
    });

  program
    .command('export-mitsuba')
    .description('convert a scene to a Mitsuba 3 XML scene (stdout unless -o; meshes and baked textures are written beside it)')
    .argument('<scene>', 'scene file (JSON)')
    .option('-o, --output <file>', 'XML output file')
    .option('--spp <n>', 'sampler sample count')
    .option('--seed <n>', 'sampler seed')
    .option('--width <px>', "film width (default: the scene's)")
    .option('--height <px>', "film height (default: the scene's)")
    .action(async (scene: string, raw: RawExportOptions) => {
      await exportMitsubaCommand(scene, raw, io.stdout, io.stderr);
    });

  return program;
}

/** Runs the CLI on `argv` (the arguments after the program name) and returns the exit code. */
export async function run(argv: readonly string[], options: RunOptions = {}): Promise<number> {
  const io = { stdout: options.stdout ?? process.stdout, stderr: options.stderr ?? process.stderr };
  const program = buildProgram(io, options);
  try {
    await program.parseAsync([...argv], { from: 'user' });
    return 0;
  } catch (error) {
    if (error instanceof CommanderError) {
      // Commander has printed help, the version or its one-line error already.
      return error.exitCode === 0 ? 0 : EXIT_USAGE;
    }
    const { exitCode, lines } = describeError(error, options.env ?? process.env);
    for (const line of lines) io.stderr.write(`${line}\n`);
    return exitCode;
  }
}

/** Entry point when this file is the program (node dist/cli/main.js, or bin/pathtrace.js). */
export async function main(argv: readonly string[] = process.argv.slice(2)): Promise<void> {
  // `pathtrace export-mitsuba x.json | head` closes stdout early: not an error.
  process.stdout.on('error', (error: NodeJS.ErrnoException) => {
    if (error.code === 'EPIPE') process.exit(process.exitCode ?? 0);
  });
  const code = await run(argv);
  process.exitCode = code;
  // If a stray handle (a browser that would not die) keeps the event loop
  // alive, leave anyway; the unref'd timer never fires on a normal exit.
  setTimeout(() => process.exit(code), 3000).unref();
}

const invokedDirectly = process.argv[1] !== undefined && import.meta.url === pathToFileURL(process.argv[1]).href;
if (invokedDirectly) void main();
