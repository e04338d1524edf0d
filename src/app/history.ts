/** Undo/redo of whole-scene snapshots (scenes are small: a few KB). Pure. */
export class History<T> {
  private readonly undoStack: T[] = [];
  private readonly redoStack: T[] = [];

  constructor(private readonly limit = 200) {}

  /** Records the state before an edit; clears the redo stack. */
  record(before: T): void {
    this.undoStack.push(before);
    if (this.undoStack.length > this.limit) this.undoStack.shift();
    this.redoStack.length = 0;
  }

  /** Returns the state to go back to (and remembers `current` for redo), or null. */
  undo(current: T): T | null {
    const previous = this.undoStack.pop();
    if (previous === undefined) return null;
    this.redoStack.push(current);
    return previous;
  }

  redo(current: T): T | null {
    const next = this.redoStack.pop();
    if (next === undefined) return null;
    this.undoStack.push(current);
    return next;
  }

  get canUndo(): boolean {
    return this.undoStack.length > 0;
  }

  get canRedo(): boolean {
    return this.redoStack.length > 0;
  }

  /** Both stacks, oldest first (to save them). */
  entries(): { undo: T[]; redo: T[] } {
    return { undo: [...this.undoStack], redo: [...this.redoStack] };
  }

  /** Replaces both stacks (oldest first), e.g. with saved ones; keeps the newest `limit` undo steps. */
  replace(undo: T[], redo: T[]): void {
    this.undoStack.splice(0, this.undoStack.length, ...undo.slice(-this.limit));
    this.redoStack.splice(0, this.redoStack.length, ...redo.slice(-this.limit));
  }

  clear(): void {
    this.undoStack.length = 0;
    this.redoStack.length = 0;
  }
}
