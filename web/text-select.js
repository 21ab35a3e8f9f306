// Selects line `line` (1-based) of a textarea, or its character at `column`,
// and scrolls it into view: where a JSON or program error points.
export function selectLine(textarea, line, column = 0) {
  const lines = textarea.value.split("\n");
  let start = 0;
  for (let i = 0; i < line - 1 && i < lines.length; i++) start += lines[i].length + 1;
  const len = (lines[line - 1] ?? "").length;
  const from = column > 0 ? start + Math.min(column - 1, len) : start;
  const to = column > 0 ? Math.min(from + 1, start + len) : start + len;
  textarea.focus();
  textarea.setSelectionRange(from, to);
  const lineHeight = parseFloat(getComputedStyle(textarea).lineHeight) || 20;
  textarea.scrollTop = Math.max(0, (line - 3) * lineHeight);
}
