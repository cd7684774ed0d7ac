// The page: two engines (this one for a pixel, the worker's for a whole
// render, a compare or a ray log), given the same files, scene and
// toggles. Everything shown comes from the engines' replies.

const $ = (id) => document.getElementById(id);
/** Timings a test or a curious teacher can read (milliseconds). */
const timings = (window.raystepTimings = {});

const page = {
  call: null,          // this page's engine
  module: null,        // the compiled engine, for a new worker
  worker: null,
  jobs: new Map(),     // worker job id -> {resolve, reject}
  nextJob: 1,
  given: new Map(),    // path -> bytes: every file given, replayed to a new worker
  load: null,          // the last good load's arguments
  options: {},         // the last toggles sent
  scene: null,         // the last load's reply
  png: null,           // the last render's PNG bytes
  bitmap: null,
  cursor: { x: 0, y: 0 },
  view: null,          // the picked pixel's reply
  row: 0,              // the selected tree row
  collapsed: new Set(),
  renderId: 0,
  panic: null,
};

// ---- engines ---------------------------------------------------------------

function status(text) { $("status").textContent = text; }

async function startEngine() {
  page.call = await engine(page.module, {
    progress: () => {},
    panicked: (message) => { page.panic = message; },
  });
}

/** A call on this page's engine; a trap restarts it with the same state. */
function call(op, args, bytes) {
  try {
    return page.call(op, args, bytes);
  } catch (error) {
    if (error instanceof EngineError) throw error;
    const why = page.panic || String(error);
    page.panic = null;
    restartEngine();
    throw new EngineError(`raystep stopped on an internal error (${why}); it was restarted`);
  }
}

async function restartEngine() {
  await startEngine();
  for (const [path, bytes] of page.given) page.call("give", { path }, bytes);
  if (page.load) page.call("load", page.load);
  page.call("options", page.options);
}

function startWorker() {
  if (page.worker) page.worker.terminate();
  for (const job of page.jobs.values()) job.reject(new EngineError("cancelled"));
  page.jobs.clear();
  const url = URL.createObjectURL(new Blob([WORKER_SOURCE], { type: "text/javascript" }));
  const worker = new Worker(url);
  URL.revokeObjectURL(url);
  worker.onmessage = (event) => {
    const m = event.data;
    if (m.type === "progress") {
      $("progress").hidden = false;
      $("progress").value = m.done / m.total;
    } else if (m.type === "panicked") {
      page.panic = m.message;
    } else if (m.type === "reply") {
      const job = page.jobs.get(m.id);
      page.jobs.delete(m.id);
      if (!job) return;
      if (m.error === undefined) job.resolve(m);
      else if (m.trapped) {
        job.reject(new EngineError(`raystep stopped on an internal error (${page.panic || m.error}); it was restarted`));
        page.panic = null;
        startWorker();
      } else job.reject(new EngineError(m.error));
    }
  };
  worker.postMessage({ type: "init", module: page.module });
  page.worker = worker;
  for (const [path, bytes] of page.given) post("give", { path }, bytes);
  if (page.load) post("load", page.load);
  post("options", page.options);
}

/** A job for the worker; resolves with {reply, ms}. */
function post(op, args, bytes) {
  const id = page.nextJob++;
  const promise = new Promise((resolve, reject) => page.jobs.set(id, { resolve, reject }));
  promise.catch(() => {});
  page.worker.postMessage({ type: "call", id, op, args, bytes });
  return promise;
}

/** A call that changes state: made here, and sent to the worker. */
function both(op, args, bytes) {
  const reply = call(op, args, bytes);
  post(op, args, bytes);
  return reply;
}

function give(path, bytes) {
  page.given.set(path, bytes);
  both("give", { path }, bytes);
}

// ---- scenes ----------------------------------------------------------------

const SCENE = /\.(toml|nff|test)$/i;

function sceneText(path) {
  const bytes = page.given.get(path);
  return bytes ? new TextDecoder().decode(bytes) : "";
}

function addSceneOption(path, label) {
  const list = $("scene-list");
  if ([...list.options].some((o) => o.value === path)) return;
  const option = document.createElement("option");
  option.value = path;
  option.textContent = label || path;
  list.append(option);
}

function parseSize() {
  const text = $("size").value.trim();
  if (!text) return null;
  const m = /^(\d+)\s*[x×]\s*(\d+)$/i.exec(text);
  if (!m) throw new EngineError(`invalid size "${text}": write it as WxH, e.g. 320x240`);
  return [Number(m[1]), Number(m[2])];
}

/** Reads scene `path` (from the given files) and renders it; an error is
 * shown as the command line says it, with its line and column. */
function openScene(path, { keepText } = {}) {
  $("scene-list").value = path;
  if (!keepText) $("scene-text").value = sceneText(path);
  let reply;
  try {
    const args = { path, size: parseSize() };
    reply = both("load", args);
    page.load = args;
  } catch (error) {
    showSceneError(error);
    return false;
  }
  showSceneError(null);
  page.scene = reply;
  page.options = {};
  // The menu lists what this scene's profile offers: built again below.
  $("mistake-list").replaceChildren();
  page.view = null;
  clearPixel();
  showSettings(reply.settings);
  $("warnings").textContent = reply.warnings.map((w) => `warning: ${w}`).join("\n");
  page.cursor = { x: Math.min(page.cursor.x, reply.width - 1), y: Math.min(page.cursor.y, reply.height - 1) };
  render();
  return true;
}

function showSceneError(error) {
  const box = $("scene-error");
  box.hidden = !error;
  box.textContent = error ? `error: ${error.message}` : "";
  if (error) status("the scene has an error: see below the picture");
}

// ---- toggles ---------------------------------------------------------------

function showSettings(s) {
  $("t-shadows").checked = s.shadows;
  $("t-reflection").checked = s.reflection;
  $("t-transmission").checked = s.transmission;
  $("t-ambient").checked = s.ambient;
  $("t-specular").value = s.specular;
  $("t-depth").value = s.max_depth;
  showProfile(s);
  const list = $("mistake-list");
  if (!list.childElementCount && page.scene) {
    for (const [name, summary] of page.scene.catalogue) {
      const label = document.createElement("label");
      label.innerHTML = `<input type="checkbox" data-mistake=""> <b></b>: <span></span>`;
      label.querySelector("input").dataset.mistake = name;
      label.querySelector("b").textContent = name;
      label.querySelector("span").textContent = summary;
      list.append(label);
    }
  }
  for (const box of list.querySelectorAll("input")) box.checked = s.mistakes.includes(box.dataset.mistake);
  $("mistake-count").textContent = s.mistakes.length ? s.mistakes.join(", ") : "none";
}

/** The profile the scene is traced with, named as the debugger's header
 * names it, only when it is not the lecture's (the engine sends `profile`
 * only then); CSE 167's `maxdepth` counts bounces, one less than MODEL §5's
 * depth (docs/CSE167.md), so the depth says both. */
function showProfile(s) {
  for (const id of ["bounces", "profile"]) $(id).hidden = !s.profile;
  $("bounces").textContent = s.profile ? ` (${Math.max(0, s.max_depth - 1)} bounces)` : "";
  $("profile").textContent = s.profile ? `profile ${s.profile} (MODEL §11)` : "";
  $("profile").title = s.profile_words || "";
  // As the debugger's header: no transmission switch where nothing refracts.
  $("t-transmission").parentElement.hidden = s.refracts === false;
  page.profile = s.profile;
}

function readToggles() {
  return {
    shadows: $("t-shadows").checked,
    reflection: $("t-reflection").checked,
    transmission: $("t-transmission").checked,
    ambient: $("t-ambient").checked,
    specular: $("t-specular").value,
    max_depth: Number($("t-depth").value),
    mistakes: [...$("mistake-list").querySelectorAll("input:checked")].map((b) => b.dataset.mistake),
  };
}

function applyToggles(message) {
  const options = readToggles();
  try {
    showSettings(both("options", options));
    page.options = options;
    status(message || "toggles changed");
  } catch (error) {
    showSettings(call("options", page.options));
    status(error.message);
    return;
  }
  const picked = page.view && page.view.pixel;
  render();
  if (picked) pick(picked[0], picked[1]);
}

// ---- the picture -------------------------------------------------------------

async function render() {
  const id = ++page.renderId;
  if (page.jobs.size) startWorker(); // a newer render replaces a running one
  status("rendering…");
  $("progress").hidden = false;
  $("progress").value = 0;
  const started = performance.now();
  let done;
  try {
    done = await post("render", {});
  } catch (error) {
    if (id === page.renderId && error.message !== "cancelled") status(error.message);
    return;
  } finally {
    if (id === page.renderId) $("progress").hidden = true;
  }
  if (id !== page.renderId) return;
  page.png = done.reply;
  page.bitmap = await createImageBitmap(new Blob([page.png], { type: "image/png" }));
  timings.render = done.ms;
  timings.renderWall = performance.now() - started;
  draw();
  if (timings.firstPicture === undefined) timings.firstPicture = performance.now();
  status(`rendered ${page.scene.width}x${page.scene.height} in ${Math.round(done.ms)} ms`);
  document.body.dataset.rendered = String(id);
}

/** How much larger than the image it is shown: up to 640 x 480 on screen. */
function fit() {
  return Math.max(1, Math.min(640 / page.scene.width, 480 / page.scene.height));
}

function draw() {
  if (!page.bitmap) return;
  const canvas = $("image");
  // Drawn at a whole scale, shown at the fitting one: every pixel a block.
  const s = Math.ceil(fit());
  canvas.width = page.scene.width * s;
  canvas.style.width = `${page.scene.width * fit()}px`;
  canvas.dataset.width = page.scene.width;
  canvas.height = page.scene.height * s;
  const g = canvas.getContext("2d");
  g.imageSmoothingEnabled = false;
  g.drawImage(page.bitmap, 0, 0, canvas.width, canvas.height);
  const { x, y } = page.cursor;
  g.lineWidth = 2;
  g.strokeStyle = "#ff0";
  g.strokeRect(x * s - 1, y * s - 1, s + 2, s + 2);
  g.strokeStyle = "#000";
  g.strokeRect(x * s - 3, y * s - 3, s + 6, s + 6);
  $("cursor-words").textContent = `cursor (${x}, ${y}): Enter or a click shows why it has its colour`;
}

function moveCursor(dx, dy) {
  const c = page.cursor;
  c.x = Math.min(page.scene.width - 1, Math.max(0, c.x + dx));
  c.y = Math.min(page.scene.height - 1, Math.max(0, c.y + dy));
  draw();
}

// ---- the pixel -----------------------------------------------------------------

function clearPixel() {
  for (const id of ["tree", "details", "events", "explain", "diagram", "only-yours", "yours"]) $(id).textContent = "";
  $("pixel-title").textContent = "Click a pixel (or move with the arrow keys and press Enter) to see why it has its colour.";
}

function swatch(rgb) {
  const span = document.createElement("span");
  span.className = "swatch";
  if (rgb) span.style.background = `rgb(${rgb[0]},${rgb[1]},${rgb[2]})`;
  return span;
}

function pick(x, y) {
  const started = performance.now();
  page.cursor = { x, y };
  draw();
  let view;
  try {
    view = call("pixel", { x, y });
  } catch (error) {
    status(error.message);
    return;
  }
  page.view = view;
  page.collapsed = new Set();
  page.row = 0;
  const title = $("pixel-title");
  title.textContent = view.title;
  title.append(swatch(view.rgb8));
  $("explain").textContent = view.explain;
  $("only-yours").textContent = (view.only_yours || []).join("\n");
  showEvents();
  showTree();
  showRay(0);
  showDiagram();
  timings.pick = performance.now() - started;
  document.body.dataset.picked = `${x},${y}`;
}

function showTree() {
  const list = $("tree");
  list.textContent = "";
  const rows = page.view.rows;
  let hideDeeper = Infinity;
  rows.forEach((row, i) => {
    if (row.indent > hideDeeper) return;
    hideDeeper = Infinity;
    const li = document.createElement("li");
    li.setAttribute("role", "treeitem");
    li.dataset.row = i;
    li.style.paddingLeft = `${row.indent * 1.2}em`;
    const opens = i + 1 < rows.length && rows[i + 1].indent > row.indent;
    const toggle = document.createElement("span");
    toggle.className = "toggle";
    if (opens) {
      const closed = page.collapsed.has(i);
      toggle.textContent = closed ? "▸" : "▾";
      li.setAttribute("aria-expanded", String(!closed));
      if (closed) hideDeeper = row.indent;
    }
    li.append(toggle);
    if (row.log) {
      const mark = document.createElement("span");
      const kind = { "✓": "same", "≠": "differs", "−": "missing", "+": "only" }[row.log.mark];
      mark.className = `log-mark ${kind}`;
      mark.textContent = `${row.log.mark} ${row.log.path}`;
      if (row.log.first) li.classList.add("first");
      li.append(mark);
    }
    li.append(document.createTextNode(row.text), swatch(row.rgb8));
    const share = document.createElement("span");
    share.className = "share";
    share.textContent = row.share;
    li.append(share);
    if (row.log && row.log.first) li.append(" ◀ first divergence");
    li.setAttribute("aria-selected", String(i === page.row));
    li.onclick = (event) => {
      if (event.target === toggle && opens) toggleRow(i);
      else selectRow(i);
    };
    list.append(li);
  });
  markCurrentRow();
}

function toggleRow(i) {
  if (page.collapsed.has(i)) page.collapsed.delete(i);
  else page.collapsed.add(i);
  showTree();
}

function selectRow(i) {
  page.row = i;
  showTree();
  showRay(page.view.rows[i].node);
}

/** The row of the event the stepping is at, outlined; its ancestors open. */
function markCurrentRow() {
  const view = page.view;
  const event = view.events[view.at];
  if (!event) return;
  for (const li of $("tree").children) {
    const row = view.rows[li.dataset.row];
    const here = row.node === event.node && (row.kind === "ray" ? event.light == null : row.light === event.light);
    li.classList.toggle("current", here);
  }
}

function showRay(id) {
  let reply;
  try {
    reply = call("ray", { id });
  } catch (error) {
    status(error.message);
    return;
  }
  $("ray-title").textContent = `r${id}`;
  const box = $("details");
  box.textContent = "";
  for (const line of reply.lines) {
    const div = document.createElement("div");
    div.style.paddingLeft = `${line.indent}ch`;
    if (line.marked) div.className = "marked";
    line.words.forEach(([text, rgb], i) => {
      if (i) div.append(" ");
      div.append(text);
      if (rgb) div.append(swatch(rgb));
    });
    box.append(div);
  }
  const yours = $("yours");
  yours.textContent = "";
  if (reply.yours) {
    const table = document.createElement("table");
    table.className = "checks mono";
    table.innerHTML = "<caption></caption><tr><th></th><th>yours</th><th>ours</th></tr>";
    table.querySelector("caption").textContent = `your ray ${reply.yours.path}`;
    for (const [field, mine, ours, agrees] of reply.yours.checks) {
      const tr = table.insertRow();
      for (const text of [field, mine, ours]) tr.insertCell().textContent = text;
      if (!agrees) tr.className = "no";
    }
    yours.append(table);
  }
}

function showEvents() {
  const list = $("events");
  list.textContent = "";
  page.view.events.forEach((event, i) => {
    const li = document.createElement("li");
    li.textContent = "  ".repeat(event.indent) + event.text;
    if (event.rgb8) li.append(swatch(event.rgb8));
    li.onclick = () => goTo(call("goto", { at: i }));
    list.append(li);
  });
  markEvent();
}

function markEvent() {
  const items = $("events").children;
  for (const li of items) li.classList.remove("current");
  const li = items[page.view.at];
  if (li) {
    li.classList.add("current");
    // Within the list only: the page itself stays where the reader put it.
    const list = $("events");
    list.scrollTop = li.offsetTop - list.offsetTop - list.clientHeight / 2;
  }
}

function goTo(position) {
  const view = page.view;
  view.at = position.at;
  markEvent();
  // Open the tree down to the event's ray, and show that ray.
  const row = view.rows.findIndex((r) => r.node === position.node && r.kind === "ray");
  for (const i of [...page.collapsed]) if (i < row && isAncestorRow(i, row)) page.collapsed.delete(i);
  page.row = row;
  showTree();
  showRay(position.node);
  showDiagram();
}

function isAncestorRow(i, row) {
  const rows = page.view.rows;
  for (let j = i + 1; j <= row; j++) if (rows[j].indent <= rows[i].indent) return false;
  return true;
}

function step(how) {
  if (!page.view) return;
  try {
    goTo(call("step", { how }));
  } catch (error) {
    status(error.message);
  }
}

function diagramArgs(whole) {
  return { plane: $("plane").value, shadows: $("shadows").value, whole };
}

function showDiagram() {
  try {
    $("diagram").innerHTML = call("diagram", diagramArgs(false));
  } catch (error) {
    $("diagram").textContent = error.message;
  }
}

// ---- the student's work ------------------------------------------------------

function download(bytes, name, type) {
  const a = document.createElement("a");
  a.href = URL.createObjectURL(new Blob([bytes], { type }));
  a.download = name;
  a.click();
  setTimeout(() => URL.revokeObjectURL(a.href), 1000);
}

function stem() {
  return (page.load ? page.load.path : "raystep").split("/").pop().replace(/\.[^.]*$/, "");
}

async function compareImage(name, bytes) {
  $("compare").hidden = false;
  $("compare-report").textContent = "comparing (raystep renders the scene and each mistake of its catalogue)…";
  status("comparing your render…");
  try {
    const { reply } = await post("compare", { path: name }, bytes);
    $("compare-report").textContent = reply.report +
      (reply.error_map ? "" : "\nFLIP is not in this page: the verdict, the regions and the mistakes above do not need it.");
    const images = $("compare-images");
    images.textContent = "";
    const yours = document.createElement("img");
    yours.alt = "your render";
    yours.src = URL.createObjectURL(new Blob([bytes], { type: "image/png" }));
    images.append(yours);
    if (reply.error_map) {
      const map = document.createElement("img");
      map.alt = "FLIP error map";
      map.src = URL.createObjectURL(new Blob([(await post("error_map", {})).reply], { type: "image/png" }));
      images.append(map);
    }
    status(reply.matches ? "your render matches" : `your render differs${reply.mistakes.length ? ": " + reply.mistakes[0] + " first" : ""}`);
    document.body.dataset.compared = name;
  } catch (error) {
    $("compare-report").textContent = `error: ${error.message}`;
    status(error.message);
  }
}

function readRayLog(name, bytes) {
  $("raylog").hidden = false;
  let reply;
  try {
    reply = call("raylog", { path: name }, bytes);
  } catch (error) {
    $("raylog-report").textContent = `error: ${error.message}`;
    status(error.message);
    return;
  }
  $("raylog-report").textContent = reply.report;
  const list = $("raylog-pixels");
  list.textContent = "";
  for (const p of reply.pixels) {
    const li = document.createElement("li");
    const button = document.createElement("button");
    button.textContent = `(${p.pixel[0]}, ${p.pixel[1]})`;
    button.onclick = () => pick(p.pixel[0], p.pixel[1]);
    li.append(button, ` ${p.words}`);
    list.append(li);
  }
  status(`${name}: ${reply.pixel_count} pixel${reply.pixel_count === 1 ? "" : "s"} logged`);
  if (reply.pixels.length) pick(reply.pixels[0].pixel[0], reply.pixels[0].pixel[1]);
  document.body.dataset.raylog = name;
}

/** Files opened or dropped: a PNG is compared, a ray log read, scenes and
 * meshes given (the first scene among them opened). */
async function takeFiles(files) {
  let scene = null;
  for (const file of files) {
    const bytes = new Uint8Array(await file.arrayBuffer());
    const name = file.name;
    if (/\.png$/i.test(name)) await compareImage(name, bytes);
    else if (/\.(jsonl|json|log|txt)$/i.test(name)) readRayLog(name, bytes);
    else {
      // A folder's files keep their place below it, as a scene names them.
      const path = (file.webkitRelativePath || name).split("/").slice(file.webkitRelativePath ? 1 : 0).join("/");
      give(path, bytes);
      if (path !== name) give(name, bytes);
      if (SCENE.test(name) && !scene) scene = path;
    }
  }
  if (scene) {
    addSceneOption(scene, `${scene} (opened)`);
    openScene(scene);
  }
}

// ---- keys --------------------------------------------------------------------

const HELP = `Keys (as in the terminal debugger):
  arrows         move the cursor on the image (Shift: 10 pixels)
  Enter          show why the pixel under the cursor has its colour
  n / p          next / previous event
  i / o / u      step into the next ray cast / over this ray's children / out to its parent
  g / e          first / last event
  s r t a        shadows, reflection, transmission, ambient on or off
  m              Blinn (N·H) or Phong (R·V) highlights
  [ / ]          max depth down / up
  R              render again
  ?              this help
In the ray tree: up and down select a row, left and right close and open it.
Tab moves between the controls; drop a PNG to compare it, a ray log to read it,
a scene (with its meshes) to open it.`;

function onKey(event) {
  const tag = event.target.tagName;
  if (["INPUT", "TEXTAREA", "SELECT"].includes(tag) || event.ctrlKey || event.metaKey || event.altKey) return;
  if (!page.scene) return;
  const inTree = event.target === $("tree");
  const by = event.shiftKey ? 10 : 1;
  const steps = { n: "next", p: "previous", i: "into", o: "over", u: "out", g: "start", e: "end" };
  const toggles = { s: "t-shadows", r: "t-reflection", t: "t-transmission", a: "t-ambient" };
  let handled = true;
  if (inTree && page.view && ["ArrowUp", "ArrowDown", "ArrowLeft", "ArrowRight"].includes(event.key)) {
    const visible = [...$("tree").children].map((li) => Number(li.dataset.row));
    const at = visible.indexOf(page.row);
    if (event.key === "ArrowUp" && at > 0) selectRow(visible[at - 1]);
    else if (event.key === "ArrowDown" && at + 1 < visible.length) selectRow(visible[at + 1]);
    else if (event.key === "ArrowLeft" && !page.collapsed.has(page.row)) toggleRow(page.row);
    else if (event.key === "ArrowRight" && page.collapsed.has(page.row)) toggleRow(page.row);
  } else if (event.key === "ArrowLeft") moveCursor(-by, 0);
  else if (event.key === "ArrowRight") moveCursor(by, 0);
  else if (event.key === "ArrowUp") moveCursor(0, -by);
  else if (event.key === "ArrowDown") moveCursor(0, by);
  else if (event.key === "Enter" && (event.target === $("image") || event.target === document.body)) pick(page.cursor.x, page.cursor.y);
  else if (steps[event.key]) step(steps[event.key]);
  else if (toggles[event.key] && $(toggles[event.key]).parentElement.hidden) {
    status(`transmission has no meaning under the ${page.profile} profile: it casts no transmitted ray (MODEL §11)`);
  } else if (toggles[event.key]) {
    $(toggles[event.key]).checked = !$(toggles[event.key]).checked;
    applyToggles();
  } else if (event.key === "m") {
    $("t-specular").value = $("t-specular").value === "blinn" ? "phong" : "blinn";
    applyToggles();
  } else if (event.key === "[" || event.key === "]") {
    $("t-depth").value = Number($("t-depth").value) + (event.key === "]" ? 1 : -1);
    applyToggles();
  } else if (event.key === "R") render();
  else if (event.key === "?") $("help").showModal();
  else handled = false;
  if (handled) event.preventDefault();
}

// ---- start ---------------------------------------------------------------------

function wire() {
  $("help-text").textContent = HELP;
  $("scene-list").onchange = () => openScene($("scene-list").value);
  $("size").onchange = () => page.load && openScene(page.load.path, { keepText: true });
  $("render").onclick = () => render();
  $("download-png").onclick = () => page.png && download(page.png, `${stem()}.png`, "image/png");
  $("open-files").onchange = (e) => takeFiles([...e.target.files]);
  $("compare-file").onchange = (e) => takeFiles([...e.target.files]);
  $("raylog-file").onchange = (e) => takeFiles([...e.target.files]);
  for (const id of ["t-shadows", "t-reflection", "t-transmission", "t-ambient", "t-specular", "t-depth"]) $(id).onchange = () => applyToggles();
  $("mistake-list").onchange = () => applyToggles();
  $("stepper").onclick = (e) => e.target.dataset.step && step(e.target.dataset.step);
  $("plane").onchange = showDiagram;
  $("shadows").onchange = showDiagram;
  $("download-svg").onclick = () => {
    if (!page.view) return;
    try {
      const [x, y] = page.view.pixel;
      download(call("diagram", diagramArgs(true)), `${stem()}-${x}-${y}-${$("plane").value}.svg`, "image/svg+xml");
    } catch (error) {
      status(error.message);
    }
  };
  $("image").onclick = (e) => {
    const canvas = $("image");
    const x = Math.floor((e.offsetX / canvas.clientWidth) * page.scene.width);
    const y = Math.floor((e.offsetY / canvas.clientHeight) * page.scene.height);
    pick(Math.min(x, page.scene.width - 1), Math.min(y, page.scene.height - 1));
  };
  let editing = 0;
  $("scene-text").oninput = () => {
    clearTimeout(editing);
    editing = setTimeout(() => {
      const path = $("scene-list").value;
      give(path, new TextEncoder().encode($("scene-text").value));
      openScene(path, { keepText: true });
    }, 400);
  };
  document.addEventListener("keydown", onKey);
  document.addEventListener("dragover", (e) => e.preventDefault());
  document.addEventListener("drop", (e) => {
    e.preventDefault();
    takeFiles([...e.dataTransfer.files]);
  });
}

async function start() {
  status("starting…");
  wire();
  page.module = await WebAssembly.compile(await unpack($("wasm").textContent.trim()));
  await startEngine();
  startWorker();
  const bundle = await unpack($("scenes").textContent.trim());
  const newline = bundle.indexOf(10);
  const header = JSON.parse(new TextDecoder().decode(bundle.subarray(0, newline)));
  const files = [];
  let at = newline + 1;
  for (const [path, length] of header) {
    files.push([path, bundle.slice(at, at + length)]);
    at += length;
  }
  const scenes = files.map(([path]) => path).filter((path) => SCENE.test(path));
  for (const path of scenes) addSceneOption(path);
  timings.ready = performance.now();
  // The first scene and every mesh first, so that its render starts before
  // the other scenes (megabytes of them) are handed to the worker.
  const first = scenes.includes("seven-rays.toml") ? "seven-rays.toml" : scenes[0];
  const own = ([path]) => path === first || !SCENE.test(path);
  for (const [path, bytes] of files.filter(own)) give(path, bytes);
  openScene(first);
  for (const [path, bytes] of files.filter((f) => !own(f))) give(path, bytes);
  $("image").focus();
}

start().catch((error) => status(`raystep could not start: ${error.message || error}`));
