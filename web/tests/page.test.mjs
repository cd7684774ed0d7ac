// The web page driven as a person drives it, in Debian's headless
// Chromium through Playwright: real clicks, keys, file drops and
// downloads. tests/suite/web_page.rs writes what the command line answered
// (expectations.json) and runs this; every check compares the page with it.
//
//   node web/tests/page.test.mjs EXPECTATIONS.json

import fs from "node:fs";
import { chromium } from "playwright-core";

const expected = JSON.parse(fs.readFileSync(process.argv[2], "utf8"));
const failures = [];
function check(ok, what) {
  if (!ok) failures.push(what);
  console.log(`${ok ? "ok  " : "FAIL"} ${what}`);
}

const browser = await chromium.launch({
  executablePath: expected.chromium,
  // As the suite's other browser tests: no network, no profile, no GPU.
  args: ["--no-sandbox", "--disable-gpu", "--disable-quic", "--no-first-run",
         "--disable-background-networking", "--disable-component-update", "--disable-sync"],
});
const context = await browser.newContext({ viewport: { width: 1280, height: 720 }, acceptDownloads: true });
const pageUrl = "file://" + expected.page;
const network = [];
context.on("request", (request) => {
  const url = request.url();
  if (url !== pageUrl && !url.startsWith("blob:") && !url.startsWith("data:")) network.push(url);
});
const p = await context.newPage();
const errors = [];
p.on("pageerror", (error) => errors.push(error.message));

/** Runs `action` and waits for the render it starts to be on screen. */
async function rendered(action) {
  const before = await p.evaluate(() => document.body.dataset.rendered || "0");
  await action();
  await p.waitForFunction((b) => (document.body.dataset.rendered || "0") !== b, before, { timeout: 180000 });
}

async function downloadPng() {
  const [download] = await Promise.all([p.waitForEvent("download"), p.click("#download-png")]);
  return fs.readFileSync(await download.path());
}

const same = (bytes, file) => Buffer.compare(bytes, fs.readFileSync(file)) === 0;

/** Drops `file` on the page, as from a file manager. */
async function drop(file, name) {
  const bytes = [...fs.readFileSync(file)];
  const transfer = await p.evaluateHandle(({ bytes, name }) => {
    const dt = new DataTransfer();
    dt.items.add(new File([new Uint8Array(bytes)], name));
    return dt;
  }, { bytes, name });
  await p.dispatchEvent("body", "drop", { dataTransfer: transfer });
}

/** Clicks pixel (x, y) of the image. */
async function clickPixel(x, y) {
  const box = await p.locator("#image").boundingBox();
  const scale = box.width / Number(await p.getAttribute("#image", "data-width"));
  await p.mouse.click(box.x + (x + 0.5) * scale, box.y + (y + 0.5) * scale);
  await p.waitForFunction((at) => document.body.dataset.picked === at, `${x},${y}`);
}

// ---- opening: the first picture, with the keyboard alone ----------------------
await p.goto(pageUrl);
await p.waitForFunction(() => document.body.dataset.rendered, null, { timeout: 60000 });
const opened = await p.evaluate(() => window.raystepTimings.firstPicture);
console.log(`first picture on screen ${Math.round(opened)} ms after opening`);
check(await p.evaluate(() => document.activeElement.id === "image"), "the image has the keyboard's focus on opening");
for (const key of ["ArrowRight", "ArrowRight", "ArrowRight", "ArrowDown", "ArrowDown", "Enter"]) await p.keyboard.press(key);
await p.waitForFunction(() => document.body.dataset.picked === "3,2");
check(true, "arrows and Enter pick pixel (3, 2)");
const keys = expected.keys;
await p.keyboard.press("i");
check(await p.evaluate(() => [...document.querySelectorAll("#events li")].findIndex((li) => li.classList.contains("current"))) === keys.into,
  `i steps into the next ray cast: event ${keys.into}, as the debugger's stepper`);
await p.keyboard.press("e");
check(await p.evaluate(() => [...document.querySelectorAll("#events li")].findIndex((li) => li.classList.contains("current"))) === keys.events - 1,
  `e goes to the last of the pixel's ${keys.events} events`);

// ---- every built-in scene, as `raystep render` writes it --------------------
for (const scene of expected.scenes) {
  await rendered(() => p.selectOption("#scene-list", scene.path));
  check(same(await downloadPng(), scene.png), `${scene.path} renders to the PNG bytes of raystep render`);
}

// ---- the profile, named where the debugger's header names it ---------------------
const profile = expected.profile;
await rendered(() => p.selectOption("#scene-list", profile.scene));
check(await p.isVisible("#profile") && (await p.textContent("#profile")) === profile.text
  && (await p.getAttribute("#profile", "title")) === profile.words,
  `${profile.scene} names its profile: "${profile.text}", with inspect's words`);
check((await p.textContent("#bounces")) === profile.bounces, `${profile.scene}'s depth says "${profile.bounces}"`);
check(!(await p.isVisible("#t-transmission")), `${profile.scene} shows no transmission switch (it refracts nothing)`);
await p.evaluate(() => document.activeElement.blur());
await p.keyboard.press("t");
check((await p.textContent("#status")).startsWith("transmission has no meaning under the cse167 profile"),
  `t under ${profile.scene} says why instead of switching`);
const menu = () => p.$$eval("#mistake-list input", (boxes) => boxes.map((b) => b.dataset.mistake));
check(JSON.stringify(await menu()) === JSON.stringify(profile.offered),
  `${profile.scene}'s mistakes menu offers the ${profile.offered.length} its profile offers`);

// ---- a pixel of glass.toml: explain, the tree, the diagram ------------------------
const pixel = expected.pixel;
await rendered(() => p.selectOption("#scene-list", pixel.scene));
check(!(await p.isVisible("#profile")) && !(await p.isVisible("#bounces")), `${pixel.scene} (the lecture's) names no profile`);
check(await p.isVisible("#t-transmission"), `${pixel.scene} shows its transmission switch again`);
check(JSON.stringify(await menu()) === JSON.stringify(profile.catalogue),
  `${pixel.scene}'s mistakes menu offers the whole catalogue (${profile.catalogue.length}) again`);
await clickPixel(pixel.x, pixel.y);
check((await p.textContent("#explain")) === pixel.explain, `(${pixel.x}, ${pixel.y}): the explain text is the command line's`);
check((await p.textContent("#pixel-title")).includes(`, ${pixel.rays} rays`), `(${pixel.x}, ${pixel.y}): ${pixel.rays} rays, as inspect's tree`);
check((await p.locator("#diagram svg").count()) === 1, "the diagram is drawn");
const click = await p.evaluate(() => window.raystepTimings.pick);
console.log(`a click to the full pixel view: ${click.toFixed(1)} ms`);

// ---- a toggle and a mistake, as the command line's scene and flags ---------------
await rendered(() => p.keyboard.press("["));
check(same(await downloadPng(), expected.depth.png), `[ lowers max depth to ${expected.depth.max_depth}: the render of the scene with that depth`);
await rendered(() => p.keyboard.press("]"));
await p.click("#mistakes summary");
await rendered(() => p.check(`#mistake-list input[data-mistake="${expected.mistake.name}"]`));
check(same(await downloadPng(), expected.mistake.png), `the ${expected.mistake.name} mistake renders as --mistake ${expected.mistake.name}`);
await rendered(() => p.uncheck(`#mistake-list input[data-mistake="${expected.mistake.name}"]`));

// ---- the student's work: a render and a ray log, dropped ---------------------------
await drop(expected.compare.png, "mine.png");
await p.waitForFunction(() => document.body.dataset.compared === "mine.png", null, { timeout: 180000 });
const report = await p.textContent("#compare-report");
check(report.includes(expected.compare.first_mistake) && (await p.textContent("#status")).includes(`${expected.compare.first_mistake} first`),
  `a dropped render is named ${expected.compare.first_mistake}, as compare names it`);
await drop(expected.raylog.file, "mine.jsonl");
await p.waitForFunction(() => document.body.dataset.raylog === "mine.jsonl");
check((await p.textContent("#raylog-pixels")).includes(`first differs at ${expected.raylog.first}`),
  `a dropped ray log's first divergence is ${expected.raylog.first}, as compare --rays says`);
check((await p.locator("#tree .first").count()) === 1, "the tree marks the ray of the first divergence");

// ---- errors, as the command line gives them ---------------------------------------
await p.fill("#size", "4096x4096");
await p.press("#size", "Enter");
await p.waitForFunction(() => document.getElementById("scene-error").textContent.includes("4096"));
check((await p.textContent("#scene-error")).startsWith("error: image size 4096x4096 is too large"), "a 4096x4096 size is refused");

await p.fill("#size", "");
await rendered(() => p.press("#size", "Enter"));
await p.fill("#scene-text", expected.error.text);
await p.waitForFunction(() => !document.getElementById("scene-error").hidden);
check((await p.textContent("#scene-error")) === expected.error.message, "a scene error is shown at its line and column, as the command line says it");
check(network.length === 0, `no network request (${network.join(", ") || "none"})`);
check(errors.length === 0, `no script error (${errors.join("; ") || "none"})`);
await browser.close();
if (failures.length) {
  console.log(`${failures.length} check(s) failed`);
  process.exit(1);
}
