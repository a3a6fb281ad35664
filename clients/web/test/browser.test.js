// End to end: the demo page served by `papernet serve` (PAPERNET_WEB_ROOT = the built bundle),
// driven in Debian's headless Chromium by playwright-core. Uploads a sample mesh, waits for the
// net, checks the SVG net and the 3D canvas, moves the fold slider and saves a screenshot.
//   PAPERNET_BIN, PAPERNET_WEB_DIST (built bundle), PAPERNET_SCREENSHOT (PNG path to write),
//   CHROMIUM (default /usr/bin/chromium), PAPERNET_DEMO_SAMPLE / PAPERNET_DEMO_STRATEGY.
import { test, before, after } from "node:test";
import assert from "node:assert/strict";
import { mkdtempSync, rmSync, statSync, mkdirSync } from "node:fs";
import { tmpdir } from "node:os";
import { dirname, join, resolve } from "node:path";
import { chromium } from "playwright-core";
import { startServer, dataDir } from "../../js/test/server.js";

const executablePath = process.env.CHROMIUM ?? "/usr/bin/chromium";
const screenshot = resolve(process.env.PAPERNET_SCREENSHOT ?? join(tmpdir(), "papernet-demo.png"));
const sampleName = process.env.PAPERNET_DEMO_SAMPLE ?? "Duck.glb";
const strategy = process.env.PAPERNET_DEMO_STRATEGY ?? "QQ";

let server;
let context;
let profile;

before(async () => {
  const dist = process.env.PAPERNET_WEB_DIST;
  if (!process.env.PAPERNET_URL) {
    assert.ok(dist, "set PAPERNET_WEB_DIST to the built web bundle (node web/build.mjs DIR)");
    process.env.PAPERNET_WEB_ROOT = dist;
  }
  server = await startServer(["--workers", "1"]);
  profile = mkdtempSync(join(tmpdir(), "papernet-chromium-"));
  context = await chromium.launchPersistentContext(profile, {
    executablePath,
    headless: true,
    viewport: { width: 1280, height: 800 },
    args: [
      "--headless",
      "--no-sandbox",
      "--disable-gpu",
      "--disable-quic",
      "--no-first-run",
      "--disable-background-networking",
      "--disable-component-update",
      "--disable-sync",
      "--use-angle=swiftshader",
      "--enable-unsafe-swiftshader",
    ],
  });
});

after(async () => {
  await context?.close();
  await server?.stop();
  if (profile) rmSync(profile, { recursive: true, force: true });
});

test(`the demo page unfolds ${sampleName} and folds the net`, async () => {
  const page = await context.newPage();
  const problems = [];
  page.on("pageerror", (e) => problems.push(`page error: ${e.message}`));
  page.on("console", (m) => m.type() === "error" && problems.push(`console: ${m.text()}`));
  // Nothing but the papernet server may be asked for anything (no CDN, no network).
  const foreign = [];
  page.on("request", (r) => {
    if (!r.url().startsWith(server.url)) foreign.push(r.url());
  });

  await page.goto(`${server.url}/`);
  await page.waitForSelector("#model canvas");
  await page.setInputFiles("#file", join(dataDir, sampleName));
  await page.selectOption("#strategy", strategy);
  await page.fill("#size", "120");
  await page.fill("#detail", "full"); // every face: the live approximation levels are tested
  await page.selectOption("#paper", "A4");
  await page.fill("#time-limit", "240");
  // Record every status line and every value of the bar, to check the live progress shown while
  // the job runs.
  await page.evaluate(() => {
    window.statusLog = [];
    window.barLog = [];
    const status = document.getElementById("status");
    new MutationObserver(() => window.statusLog.push(status.textContent)).observe(status, {
      childList: true,
      characterData: true,
      subtree: true,
    });
    const bar = document.getElementById("progress");
    new MutationObserver(() => bar.hasAttribute("value") && window.barLog.push(bar.value)).observe(bar, {
      attributes: true,
      attributeFilter: ["value"],
    });
  });
  await page.click("#start");

  await page.waitForFunction(() => ["done", "failed", "cancelled", "error"].includes(document.body.dataset.state), null, {
    timeout: 300000,
  });
  const state = await page.evaluate(() => document.body.dataset.state);
  const status = await page.textContent("#status");
  assert.equal(state, "done", `page ended in ${state}: ${status}`);
  assert.match(status, /^(succeeded|approximated): net of \d+ faces/);
  assert.match(status, / · \d+ glue tabs, \d+ glue strips, \d+ pages/, "the print's glue and pages are shown");
  const log = await page.evaluate(() => window.statusLog);
  const live = log.filter((line) => /^running · .*approximation: \d+ of \d+ faces/.test(line));
  assert.ok(live.length > 0, `the approximation level was shown while running: ${JSON.stringify(log.slice(0, 5))}`);
  console.log(`live status lines: ${live.length}, e.g. ${live[Math.floor(live.length / 2)]}`);
  // The bar: the job's one fraction over every phase, never back, full only at the end.
  const bar = await page.evaluate(() => window.barLog);
  assert.ok(bar.length > 1, `the bar moved: ${JSON.stringify(bar)}`);
  assert.ok(bar.every((v, i) => i === 0 || v >= bar[i - 1]), `the bar never goes back: ${JSON.stringify(bar)}`);
  assert.equal(bar.at(-1), 1);
  assert.ok(bar.some((v) => v > 0 && v < 1), `the bar went through the run: ${JSON.stringify(bar)}`);
  assert.ok(log.some((line) => /^running · tabs · \d+ %/.test(line)), "the tabs phase is shown with the fraction");

  // The net: the server's SVG with drawn paths.
  const paths = await page.locator("#net svg path").count();
  assert.ok(paths > 0, "the net SVG has paths");
  const box = await page.locator("#net svg").boundingBox();
  assert.ok(box && box.width > 100 && box.height > 100, `net is drawn at a visible size: ${JSON.stringify(box)}`);
  // The 3D view: a WebGL canvas of real size.
  const canvas = await page.locator("#model canvas").boundingBox();
  assert.ok(canvas && canvas.width > 100 && canvas.height > 100);
  assert.equal(await page.getAttribute("#dl-pdf", "href"), await page.evaluate(() => document.getElementById("dl-pdf").href.replace(location.origin, "")));

  // Fold slider: half folded, then back to fully folded; the label follows.
  assert.equal(await page.isDisabled("#fold"), false);
  await page.locator("#fold").fill("0");
  assert.equal(await page.textContent("#fold-value"), "flat net");
  const flatPixels = await page.locator("#model canvas").screenshot();
  await page.locator("#fold").fill("0.5");
  assert.equal(await page.textContent("#fold-value"), "50 % folded");
  const halfPixels = await page.locator("#model canvas").screenshot();
  assert.notDeepEqual(flatPixels, halfPixels, "moving the fold slider changes the 3D view");

  // The download links answer with the files.
  for (const [id, magic] of [["#dl-svg", "<"], ["#dl-pdf", "%PDF"], ["#dl-glb", "glTF"]]) {
    const href = await page.getAttribute(id, "href");
    const res = await page.request.get(new URL(href, server.url).toString());
    assert.equal(res.status(), 200, href);
    assert.ok((await res.body()).toString("latin1").trimStart().startsWith(magic), `${href} starts with ${magic}`);
  }

  // The status says the detail printed; the sheets, one by one, as the printer prints them.
  assert.match(await page.textContent("#status"), / · detail full · /);
  const sheets = await page.locator("#sheet option").count();
  assert.ok(sheets > 2, `the sheet chooser lists the whole net and the sheets: ${sheets}`);
  await page.selectOption("#sheet", "2");
  await page.waitForFunction((n) => document.querySelector("#net svg")?.textContent.includes(`page 2 of ${n}`), sheets - 1);
  assert.ok((await page.locator("#net svg path").count()) > 0, "sheet 2 has paths");

  mkdirSync(dirname(screenshot), { recursive: true });
  await page.screenshot({ path: screenshot, fullPage: true });
  assert.ok(statSync(screenshot).size > 10000);
  console.log(`screenshot: ${screenshot}`);
  await page.selectOption("#sheet", "0");
  assert.deepEqual(problems, []);
  assert.deepEqual(foreign, []);
});

test("the demo unfolds every part of a model, or only the largest, and lists the repairs", async () => {
  const page = await context.newPage();
  const problems = [];
  page.on("pageerror", (e) => problems.push(`page error: ${e.message}`));
  await page.goto(`${server.url}/`);
  await page.waitForSelector("#model canvas");
  // A .gltf with its buffer and texture: the truck's 11 parts, two of them pinched.
  const truck = ["CesiumMilkTruck.gltf", "CesiumMilkTruck0.bin", "CesiumMilkTruck.png"].map((f) =>
    join(dataDir, "CesiumMilkTruck", f),
  );
  const run = async (components) => {
    await page.setInputFiles("#file", truck);
    await page.selectOption("#strategy", "TU");
    await page.selectOption("#components", components);
    await page.evaluate(() => delete document.body.dataset.state);
    await page.click("#start");
    await page.waitForFunction(() => ["done", "failed", "cancelled", "error"].includes(document.body.dataset.state), null, {
      timeout: 120000,
    });
    return {
      state: await page.evaluate(() => document.body.dataset.state),
      status: await page.textContent("#status"),
      repairs: await page.$$eval("#repairs li", (items) => items.map((li) => [li.dataset.code, li.textContent])),
    };
  };
  const all = await run("all");
  assert.equal(all.state, "done", all.status);
  assert.match(all.status, /net of \d+ faces in (\d+) pieces of (\d+) parts/);
  assert.ok(Number(all.status.match(/of (\d+) parts/)[1]) > 10, all.status);
  assert.ok(all.repairs.some(([code]) => code === "split_pinched_vertices"), JSON.stringify(all.repairs));
  assert.ok(await page.isVisible("#repairs"));
  const pieces = screenshot.replace(/\.png$/, "-pieces.png");
  await page.screenshot({ path: pieces, fullPage: true });
  console.log(`screenshot: ${pieces}`);
  const largest = await run("largest");
  assert.equal(largest.state, "done", largest.status);
  assert.doesNotMatch(largest.status, / parts/);
  assert.ok(largest.repairs.some(([code, text]) => code === "dropped_components" && /kept the largest/.test(text)), JSON.stringify(largest.repairs));
  console.log(`parts: "${all.status.split(" · ")[0]}"; repairs: ${all.repairs.map(([c]) => c).join(", ")}`);
  assert.deepEqual(problems, []);
});
