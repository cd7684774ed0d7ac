// The web page's figures (BENCHMARKS.md): its size, the first picture
// after opening, a render of glass.toml at 320x240 against the native
// single-thread render, and a click to the full pixel view on glass.toml
// and teapot.nff. Medians of several runs; the machine is shared and noisy.
//
//   node web/tests/bench.mjs dist/raystep.html target/release/raystep

import fs from "node:fs";
import path from "node:path";
import { execFileSync } from "node:child_process";
import { chromium } from "playwright-core";

const [pageFile, raystep] = process.argv.slice(2).map((p) => path.resolve(p));
const runs = 5;
const median = (xs) => [...xs].sort((a, b) => a - b)[Math.floor(xs.length / 2)];
const browser = await chromium.launch({
  executablePath: "/usr/bin/chromium",
  args: ["--no-sandbox", "--disable-gpu", "--disable-background-networking", "--disable-component-update"],
});

async function open() {
  const p = await browser.newPage({ viewport: { width: 1280, height: 720 } });
  await p.goto("file://" + pageFile);
  await p.waitForFunction(() => document.body.dataset.rendered, null, { timeout: 60000 });
  return p;
}

async function renderScene(p, scene, size) {
  const before = await p.evaluate(() => document.body.dataset.rendered);
  await p.fill("#size", size);
  await p.selectOption("#scene-list", scene);
  await p.evaluate(() => document.getElementById("size").dispatchEvent(new Event("change")));
  await p.waitForFunction((b) => document.body.dataset.rendered !== b, before, { timeout: 120000 });
  // A second render, of the settled scene, is the one measured.
  const settled = await p.evaluate(() => document.body.dataset.rendered);
  await p.click("#render");
  await p.waitForFunction((b) => document.body.dataset.rendered !== b, settled, { timeout: 120000 });
  return p.evaluate(() => window.raystepTimings.render);
}

async function clicks(p, scene, size) {
  await renderScene(p, scene, size);
  const times = [];
  const box = await p.locator("#image").boundingBox();
  for (let i = 0; i < runs; i++) {
    const [fx, fy] = [0.3 + 0.1 * i, 0.5];
    await p.mouse.click(box.x + fx * box.width, box.y + fy * box.height);
    await p.waitForTimeout(50);
    times.push(await p.evaluate(() => window.raystepTimings.pick));
  }
  return median(times);
}

const firsts = [];
for (let i = 0; i < 3; i++) {
  const p = await open();
  firsts.push(await p.evaluate(() => window.raystepTimings.firstPicture));
  await p.close();
}
const p = await open();
const pageRenders = [];
for (let i = 0; i < 3; i++) pageRenders.push(await renderScene(p, "glass.toml", "320x240"));
const glassClick = await clicks(p, "glass.toml", "");
const teapotClick = await clicks(p, "spd/teapot.nff", "");
await browser.close();

const root = path.resolve(path.dirname(new URL(import.meta.url).pathname), "../..");
const out = path.join(fs.mkdtempSync("/tmp/raystep-bench-"), "glass.png");
const native = [];
for (let i = 0; i < runs; i++) {
  const said = execFileSync(raystep, ["render", "scenes/glass.toml", "--size", "320x240", "--threads", "1",
    "--timings", "-o", out], { cwd: root });
  native.push(JSON.parse(said.toString()).trace_seconds * 1000);
}
const page = median(pageRenders), cli = median(native);
console.log(`page file:                ${(fs.statSync(pageFile).size / 1e6).toFixed(2)} MB`);
console.log(`first picture on screen:  ${median(firsts).toFixed(0)} ms after opening (median of 3)`);
console.log(`glass.toml 320x240:       page ${page.toFixed(0)} ms (render and PNG, in the worker), native one thread ${cli.toFixed(0)} ms (trace): ${(page / cli).toFixed(2)}x`);
console.log(`click to the pixel view:  glass.toml ${glassClick.toFixed(1)} ms, teapot.nff ${teapotClick.toFixed(1)} ms (medians of ${runs})`);
