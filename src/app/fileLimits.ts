/**
 * How large the user's own files may be on the page: one file is refused
 * above MAX_ASSET_BYTES before it is read (from File.size), since the
 * autosave could not keep it (store.ts); all kept together take at most
 * MAX_TOTAL_ASSET_BYTES. A module of its own: the mesh Worker reads it too.
 */

/** One user file (model, .bin, image, map) kept with the scene: at most this many bytes. */
export const MAX_ASSET_BYTES = 64 * 1024 * 1024;
/** All user files kept together: at most this many bytes. */
export const MAX_TOTAL_ASSET_BYTES = 256 * 1024 * 1024;
