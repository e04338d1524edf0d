/** The path-tracing pass: adds samples to the running sums in a ping-pong pair. */
import { type CameraFrame, cameraFrame, inverseViewProjection } from '../../scene/camera';
import type { Scene } from '../../scene/types';
import { resolveFileMaterials, type RenderScene } from '../../scene/fileMaterials';
import { Program } from '../gl/program';
import { TEXTURE_UNITS } from '../gl/textureUnits';
import type { PingPong } from '../gl/targets';
import { missingAssets, type SceneAssets } from '../../scene/assets';
import type { TextureInput } from '../../scene/texture/texture';
import { areaMean, textureEmissionMeans } from '../geometry/records';
import { SceneError } from '../../scene/schema';
import { BLOCK_VEC4S, DATA_ROWS, LIGHT_CHOICE_WIDTH, SCENE_ROW_TEXELS } from '../layout/scene';
import { createDataTexture } from '../gl/dataTexture';
import { CellTable } from '../gl/cellTable';
import { AssetTextures, environmentDistribution } from './assetTextures';
import { prepareWorldMeshes, type PrebuiltBvh, type WorldMeshes } from '../geometry/world';
import { BASE_FEATURES, packScene, type SceneFeatures } from '../packScene';
import type { SamplerKind } from '../sampling';
import { featureDefines, sceneDefines } from '../shaderChunks';
import { TRACE_CHUNKS, VERTEX_CHUNKS } from '../shaderSources';
import { FULL_SCREEN, type TileRun } from '../tiles';
import type { CellGrid } from '../adaptive';

const featureKey = (f: SceneFeatures) => JSON.stringify(f);

const UNIFORM_TYPES: Record<string, string> = {
  uInverseViewProjection: 'mat4',
  uCameraPosition: 'vec3',
  uCameraRight: 'vec3',
  uCameraUp: 'vec3',
  uCameraForward: 'vec3',
  uAperture: 'float',
  uFocusDistance: 'float',
  uResolution: 'vec2',
  uMaxBounces: 'int',
  uAccumulation: 'sampler2D',
  uFirstSample: 'uint',
  uSamplesPerDraw: 'uint',
  uSeed: 'uint',
  uSceneData: 'sampler2D',
  uLightChoice: 'sampler2D',
  uTiles: 'uvec4',
  uTileGrid: 'uvec3',
  uTileList: 'bool',
  uCellSamples: 'usampler2D',
  uCellSize: 'uint',
};

const SCENE_BLOCK_BINDING = 0;

export class TracePass {
  /**
   * One program per set of features a scene uses (number of caustic guides,
   * glass; see featureDefines): SwiftShader runs every masked branch, so
   * code a scene does not need must not be compiled in. The variants for
   * 0 and 1 guide without glass are compiled up front, so common edits never
   * compile; the others once, on first use, then cached.
   */
  private readonly programs = new Map<string, Program>();
  /** The variant for the current scene. */
  private program: Program;
  private readonly sceneBuffer: WebGLBuffer;
  /**
   * The scene's tables, one RGBA32F texel per vec4 (row 0): the loops over
   * spheres index them dynamically, and in SwiftShader a texelFetch is much
   * cheaper than a dynamically indexed, bounds-checked uniform-block read
   * (per-lane conditional loads). The uniform block holds only constants.
   */
  private readonly sceneTexture: WebGLTexture;
  /** The emitter-choice tables (render/lightChoice.ts), LIGHT_CHOICE_WIDTH wide; `rows` of them. */
  private lightChoice: { texture: WebGLTexture; rows: number } | null = null;
  /** Adaptive sampling's per-cell samples (drawCells). */
  private readonly cells: CellTable;

  private readonly defines: Record<string, string | number>;
  /** The meshes prepared for the last scene (kept: the next keeps its copies where they still fit). */
  private world: WorldMeshes | null = null;
  /** The scene's decoded files on the GPU (environment map). */
  private readonly assets: AssetTextures;
  /** Textured emissions' per-triangle means, kept per mesh data and texture (records.ts). */
  private readonly emissionMeans = new WeakMap<object, Map<string, Float32Array>>();
  /** What setScene last uploaded: other passes built from the scene chunks need its camera and features. */
  private current: { scene: RenderScene; frame: CameraFrame; width: number; height: number; features: SceneFeatures } | null = null;

  constructor(
    private readonly gl: WebGL2RenderingContext,
    sampler: SamplerKind = 'kronecker',
    russianRoulette = false,
  ) {
    this.defines = sceneDefines(sampler, russianRoulette);
    this.program = this.programFor(BASE_FEATURES);
    this.programFor({ ...BASE_FEATURES, guides: 1 });
    this.assets = new AssetTextures(gl);
    this.cells = new CellTable(gl);
    this.sceneBuffer = gl.createBuffer()!;
    gl.bindBuffer(gl.UNIFORM_BUFFER, this.sceneBuffer);
    gl.bufferData(gl.UNIFORM_BUFFER, BLOCK_VEC4S * 16, gl.DYNAMIC_DRAW);
    gl.bindBuffer(gl.UNIFORM_BUFFER, null);
    this.sceneTexture = gl.createTexture()!;
    gl.bindTexture(gl.TEXTURE_2D, this.sceneTexture);
    gl.texStorage2D(gl.TEXTURE_2D, 1, gl.RGBA32F, SCENE_ROW_TEXELS, DATA_ROWS);
    gl.texParameteri(gl.TEXTURE_2D, gl.TEXTURE_MIN_FILTER, gl.NEAREST);
    gl.texParameteri(gl.TEXTURE_2D, gl.TEXTURE_MAG_FILTER, gl.NEAREST);
    gl.bindTexture(gl.TEXTURE_2D, null);
  }

  private programFor(features: SceneFeatures): Program {
    let program = this.programs.get(featureKey(features));
    if (!program) {
      program = new Program(this.gl, VERTEX_CHUNKS, TRACE_CHUNKS, { ...this.defines, ...featureDefines(features) });
      const blockIndex = this.gl.getUniformBlockIndex(program.handle, 'SceneBlock');
      this.gl.uniformBlockBinding(program.handle, blockIndex, SCENE_BLOCK_BINDING);
      this.programs.set(featureKey(features), program);
    }
    return program;
  }

  /**
   * Uploads the scene: tables to the data texture, constants to the uniform
   * block, camera to uniforms; the files it names from `assets` (uploaded
   * only when they change). Throws SceneError when a file is not in `assets`.
   */
  setScene(sceneModel: Scene, allAssets: SceneAssets, width: number, height: number, bvh?: PrebuiltBvh): void {
    const gl = this.gl;
    const missing = missingAssets(sceneModel, allAssets);
    if (missing.length > 0) throw new SceneError(missing);
    // One material per mesh from here on: meshes wearing their files' materials are split by material.
    const { scene, assets } = resolveFileMaterials(sceneModel, allAssets);
    const map = scene.environment && 'map' in scene.environment ? assets.maps.get(scene.environment.map)! : null;
    this.assets.setEnvironmentMap(map);
    const world = (this.world = prepareWorldMeshes(scene, assets, this.world));
    const environmentIntegral = map ? environmentDistribution(map).integral : undefined;
    const images = assets.images ?? new Map();
    this.assets.setTextures(scene, images);
    const placement = (image: string, input: TextureInput) => this.assets.textures.placement(image, input);
    const means = textureEmissionMeans(scene, world, images, this.emissionMeans);
    const emissionScale = new Map([...means].map(([i, m]) => [i, areaMean(world.meshes[i]!, m)]));
    const packed = packScene(scene, { environmentIntegral, meshes: world.sizes, groups: world.groups, placement, emissionScale });
    this.assets.setMeshes(world, packed.meshEmitters, bvh, means);
    gl.bindBuffer(gl.UNIFORM_BUFFER, this.sceneBuffer);
    gl.bufferSubData(gl.UNIFORM_BUFFER, 0, packed.block);
    gl.bindBuffer(gl.UNIFORM_BUFFER, null);
    gl.bindTexture(gl.TEXTURE_2D, this.sceneTexture);
    gl.texSubImage2D(gl.TEXTURE_2D, 0, 0, 0, SCENE_ROW_TEXELS, DATA_ROWS, gl.RGBA, gl.FLOAT, packed.data);
    gl.bindTexture(gl.TEXTURE_2D, null);
    this.uploadLightChoice(packed.lightChoice.texels);
    this.program = this.programFor(packed.features);
    const frame = cameraFrame(scene.camera);
    this.current = { scene, frame, width, height, features: packed.features };
    for (const program of this.programs.values()) {
      this.setCameraUniforms(program, scene, frame, width, height);
      this.assets.setUniforms(program, scene);
    }
  }

  /**
   * The emitter-choice tables, in a texture of as many rows as they need (a
   * new one only when they need more): whole rows, then the last one's
   * start, straight from the packed array (no padded copy on every edit).
   */
  private uploadLightChoice(texels: Float32Array): void {
    const gl = this.gl;
    const count = texels.length / 4;
    const fullRows = Math.floor(count / LIGHT_CHOICE_WIDTH);
    const rest = count - fullRows * LIGHT_CHOICE_WIDTH;
    const rows = Math.max(1, fullRows + (rest > 0 ? 1 : 0));
    if (!this.lightChoice || this.lightChoice.rows < rows) {
      if (this.lightChoice) gl.deleteTexture(this.lightChoice.texture);
      this.lightChoice = { texture: createDataTexture(gl, LIGHT_CHOICE_WIDTH, rows), rows };
    }
    gl.bindTexture(gl.TEXTURE_2D, this.lightChoice.texture);
    if (fullRows > 0) gl.texSubImage2D(gl.TEXTURE_2D, 0, 0, 0, LIGHT_CHOICE_WIDTH, fullRows, gl.RGBA, gl.FLOAT, texels.subarray(0, fullRows * LIGHT_CHOICE_WIDTH * 4));
    if (rest > 0) gl.texSubImage2D(gl.TEXTURE_2D, 0, 0, fullRows, rest, 1, gl.RGBA, gl.FLOAT, texels.subarray(fullRows * LIGHT_CHOICE_WIDTH * 4));
    gl.bindTexture(gl.TEXTURE_2D, null);
  }

  private setCameraUniforms(program: Program, scene: RenderScene, frame: CameraFrame, width: number, height: number): void {
    program.use().setUniforms(
      {
        uInverseViewProjection: inverseViewProjection(scene.camera, width / height),
        uCameraPosition: frame.position,
        uCameraRight: frame.right,
        uCameraUp: frame.up,
        uCameraForward: frame.forward,
        uAperture: scene.camera.aperture,
        uFocusDistance: frame.focusDistance,
        uResolution: [width, height],
        uMaxBounces: scene.render.maxBounces,
        uAccumulation: TEXTURE_UNITS.accumulation,
        uSceneData: TEXTURE_UNITS.sceneData,
        uLightChoice: TEXTURE_UNITS.lightChoice,
        uCellSamples: TEXTURE_UNITS.cellSamples,
      },
      UNIFORM_TYPES,
    );
  }

  /** The texture atlas's GPU bytes and its warnings (images halved to fit the device). */
  get textures(): { bytes: number; warnings: readonly string[] } {
    return { bytes: this.assets.textures.bytes, warnings: this.assets.textures.warnings };
  }

  /** The features of the current scene: other passes compile their variants with featureDefines(features). */
  get features(): SceneFeatures {
    if (!this.current) throw new Error('TracePass: no scene uploaded');
    return this.current.features;
  }

  /**
   * Prepares another program built from the scene chunks (the AOV pass) to
   * read the current scene: binds its uniform block, the data texture (unit
   * 1) and the asset textures (units 2-6), and sets the camera and asset
   * uniforms. Leaves `program` in use and texture unit 0 active.
   */
  bindScene(program: Program): void {
    if (!this.current) throw new Error('TracePass: no scene uploaded');
    const { scene, frame, width, height } = this.current;
    const blockIndex = this.gl.getUniformBlockIndex(program.handle, 'SceneBlock');
    this.gl.uniformBlockBinding(program.handle, blockIndex, SCENE_BLOCK_BINDING);
    this.setCameraUniforms(program, scene, frame, width, height);
    this.assets.setUniforms(program, scene);
    this.bindSceneData(program);
  }

  /** Binds the uniform block, the asset textures and the data texture; leaves unit 0 active. */
  private bindSceneData(program: Program): void {
    const gl = this.gl;
    gl.bindBufferBase(gl.UNIFORM_BUFFER, SCENE_BLOCK_BINDING, this.sceneBuffer);
    this.assets.bind(program);
    gl.activeTexture(gl.TEXTURE0 + TEXTURE_UNITS.sceneData);
    gl.bindTexture(gl.TEXTURE_2D, this.sceneTexture);
    gl.activeTexture(gl.TEXTURE0 + TEXTURE_UNITS.lightChoice);
    gl.bindTexture(gl.TEXTURE_2D, this.lightChoice?.texture ?? null);
    gl.activeTexture(gl.TEXTURE0 + TEXTURE_UNITS.cellSamples);
    gl.bindTexture(gl.TEXTURE_2D, this.cells.texture);
    gl.activeTexture(gl.TEXTURE0);
  }

  /**
   * One draw: writes the sums read from `targets.read` plus `samples`
   * samples per pixel, numbered from `firstSample`, into `targets.write`:
   * over the whole image, or only over the run of tiles `tiles` (the rest of
   * `targets.write` is left as it was). Does not swap: the caller swaps once
   * every pixel of the pass is written.
   */
  draw(targets: PingPong, firstSample: number, samples: number, seed: number, tiles: TileRun | null = null): void {
    const gl = this.gl;
    this.program.use().setUniforms(
      { uFirstSample: firstSample, uSamplesPerDraw: samples, uSeed: seed >>> 0, uCellSize: 0, uTileList: false, ...(tiles ? tiles.layout.uniforms(tiles) : FULL_SCREEN) },
      UNIFORM_TYPES,
    );
    this.drawSums(targets, () => {
      if (tiles) gl.drawArrays(gl.POINTS, 0, tiles.count);
      else gl.drawArrays(gl.TRIANGLES, 0, 3);
    });
  }

  /** Runs `drawCall` with the uniforms set: the scene bound, `targets.read` as uAccumulation, into `targets.write`. */
  private drawSums(targets: PingPong, drawCall: () => void): void {
    const gl = this.gl;
    this.bindSceneData(this.program);
    gl.bindTexture(gl.TEXTURE_2D, targets.read.texture);
    gl.bindFramebuffer(gl.FRAMEBUFFER, targets.write.framebuffer);
    gl.viewport(0, 0, targets.write.width, targets.write.height);
    drawCall();
    gl.bindFramebuffer(gl.FRAMEBUFFER, null);
  }

  /**
   * One draw of adaptive sampling (src/render/adaptive.ts): writes the sums
   * read from `targets.read` plus, for each cell of `grid`,
   * `samples[c]` samples numbered from `first[c]` into `targets.write`, over
   * the cells with samples only (one point sprite each; the rest of
   * `targets.write` is left as it was). Does not swap.
   */
  drawCells(targets: PingPong, grid: CellGrid, first: Uint32Array, samples: Uint32Array, seed: number): void {
    const gl = this.gl;
    const cells = grid.columns * grid.rows;
    const texels = new Uint32Array(cells * 4);
    const listed: number[] = [];
    for (let c = 0; c < cells; c++) {
      texels[c * 4] = first[c];
      texels[c * 4 + 1] = samples[c];
      if (samples[c] > 0) listed.push(c);
    }
    if (listed.length === 0) return;
    this.cells.upload(grid.columns, grid.rows, texels, new Float32Array(listed));
    this.program.use().setUniforms(
      // uTiles.x and .y only keep the unused tile order's arithmetic defined.
      { uSeed: seed >>> 0, uCellSize: grid.size, uTileList: true, uTiles: [cells, 1, grid.columns, 0], uTileGrid: [grid.size, grid.width, grid.height] },
      UNIFORM_TYPES,
    );
    this.drawSums(targets, () => {
      this.cells.enableList();
      gl.drawArrays(gl.POINTS, 0, listed.length);
      this.cells.disableList();
    });
  }

  dispose(): void {
    this.cells.dispose();
    for (const program of this.programs.values()) program.dispose();
    this.assets.dispose();
    this.gl.deleteBuffer(this.sceneBuffer);
    this.gl.deleteTexture(this.sceneTexture);
    if (this.lightChoice) this.gl.deleteTexture(this.lightChoice.texture);
  }
}
