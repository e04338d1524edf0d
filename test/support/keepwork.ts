/**
 * Helpers for the "never lose the user's work" page tests: the autosave
 * record in IndexedDB (written raw, as a corrupt or foreign record would be)
 * and waiting for the page's save status.
 */
import type { Page } from 'playwright-core';

/** Waits until the page says its state is saved (body[data-saved="saved"]). */
export async function waitSaved(page: Page): Promise<void> {
  await page.waitForFunction(() => document.body.dataset.saved === 'saved', undefined, { timeout: 30_000 });
}

/** Writes `value` as the autosave record, the way any other writer (or a damaged disk) could. */
export async function writeSavedRecord(page: Page, value: unknown): Promise<void> {
  await page.evaluate(
    (v) =>
      new Promise<void>((resolve, reject) => {
        const open = indexedDB.open('pathtrace');
        open.onupgradeneeded = () => open.result.createObjectStore('keyval');
        open.onerror = () => reject(open.error);
        open.onsuccess = () => {
          const tx = open.result.transaction('keyval', 'readwrite');
          tx.objectStore('keyval').put(v, 'autosave');
          tx.oncomplete = () => {
            open.result.close();
            resolve();
          };
          tx.onerror = () => reject(tx.error);
        };
      }),
    value,
  );
}
