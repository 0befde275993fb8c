// Undo and redo over whole sketches: each edit pushes the sketch as it is after the edit.
export class SketchHistory {
  constructor() { this.done = []; this.undone = []; }
  // The sketch after an edit, as text; a repeat of the last is not an edit.
  push(text) {
    if (this.done[this.done.length - 1] === text) return;
    this.done.push(text);
    this.undone = [];
  }
  // Drops the latest `text`, an edit the server refused; the first sketch stays.
  forget(text) {
    const i = this.done.lastIndexOf(text);
    if (i < 1) return;
    this.done.splice(i, 1);
    // Equal neighbours left behind are one state.
    if (this.done[i - 1] === this.done[i]) this.done.splice(i, 1);
  }
  canUndo() { return this.done.length > 1; }
  canRedo() { return this.undone.length > 0; }
  undo() {
    if (!this.canUndo()) return null;
    this.undone.push(this.done.pop());
    return this.done[this.done.length - 1];
  }
  redo() {
    if (!this.canRedo()) return null;
    const text = this.undone.pop();
    this.done.push(text);
    return text;
  }
}
