// The sprocket table of the web page: one row of plain form fields per sprocket.
//
// Every committed cell (Enter, Tab, leaving the field, a choice in a list, a tick) sends the
// whole table to the page at once, so the page's run starts without waiting (Streamlit's
// data editor waits 150 ms before it sends an edit). The page gives the table back as
// `data.rows`; when those are the rows this table last sent, the fields are left as they are
// (focus, caret and any text being typed stay); otherwise the table is drawn again from them.
//
// A number cell sends a number when its text is one, and the text itself otherwise: the page
// reads "120 rpm" with its unit, and names the field when it cannot read it. An empty cell
// sends null (the design's default applies).
//
// data = {columns: [{key, label, title, kind: text|int|float|select|bool, options, width,
//                    placeholder}],
//         rows: [{_row: base row index or null, <key>: value, ...}], caption: str}

const NUMBER = /^[-+]?(\d+\.?\d*|\.\d+)([eE][-+]?\d+)?$/;
const sent = new WeakMap(); // parentElement -> JSON of the rows last sent or drawn

function cellText(value) {
  if (value === null || value === undefined) return "";
  if (typeof value === "number") {
    // 12 significant digits: a unit conversion's round-off (700.0000000000001) is not shown
    return String(Number(value.toPrecision(12)));
  }
  return String(value);
}

function parsed(column, text) {
  const t = text.trim();
  if (t === "") return null;
  if (column.kind === "text") return t;
  if (NUMBER.test(t)) return Number(t);
  return t; // the page names the field it cannot read
}

function rowName(row, index) {
  return row.name === null || row.name === undefined || row.name === ""
    ? `row ${index + 1}` : String(row.name);
}

export default function (component) {
  const { data, setStateValue, parentElement } = component;
  const incoming = JSON.stringify(data.rows);
  let root = parentElement.querySelector("div.cd-table");
  if (root && sent.get(parentElement) === incoming) {
    return; // the page drew what this table sent: keep the fields as they are
  }
  if (!root) {
    root = document.createElement("div");
    root.className = "cd-table";
    parentElement.appendChild(root);
  }
  root.replaceChildren();
  const columns = data.columns;
  const rows = JSON.parse(incoming);
  sent.set(parentElement, incoming);

  function send() {
    const text = JSON.stringify(rows);
    sent.set(parentElement, text);
    setStateValue("rows", JSON.parse(text));
  }

  const scroller = document.createElement("div");
  scroller.className = "cd-scroll";
  const table = document.createElement("table");
  const head = table.createTHead().insertRow();
  for (const column of columns) {
    const th = document.createElement("th");
    th.textContent = column.label;
    th.title = column.title || column.label;
    th.style.minWidth = `${column.width}px`;
    head.appendChild(th);
  }
  head.appendChild(document.createElement("th"));
  const body = table.createTBody();

  rows.forEach((row, index) => {
    const tr = body.insertRow();
    for (const column of columns) {
      const td = tr.insertCell();
      let field;
      if (column.kind === "bool") {
        field = document.createElement("input");
        field.type = "checkbox";
        field.checked = Boolean(row[column.key]);
        field.addEventListener("change", () => {
          row[column.key] = field.checked;
          send();
        });
      } else if (column.kind === "select") {
        field = document.createElement("select");
        const value = row[column.key];
        const options = [""].concat(column.options);
        if (value !== null && value !== undefined && !options.includes(String(value))) {
          options.push(String(value)); // a value from the file the list does not hold
        }
        for (const option of options) {
          const element = document.createElement("option");
          element.value = option;
          element.textContent = option === "" ? (column.placeholder || "—") : option;
          element.selected = option === cellText(value);
          field.appendChild(element);
        }
        field.addEventListener("change", () => {
          row[column.key] = field.value === "" ? null : field.value;
          send();
        });
      } else {
        field = document.createElement("input");
        field.type = "text";
        field.size = 1; // the column's width, not the browser's 20 characters, sets its size
        field.autocomplete = "off";
        field.spellcheck = false;
        if (column.kind !== "text") {
          field.inputMode = "decimal";
          field.className = "cd-number";
        }
        field.placeholder = column.placeholder || "";
        field.value = cellText(row[column.key]);
        let committed = field.value;
        const commit = () => {
          if (field.value === committed) return;
          committed = field.value;
          row[column.key] = parsed(column, field.value);
          send();
        };
        field.addEventListener("change", commit);
        field.addEventListener("keydown", (event) => {
          if (event.key === "Enter") commit();
          if (event.key === "Escape") field.value = committed;
        });
      }
      field.setAttribute("aria-label", `${rowName(row, index)} ${column.label}`);
      field.title = column.title || column.label;
      field.dataset.column = column.key;
      field.dataset.row = String(index);
      td.appendChild(field);
    }
    const td = tr.insertCell();
    const remove = document.createElement("button");
    remove.type = "button";
    remove.className = "cd-remove";
    remove.textContent = "×";
    remove.title = "remove this sprocket";
    remove.setAttribute("aria-label", `remove ${rowName(row, index)}`);
    remove.addEventListener("click", () => {
      rows.splice(index, 1);
      send();
      sent.delete(parentElement); // draw again: the rows below move up
    });
    td.appendChild(remove);
  });
  scroller.appendChild(table);
  root.appendChild(scroller);

  const add = document.createElement("button");
  add.type = "button";
  add.className = "cd-add";
  add.textContent = "+ add a sprocket";
  add.addEventListener("click", () => {
    const row = { _row: null };
    for (const column of columns) row[column.key] = column.kind === "bool" ? false : null;
    rows.push(row);
    send();
    sent.delete(parentElement);
  });
  root.appendChild(add);
  if (data.caption) {
    const note = document.createElement("div");
    note.className = "cd-caption";
    note.textContent = data.caption;
    root.appendChild(note);
  }
}
