// Undo and redo over whole sketches: each edit pushes the sketch as it is after the edit.
export class SketchHistory {
  constructor() { this.done = []; this.undone = []; }
  // The sketch after an edit, as text; a repeat of the last is not an edit.
  push(text) {
    if (this.done[this.done.length - 1] === text) return;
    this.done.push(text);
    this.undone = [];
  }
  // The sketch as it is instead of the last edit, which was refused.
  replaceLast(text) {
    if (!this.done.length) return this.push(text);
    this.done[this.done.length - 1] = text;
    if (this.done.length > 1 && this.done[this.done.length - 2] === text) this.done.pop();
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
