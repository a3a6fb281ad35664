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

// Waits until the page's job has ended (done, failed, cancelled or error) and returns that state.
async function jobEnded(page, timeout) {
  await page.waitForFunction(() => ["done", "failed", "cancelled", "error"].includes(document.body.dataset.state), null, {
    timeout,
  });
  return page.evaluate(() => document.body.dataset.state);
}

// The colours a person sees in an element: its screenshot, decoded by the browser, counted.
// `background`: the page's near-white; of the rest, `beige` is the paper colour every model was
// drawn in before the demo showed colour (0xf2e6c9 however lit; not counted at the rim of the
// model, where the anti-aliased edge of a yellow face on the near-white background is pale
// yellow too: thin pieces, folding, are mostly rim), `saturated` is colour far from any grey or
// beige, `tinted` any colour not grey (the overview's pastel pieces), and `yellow` (the Duck),
// `blue` and `green` (BoxTextured's logo) name hues.
async function colours(page, selector) {
  const png = (await page.locator(selector).screenshot()).toString("base64");
  return page.evaluate(async (b64) => {
    const bytes = Uint8Array.from(atob(b64), (c) => c.charCodeAt(0));
    const bitmap = await createImageBitmap(new Blob([bytes], { type: "image/png" }));
    const canvas = document.createElement("canvas");
    canvas.width = bitmap.width;
    canvas.height = bitmap.height;
    const context = canvas.getContext("2d");
    context.drawImage(bitmap, 0, 0);
    const d = context.getImageData(0, 0, bitmap.width, bitmap.height).data;
    const n = { pixels: 0, background: 0, beige: 0, saturated: 0, tinted: 0, yellow: 0, blue: 0, green: 0 };
    const w = bitmap.width;
    const background = (i) => {
      const [r, g, b] = [d[i], d[i + 1], d[i + 2]];
      return Math.min(r, g, b) > 235 && Math.max(r, g, b) - Math.min(r, g, b) < 12;
    };
    for (let i = 0; i < d.length; i += 4) {
      const [r, g, b] = [d[i], d[i + 1], d[i + 2]];
      const max = Math.max(r, g, b);
      const min = Math.min(r, g, b);
      n.pixels++;
      if (background(i)) {
        n.background++;
        continue;
      }
      const p = i / 4, x = p % w;
      const rim = (x > 0 && background(i - 4)) || (x + 1 < w && background(i + 4)) ||
        (p >= w && background(i - 4 * w)) || (i + 4 * w < d.length && background(i + 4 * w));
      if (!rim && r >= g && g >= b && r - b >= 10 && (r - b) / Math.max(r, 1) < 0.3) n.beige++;
      if (max > 60 && (max - min) / max > 0.45) n.saturated++;
      if (max - min >= 25) n.tinted++;
      if (r > 170 && g > 110 && b < 100 && r - b > 110) n.yellow++;
      if (b > r + 40 && b >= g) n.blue++;
      if (g > r + 20 && g > b + 10) n.green++;
    }
    return n;
  }, png);
}

// The model as folded in the 3D view against its coordinates in the net JSON: the scene's z
// must be the model's y for a glTF (y up), and its x the model's x, every corner (up to a shift);
// `yy`, `zz`: the same for a model drawn as its coordinates say.
async function uprightness(page) {
  return page.evaluate(() => {
    const { folding, THREE } = window.papernetDemo;
    const { vertices, faces } = folding.doc.mesh;
    const p = folding.mesh.geometry.attributes.position.array;
    folding.mesh.updateMatrixWorld(true);
    const range = () => [Infinity, -Infinity];
    const spread = { zy: range(), xx: range(), ynz: range(), yy: range(), zz: range() };
    const extent = [[Infinity, -Infinity], [Infinity, -Infinity], [Infinity, -Infinity]];
    const v = new THREE.Vector3();
    const grow = (range, x) => ((range[0] = Math.min(range[0], x)), (range[1] = Math.max(range[1], x)));
    faces.forEach((f, i) =>
      f.forEach((vertex, k) => {
        v.fromArray(p, i * 9 + k * 3);
        folding.mesh.localToWorld(v);
        const [x, y, z] = vertices[vertex];
        grow(spread.zy, v.z - y);
        grow(spread.xx, v.x - x);
        grow(spread.ynz, v.y + z);
        grow(spread.yy, v.y - y);
        grow(spread.zz, v.z - z);
        [x, y, z].forEach((c, a) => grow(extent[a], c));
      }),
    );
    const box = new THREE.Box3().setFromObject(folding.mesh);
    const size = box.getSize(new THREE.Vector3());
    const width = (r) => r[1] - r[0];
    return {
      diagonal: Math.hypot(...extent.map(width)),
      modelSize: extent.map(width),
      sceneSize: [size.x, size.y, size.z],
      zy: width(spread.zy),
      xx: width(spread.xx),
      ynz: width(spread.ynz),
      yy: width(spread.yy),
      zz: width(spread.zz),
    };
  });
}

// Waits for the 3D view's textures; answers what its materials are drawn with.
async function shownMaterials(page) {
  return page.evaluate(async () => {
    const { folding } = window.papernetDemo;
    const loaded = await folding.ready;
    return {
      loaded,
      materials: folding.mesh.material.map((m) => ({
        map: m.map ? { width: m.map.image?.width ?? 0, height: m.map.image?.height ?? 0 } : null,
        color: m.color.getHexString(),
        vertexColors: m.vertexColors,
      })),
      hasUv: !!folding.mesh.geometry.attributes.uv,
    };
  });
}

function assertUpright(u, what) {
  const tolerance = 1e-4 * u.diagonal;
  assert.ok(u.zy < tolerance && u.xx < tolerance && u.ynz < tolerance, `${what} stands as in its file (scene z = glTF y): ${JSON.stringify(u)}`);
  for (const [scene, model] of [[0, 0], [1, 2], [2, 1]]) {
    assert.ok(Math.abs(u.sceneSize[scene] - u.modelSize[model]) < 1e-3 * u.diagonal, `${what}'s bounding box: ${JSON.stringify(u)}`);
  }
}

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

  const state = await jobEnded(page, 300000);
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

  // Colour: with every face the Duck's net carries texture coordinates; the 3D view maps the
  // texture on the model, which stands (glTF is y up, the scene z up) and is yellow, not beige.
  const duck = sampleName === "Duck.glb";
  if (duck) {
    const shown = await shownMaterials(page);
    assert.ok(shown.hasUv && shown.loaded >= 1, JSON.stringify(shown));
    assert.ok(shown.materials.some((m) => m.map && m.map.width === 512 && m.map.height === 512), `the texture is mapped: ${JSON.stringify(shown)}`);
    assertUpright(await uprightness(page), "the Duck");
    const folded = await colours(page, "#model canvas");
    const model = folded.pixels - folded.background;
    console.log(`Duck folded: ${JSON.stringify(folded)}`);
    assert.ok(model > 0.05 * folded.pixels, `the model fills the view: ${JSON.stringify(folded)}`);
    assert.ok(folded.yellow > 0.5 * model && folded.beige < 0.1 * model, `the Duck is yellow: ${JSON.stringify(folded)}`);
    // The net as printed (the server's SVG): coloured too.
    const net = await colours(page, "#net");
    console.log(`Duck net: ${JSON.stringify(net)}`);
    assert.ok(net.yellow > 0.02 * net.pixels, `the net is coloured: ${JSON.stringify(net)}`);
    await page.screenshot({ path: screenshot.replace(/\.png$/, "-folded.png"), fullPage: true });
  }

  // Fold slider: half folded, then back to fully folded; the label follows.
  assert.equal(await page.isDisabled("#fold"), false);
  await page.locator("#fold").fill("0");
  assert.equal(await page.textContent("#fold-value"), "flat net");
  const flatPixels = await page.locator("#model canvas").screenshot();
  await page.locator("#fold").fill("0.5");
  assert.equal(await page.textContent("#fold-value"), "50 % folded");
  const halfPixels = await page.locator("#model canvas").screenshot();
  assert.notDeepEqual(flatPixels, halfPixels, "moving the fold slider changes the 3D view");
  if (duck) {
    // Folding, the faces keep their texture: the half-folded Duck is yellow too (less of it:
    // pieces seen edge on, their backs and the folds between small faces are darker).
    await page.waitForTimeout(100);
    const half = await colours(page, "#model canvas");
    const model = half.pixels - half.background;
    assert.ok(half.yellow > 0.25 * model && half.beige < 0.1 * model, `folding, the net is yellow: ${JSON.stringify(half)}`);
  }

  // The download links answer with the files.
  for (const [id, magic] of [["#dl-svg", "<"], ["#dl-pdf", "%PDF"], ["#dl-glb", "glTF"]]) {
    const href = await page.getAttribute(id, "href");
    const res = await page.request.get(new URL(href, server.url).toString());
    assert.equal(res.status(), 200, href);
    assert.ok((await res.body()).toString("latin1").trimStart().startsWith(magic), `${href} starts with ${magic}`);
  }
  // Saved, the PDF is named after the kit (the server's Content-Disposition: the title left
  // empty, the demo sends the file's name), not net.pdf.
  const kit = sampleName.replace(/\.[^.]*$/, "");
  const [download] = await Promise.all([page.waitForEvent("download"), page.click("#dl-pdf")]);
  assert.equal(download.suggestedFilename(), `${kit}.pdf`);

  // The status says the detail printed; the sheets, one by one, as the printer prints them.
  assert.match(await page.textContent("#status"), / · detail full · /);
  const sheets = await page.locator("#sheet option").count();
  assert.ok(sheets > 2, `the sheet chooser lists the whole net and the sheets: ${sheets}`);
  await page.selectOption("#sheet", "2");
  await page.waitForFunction((n) => document.querySelector("#net svg")?.textContent.includes(`page 2 of ${n}`), sheets - 1);
  assert.ok((await page.locator("#net svg path").count()) > 0, "sheet 2 has paths");
  // The SVG link now saves that sheet alone, named after the kit and the page.
  await page.waitForFunction(() => document.querySelector("#dl-svg").textContent === "SVG (sheet 2)");
  const [sheetFile] = await Promise.all([page.waitForEvent("download"), page.click("#dl-svg")]);
  assert.equal(sheetFile.suggestedFilename(), `${kit} - page 2.svg`);
  // Named after the file (the title left empty), with the key to its lines.
  // The drawn text (not the SVG's <title>, which says the same line).
  const sheetText = (await page.locator("#net svg text").allTextContents()).join("\n");
  assert.equal(await page.locator("#net svg > title").textContent(), `${kit} \u00b7 page 2 of ${sheets - 1}`);
  assert.ok(sheetText.includes(`${kit} \u00b7 page 2 of ${sheets - 1}`), `sheet 2 is named ${kit}`);
  assert.ok(["cut", "mountain fold", "valley fold"].every((k) => sheetText.includes(k)), "sheet 2 has the key to its lines");

  mkdirSync(dirname(screenshot), { recursive: true });
  await page.screenshot({ path: screenshot, fullPage: true });
  assert.ok(statSync(screenshot).size > 10000);
  console.log(`screenshot: ${screenshot}`);
  // The overview (page 1) shows the model as built from two sides, each piece in a colour of its
  // own: two images on the page, and colour where the line art alone has none.
  await page.selectOption("#sheet", "1");
  await page.waitForFunction((n) => document.querySelector("#net svg")?.textContent.includes(`page 1 of ${n}`), sheets - 1);
  assert.equal(await page.locator("#net svg image").count(), 2, "the overview's two views of the model");
  const overview = await colours(page, "#net");
  assert.ok(overview.tinted > 0.002 * overview.pixels, `the views are in colour: ${JSON.stringify(overview)}`);
  await page.screenshot({ path: screenshot.replace(/\.png$/, "-overview.png"), fullPage: true });
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
    return {
      state: await jobEnded(page, 120000),
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

test("the demo shows a textured glTF textured and upright, folded, flat and in the net", async () => {
  const page = await context.newPage();
  const problems = [];
  page.on("pageerror", (e) => problems.push(`page error: ${e.message}`));
  // Errors, and the demo's own warning that a texture could not be shown.
  page.on("console", (m) => (m.type() === "error" || /^texture not shown/.test(m.text())) && problems.push(`console: ${m.text()}`));
  const foreign = [];
  page.on("request", (r) => {
    if (!r.url().startsWith(server.url)) foreign.push(r.url());
  });
  await page.goto(`${server.url}/`);
  await page.waitForSelector("#model canvas");
  await page.setInputFiles("#file", join(dataDir, "BoxTextured.glb"));
  await page.selectOption("#strategy", "TU");
  await page.fill("#detail", "full");
  await page.selectOption("#paper", "A5");
  await page.selectOption("#prefer", "pieces");
  const submitted = page.waitForRequest((r) => r.method() === "POST" && new URL(r.url()).pathname === "/v1/jobs");
  await page.click("#start");
  // The paper and what the pieces save first go to the service as chosen.
  const query = new URL((await submitted).url()).searchParams;
  assert.equal(query.get("paper"), "A5");
  assert.equal(query.get("prefer"), "pieces");
  assert.equal(await jobEnded(page, 120000), "done", await page.textContent("#status"));

  // The texture (the Cesium logo, 256 × 256) is mapped by the faces' coordinates.
  const shown = await shownMaterials(page);
  assert.equal(shown.loaded, 1, JSON.stringify(shown));
  assert.ok(shown.hasUv);
  assert.deepEqual(shown.materials.map((m) => m.map), [{ width: 256, height: 256 }], JSON.stringify(shown));
  assertUpright(await uprightness(page), "the box");

  // On screen: the logo's blue sky and green hills, folded and flat; no beige paper.
  const seen = {};
  for (const [t, name] of [["1", "folded"], ["0", "flat"]]) {
    await page.locator("#fold").fill(t);
    await page.waitForTimeout(100);
    const c = (seen[name] = await colours(page, "#model canvas"));
    const model = c.pixels - c.background;
    assert.ok(model > 0.03 * c.pixels, `${name}: the box is in view: ${JSON.stringify(c)}`);
    assert.ok(c.blue > 0.1 * model && c.green > 0.1 * model, `${name}: the logo's colours: ${JSON.stringify(c)}`);
    assert.ok(c.beige < 0.05 * model, `${name}: no beige: ${JSON.stringify(c)}`);
  }
  // The net (the server's SVG, coloured by its bake) shows the logo's colours too.
  const net = (seen.net = await colours(page, "#net"));
  assert.ok(net.blue > 0.01 * net.pixels && net.green > 0.01 * net.pixels, `the net is coloured: ${JSON.stringify(net)}`);
  console.log(`BoxTextured: ${JSON.stringify(seen)}`);
  await page.locator("#fold").fill("0.6");
  const shot = screenshot.replace(/\.png$/, "-box.png");
  await page.screenshot({ path: shot, fullPage: true });
  console.log(`screenshot: ${shot}`);
  assert.deepEqual(problems, []);
  assert.deepEqual(foreign, []);
});

test("the demo shows a model's vertex colours (a PLY cube, z up as its coordinates say)", async () => {
  // A unit cube whose corner (x, y, z) is coloured (r, g, b) = (x, y, z).
  const corners = [0, 1].flatMap((x) => [0, 1].flatMap((y) => [0, 1].map((z) => [x, y, z])));
  const quads = [[0, 1, 3, 2], [4, 6, 7, 5], [0, 4, 5, 1], [2, 3, 7, 6], [0, 2, 6, 4], [1, 5, 7, 3]];
  const ply = [
    "ply", "format ascii 1.0", "element vertex 8", "property float x", "property float y", "property float z",
    "property uchar red", "property uchar green", "property uchar blue", "element face 12",
    "property list uchar int vertex_indices", "end_header",
    ...corners.map((p) => `${p.join(" ")} ${p.map((c) => 255 * c).join(" ")}`),
    ...quads.flatMap(([a, b, c, d]) => [`3 ${a} ${b} ${c}`, `3 ${a} ${c} ${d}`]),
  ].join("\n");
  const page = await context.newPage();
  const problems = [];
  page.on("pageerror", (e) => problems.push(`page error: ${e.message}`));
  await page.goto(`${server.url}/`);
  await page.waitForSelector("#model canvas");
  await page.setInputFiles("#file", { name: "cube.ply", mimeType: "application/octet-stream", buffer: Buffer.from(ply) });
  await page.selectOption("#strategy", "TU");
  await page.click("#start");
  assert.equal(await jobEnded(page, 120000), "done", await page.textContent("#status"));
  const shown = await shownMaterials(page);
  assert.ok(shown.materials.every((m) => m.vertexColors && m.color === "ffffff" && !m.map), JSON.stringify(shown));
  // Not turned: the scene's z is the file's z (only glTF is y up).
  const u = await uprightness(page);
  assert.ok(Math.max(u.xx, u.yy, u.zz) < 1e-4 * u.diagonal, `the cube as its coordinates say: ${JSON.stringify(u)}`);
  const c = await colours(page, "#model canvas");
  const model = c.pixels - c.background;
  assert.ok(c.saturated > 0.5 * model && c.blue > 0.05 * model && c.beige < 0.05 * model, `the cube's colours: ${JSON.stringify(c)}`);
  assert.deepEqual(problems, []);
});
