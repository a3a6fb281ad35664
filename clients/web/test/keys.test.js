// The demo page against a server started with --api-keys, in Debian's headless Chromium
// (playwright-core): the page sees that the server asks for a key and shows a key field; a
// refused key says so; with the right one a job runs, its progress followed through the event
// stream read with fetch (EventSource cannot send the header), and every request and download
// carries Authorization: Bearer; the key is kept for the tab (sessionStorage) across a reload.
//   PAPERNET_BIN, PAPERNET_WEB_DIST (built bundle), PAPERNET_SCREENSHOT (its -key.png sibling is
//   written), CHROMIUM (default /usr/bin/chromium).
import { test, before, after } from "node:test";
import assert from "node:assert/strict";
import { createHash, randomBytes } from "node:crypto";
import { mkdtempSync, readFileSync, rmSync, writeFileSync } from "node:fs";
import { tmpdir } from "node:os";
import { join, resolve } from "node:path";
import { chromium } from "playwright-core";
import { startServer, dataDir } from "../../js/test/server.js";

const executablePath = process.env.CHROMIUM ?? "/usr/bin/chromium";
const screenshot = resolve(process.env.PAPERNET_SCREENSHOT ?? join(tmpdir(), "papernet-demo.png")).replace(/\.png$/, "-key.png");
const secret = `demo-${randomBytes(12).toString("hex")}`;

let server;
let context;
let dir;

before(async () => {
  assert.ok(process.env.PAPERNET_WEB_DIST, "set PAPERNET_WEB_DIST to the built web bundle (node web/build.mjs DIR)");
  process.env.PAPERNET_WEB_ROOT = process.env.PAPERNET_WEB_DIST;
  dir = mkdtempSync(join(tmpdir(), "papernet-keys-"));
  const keys = join(dir, "keys.txt");
  writeFileSync(keys, `shop ${createHash("sha256").update(secret).digest("hex")} name=demo\n`);
  server = await startServer(["--workers", "1", "--api-keys", keys]);
  context = await chromium.launchPersistentContext(join(dir, "profile"), {
    executablePath,
    headless: true,
    acceptDownloads: true,
    viewport: { width: 1280, height: 800 },
    args: ["--headless", "--no-sandbox", "--disable-gpu", "--no-first-run", "--disable-background-networking", "--disable-component-update", "--disable-sync", "--use-angle=swiftshader", "--enable-unsafe-swiftshader"],
  });
});

after(async () => {
  await context?.close();
  await server?.stop();
  if (dir) rmSync(dir, { recursive: true, force: true });
});

const finished = () => ["done", "failed", "cancelled", "error", "key"].includes(document.body.dataset.state);

async function enterKey(page, key) {
  await page.fill("#api-key", key);
  await page.press("#api-key", "Tab"); // commits the field: its change event
}

test("the demo asks for the API key, keeps it and sends it with every request", async () => {
  const page = await context.newPage();
  const problems = [];
  page.on("pageerror", (e) => problems.push(`page error: ${e.message}`));
  const requests = [];
  page.on("request", (r) => {
    if (new URL(r.url()).pathname.startsWith("/v1/")) requests.push({ path: new URL(r.url()).pathname, auth: r.headers().authorization });
  });

  await page.goto(`${server.url}/`);
  await page.waitForSelector("#key-box:not([hidden])");
  assert.match(await page.textContent("#status"), /needs an API key/);
  assert.equal(await page.evaluate(() => document.activeElement.id), "api-key");
  await page.screenshot({ path: screenshot.replace(/\.png$/, "-asked.png") });

  // A wrong key: the job is refused and the page says so.
  await enterKey(page, "not-the-key");
  await page.setInputFiles("#file", join(dataDir, "sample.obj"));
  await page.selectOption("#strategy", "TU");
  await page.click("#start");
  await page.waitForFunction(finished);
  assert.equal(await page.evaluate(() => document.body.dataset.state), "key");
  assert.match(await page.textContent("#status"), /did not accept the API key/);

  // The right key: the job runs to its net.
  await enterKey(page, secret);
  await page.evaluate(() => delete document.body.dataset.state);
  const start = requests.length;
  await page.click("#start");
  await page.waitForFunction(finished, null, { timeout: 120000 });
  const status = await page.textContent("#status");
  assert.equal(await page.evaluate(() => document.body.dataset.state), "done", status);
  assert.match(status, /^(succeeded|approximated): net of \d+ faces/);
  assert.ok((await page.locator("#net svg path").count()) > 0, "the net is drawn");
  const sent = requests.slice(start);
  assert.ok(sent.some((r) => r.path.endsWith("/events")), `progress followed through the stream: ${JSON.stringify(sent)}`);
  assert.ok(sent.length > 2 && sent.every((r) => r.auth === `Bearer ${secret}`), JSON.stringify(sent));
  assert.equal(await page.evaluate(() => sessionStorage.getItem("papernet.apiKey")), secret);

  // A download is fetched with the key (a plain link could not send it), and saved under the
  // name the server gives it: the kit's title, which the demo takes from the file's name.
  const [download] = await Promise.all([page.waitForEvent("download"), page.click("#dl-svg")]);
  assert.equal(download.suggestedFilename(), "sample.svg");
  assert.match(readFileSync(await download.path(), "utf8").trimStart(), /^<(\?xml|svg)/);
  // With a sheet shown, the SVG link saves that sheet alone.
  await page.selectOption("#sheet", "2");
  await page.waitForFunction(() => document.querySelector("#dl-svg").textContent === "SVG (sheet 2)");
  const [sheet] = await Promise.all([page.waitForEvent("download"), page.click("#dl-svg")]);
  assert.equal(sheet.suggestedFilename(), "sample - page 2.svg");
  assert.match(readFileSync(await sheet.path(), "utf8"), /sample \u00b7 page 2 of \d+/);
  await page.screenshot({ path: screenshot, fullPage: true });
  console.log(`screenshot: ${screenshot}`);

  // The key is kept for the tab: after a reload it is in the field and no longer asked for.
  await page.reload();
  await page.waitForSelector("#key-box:not([hidden])");
  assert.equal(await page.inputValue("#api-key"), secret);
  assert.doesNotMatch(await page.textContent("#status"), /API key/);
  assert.deepEqual(problems, []);
});
