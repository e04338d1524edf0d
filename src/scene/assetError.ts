/**
 * The error a decoder of an asset file (an environment map, a mesh) throws
 * for a file it cannot accept. `message` says what is wrong with the file,
 * without naming where the file is used: the caller prefixes the scene path
 * (`environment.map: ...`, `meshes[2].file: ...`).
 */
export class AssetError extends Error {
  constructor(message: string) {
    super(message);
    this.name = 'AssetError';
  }
}
