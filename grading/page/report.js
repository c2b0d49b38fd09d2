// rrt-grade's report.html and its submission pages (grading/html_report.py inlines this):
// a click on a sortable table's header sorts its rows by that column (numbers by value,
// text in natural order; a second click reverses), and a run's view is loaded into its
// frame when its box is first opened. window.rrtReport tells tests what happened.
"use strict";
(function () {
  const state = {ready: false, sorts: 0, views: 0};
  window.rrtReport = state;
  const collator = new Intl.Collator(undefined, {numeric: true, sensitivity: "base"});

  // A cell's sort key: data-v when given (numbers: "" when missing), else its text.
  function key(cell, numeric) {
    const given = cell.dataset.v;
    if (!numeric) return given !== undefined ? given : cell.textContent.trim();
    return given === undefined || given === "" ? null : Number(given);
  }

  function compare(a, b, numeric) {
    if (a.key === null || b.key === null) {
      return a.key === b.key ? 0 : (a.key === null ? 1 : -1);
    }
    return numeric ? a.key - b.key : collator.compare(a.key, b.key);
  }

  // Sorts the table's body by column; rows missing a number go last either way, ties
  // keep their order.
  function sortBy(table, column, header) {
    const numeric = header.dataset.kind === "num";
    const ascending = header.getAttribute("aria-sort") !== "ascending";
    for (const other of header.parentNode.cells) other.removeAttribute("aria-sort");
    header.setAttribute("aria-sort", ascending ? "ascending" : "descending");
    const body = table.tBodies[0];
    const rows = Array.from(body.rows, (row, index) => ({row, index,
                                                         key: key(row.cells[column], numeric)}));
    rows.sort((a, b) => {
      const missing = a.key === null || b.key === null;
      const order = compare(a, b, numeric);
      return (missing || ascending ? order : -order) || a.index - b.index;
    });
    body.append(...rows.map(entry => entry.row));
    state.sorts++;
  }

  for (const table of document.querySelectorAll("table.sortable")) {
    Array.from(table.tHead.rows[0].cells).forEach((header, column) => {
      const button = header.querySelector("button");
      if (button) button.addEventListener("click", () => sortBy(table, column, header));
    });
  }

  for (const box of document.querySelectorAll("details.view")) {
    box.addEventListener("toggle", () => {
      const frame = box.querySelector("iframe");
      if (box.open && frame && !frame.getAttribute("src")) {
        frame.setAttribute("src", frame.dataset.src);
        state.views++;
      }
    });
  }
  state.ready = true;
})();
