/**
 * The files of a drop, folders included: a dropped folder's files (and its
 * subfolders') come as if dropped one by one, so a .gltf dropped in its
 * folder finds its .bin and images. Dropped files carry no folders (the
 * page matches a model's companions by name: companionFiles.ts).
 */

/** Every file dropped, the files in dropped folders included. */
export async function droppedFiles(transfer: DataTransfer | null | undefined): Promise<File[]> {
  if (!transfer) return [];
  const entries = [...transfer.items].map((item) => (item.kind === 'file' ? item.webkitGetAsEntry?.() : null));
  // Without the entries API (or without a folder among them), the plain file list.
  if (!entries.some((entry) => entry?.isDirectory)) return [...transfer.files];
  const files: File[] = [];
  for (const entry of entries) if (entry) files.push(...(await entryFiles(entry)));
  return files;
}

async function entryFiles(entry: FileSystemEntry): Promise<File[]> {
  if (entry.isFile) return [await new Promise<File>((resolve, reject) => (entry as FileSystemFileEntry).file(resolve, reject))];
  if (!entry.isDirectory) return [];
  const reader = (entry as FileSystemDirectoryEntry).createReader();
  const files: File[] = [];
  // readEntries returns its entries in batches (100 in Chromium) until an empty one.
  for (;;) {
    const batch = await new Promise<FileSystemEntry[]>((resolve, reject) => reader.readEntries(resolve, reject));
    if (batch.length === 0) return files;
    for (const child of batch) files.push(...(await entryFiles(child)));
  }
}
