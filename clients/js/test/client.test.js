// The JS client against a real `papernet serve` (see server.js), with the repository's meshes.
import { test, before, after } from "node:test";
import assert from "node:assert/strict";
import { PapernetClient, PapernetError, fileNameOf, isFinal, parseSse, parseLevel, progressFraction } from "../papernet.js";
import { startServer, sample } from "./server.js";

let server;
let client;

before(async () => {
  // One worker, so a second job stays queued while the first runs (cancel test).
  server = await startServer(["--workers", "1", "--access-log", "false"]);
  client = new PapernetClient(server.url);
});

after(async () => {
  await server?.stop();
});

/** Checks the papernet.net/2 invariants the demo's folding relies on. */
function checkNet(net) {
  assert.equal(net.format, "papernet.net/2");
  assert.ok(["complete", "approximate"].includes(net.result));
  const faces = net.mesh.faces;
  assert.ok(faces.length >= 4);
  assert.equal(net.net.faces.length, faces.length);
  const roots = net.net.faces.filter((f) => f.parent === -1);
  assert.equal(roots.length, net.pieces.length, "exactly one root face per piece");
  assert.ok(Array.isArray(net.repairs));
  net.net.faces.forEach((f) => assert.ok(f.piece >= 0 && f.piece < net.pieces.length));
  net.net.faces.forEach((f, i) => {
    assert.equal(f.points.length, 3);
    if (f.parent === -1) return;
    // A face and its parent share a mesh edge, with the same 2D position in both.
    const shared = faces[i].filter((v) => faces[f.parent].includes(v));
    assert.equal(shared.length, 2, `face ${i} shares an edge with its parent`);
    for (const v of shared) {
      const a = f.points[faces[i].indexOf(v)];
      const b = net.net.faces[f.parent].points[faces[f.parent].indexOf(v)];
      assert.ok(Math.hypot(a[0] - b[0], a[1] - b[1]) < 1e-6 * (1 + Math.hypot(a[0], a[1])));
    }
  });
}

test("raw OBJ upload: SSE progress to the end, then every result file", async () => {
  const job = await client.submit(sample("sample.obj"), {
    filename: "sample.obj",
    options: { strategy: "TU", seed: 3, paper: "A4", size_mm: 120 },
  });
  assert.match(job.id, /^[0-9a-f]{32}$/);
  assert.equal(job.options.strategy, "TU");
  const seen = [];
  for await (const update of client.events(job.id)) seen.push(update);
  assert.ok(seen.length >= 1);
  const last = seen.at(-1);
  assert.ok(isFinal(last.status), `last event is final, got ${last.status}`);
  assert.ok(["succeeded", "approximated"].includes(last.status), JSON.stringify(last.error));
  assert.equal(last.id, job.id);
  assert.ok(seen.slice(0, -1).every((j) => !isFinal(j.status)), "only the last event is final");
  // One fraction over every phase: never back, 1 only at the end.
  const fractions = seen.map(progressFraction);
  assert.ok(fractions.every((f, i) => f >= 0 && f <= 1 && (i === 0 || f >= fractions[i - 1])), JSON.stringify(fractions));
  assert.ok(fractions.slice(0, -1).every((f) => f < 1), JSON.stringify(fractions));
  assert.equal(last.progress.fraction, 1);

  const net = await client.netJson(job.id);
  checkNet(net);
  assert.equal(net.level.kind, net.result);
  assert.equal(net.level.faces, net.mesh.faces.length);
  const svg = await client.netSvg(job.id);
  assert.match(svg, /<svg[\s>]/);
  assert.match(svg, /<path|<polygon|<line/);
  // Each printed page on its own; the net's placements name them from 0.
  const pages = net.print.pages;
  assert.ok(pages >= 1);
  assert.equal(last.links.pages.length, pages);
  const page = await client.page(job.id, pages);
  assert.ok(page.includes(`page ${pages} of ${pages}`));
  net.print.placements.forEach((p) => assert.ok(p.page >= 0 && p.page < pages));
  await assert.rejects(client.page(job.id, pages + 1), (e) => e.code === "not_found" && e.status === 404);
  // A page as a file to save, under the name the server gives it (no title: page-k.svg).
  const pageFile = await client.result(job.id, `pages/${pages}`);
  assert.equal(await pageFile.text(), page);
  assert.equal(fileNameOf(pageFile), `page-${pages}.svg`);
  assert.equal(fileNameOf(await client.result(job.id, "net.pdf")), "net.pdf");
  await assert.rejects(client.result(job.id, "pages/0"), TypeError);
  await assert.rejects(client.result(job.id, "../net.pdf"), TypeError);
  const pdf = await client.netPdf(job.id);
  assert.equal(new TextDecoder().decode(pdf.slice(0, 5)), "%PDF-");
  const glb = await client.meshGlb(job.id);
  assert.equal(new TextDecoder().decode(glb.slice(0, 4)), "glTF");
});

test("GLB upload followed by polling", async () => {
  const job = await client.submit(sample("Box_Draco.glb"), {
    filename: "Box_Draco.glb",
    options: { strategy: "TU", paper: "Letter", tabs: false, title: "Ente f\u00fcr L\u00fcneburg" },
  });
  const progress = [];
  const done = await client.poll(job.id, { interval: 100, timeout: 60000, onProgress: (j) => progress.push(j) });
  assert.equal(done.status, "succeeded", JSON.stringify(done.error));
  assert.equal(done.options.paper, "Letter");
  assert.equal(done.options.tabs, "none"); // false means none; the job shows the mode
  assert.ok(progress.length >= 1);
  assert.equal(done.input.format, "glb");
  checkNet(await client.netJson(job.id));
  // Saved under the kit's title, letters outside ASCII and all (RFC 6266's filename*).
  assert.equal(fileNameOf(await client.result(job.id, "net.pdf")), "Ente f\u00fcr L\u00fcneburg.pdf");
  assert.equal(fileNameOf(await client.result(job.id, "pages/1")), "Ente f\u00fcr L\u00fcneburg - page 1.svg");
});

/** Splits a GLB into a .gltf JSON naming an external buffer file, and that file's bytes. */
function splitGlb(glb) {
  const view = new DataView(glb.buffer, glb.byteOffset, glb.byteLength);
  assert.equal(view.getUint32(0, true), 0x46546c67);
  const jsonLength = view.getUint32(12, true);
  const gltf = JSON.parse(new TextDecoder().decode(glb.subarray(20, 20 + jsonLength)));
  const binStart = 20 + jsonLength;
  // The BIN chunk is padded to 4 bytes; the buffer file has exactly the bytes the glTF declares.
  assert.ok(view.getUint32(binStart, true) >= gltf.buffers[0].byteLength);
  const bin = glb.subarray(binStart + 8, binStart + 8 + gltf.buffers[0].byteLength);
  gltf.buffers[0].uri = "duck-data.bin";
  return { gltf: JSON.stringify(gltf), bin };
}

test("multipart .gltf with its external buffer file", async () => {
  const { gltf, bin } = splitGlb(sample("Duck.glb"));
  const job = await client.submit(gltf, {
    filename: "duck.gltf",
    buffers: { "duck-data.bin": bin },
    options: { strategy: "TU", seed: 5 },
  });
  const done = await client.wait(job.id);
  assert.ok(["succeeded", "approximated"].includes(done.status), JSON.stringify(done.error));
  assert.equal(done.input.format, "gltf");
  assert.equal(done.options.seed, 5);
  const net = await client.netJson(job.id);
  checkNet(net);
  assert.equal(net.input.faces, done.progress.input_faces);
});

test("multipart: the repository's Box.gltf with Box0.bin", async () => {
  const job = await client.submit(sample("gltf_external/Box.gltf"), {
    filename: "Box.gltf",
    buffers: [{ name: "Box0.bin", data: sample("gltf_external/Box0.bin") }],
    options: { strategy: "QQ", seed: 2 },
  });
  const done = await client.wait(job.id);
  assert.ok(["succeeded", "approximated"].includes(done.status), JSON.stringify(done.error));
  checkNet(await client.netJson(job.id));
});

test("a .gltf whose buffer file is missing fails with a problem code", async () => {
  const { gltf } = splitGlb(sample("Duck.glb"));
  let code;
  try {
    const job = await client.submit(gltf, { filename: "duck.gltf", multipart: true, options: { strategy: "TU" } });
    const done = await client.wait(job.id);
    assert.equal(done.status, "failed");
    code = done.error.code;
    await assert.rejects(client.netJson(job.id), (e) => e instanceof PapernetError && e.code === code);
  } catch (e) {
    if (!(e instanceof PapernetError)) throw e;
    code = e.code;
  }
  assert.equal(code, "unreadable_mesh");
});

test("typed errors carry the server's problem code and status", async () => {
  await assert.rejects(
    client.submit(sample("sample.obj"), { filename: "sample.obj", options: { color: "red" } }),
    (e) => e instanceof PapernetError && e.code === "unknown_option" && e.status === 400 && e.problem.option === "color",
  );
  await assert.rejects(
    client.submit(sample("sample.obj"), { filename: "sample.obj", options: { strategy: "XYZ" } }),
    (e) => e instanceof PapernetError && e.code === "invalid_option_value" && e.status === 400,
  );
  await assert.rejects(
    client.submit(sample("sample.obj"), { filename: "sample.obj", options: { size_mm: 10, scale: 2 } }),
    (e) => e instanceof PapernetError && e.code === "conflicting_options",
  );
  await assert.rejects(
    client.submit(new Uint8Array([1, 2, 3, 4, 5, 6, 7, 8])),
    (e) => e instanceof PapernetError && e.code === "unsupported_format" && e.status === 415,
  );
  await assert.rejects(
    client.job("0123456789abcdef0123456789abcdef"),
    (e) => e instanceof PapernetError && e.code === "job_not_found" && e.status === 404,
  );
  const down = new PapernetClient("http://127.0.0.1:1");
  await assert.rejects(down.job("x"), (e) => e instanceof PapernetError && e.code === "network_error");
});

test("a mesh with a non-manifold edge is repaired into pieces, and refused under strict", async () => {
  // Three triangles on one edge: not manifold. Repair cuts the edge; strict refuses it as before.
  const obj = "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 -1 0\nv 0 0 1\nf 1 2 3\nf 2 1 4\nf 1 2 5\n";
  const repaired = await client.wait((await client.submit(obj, { filename: "fan.obj", options: { strategy: "TU" } })).id);
  assert.equal(repaired.status, "succeeded", JSON.stringify(repaired));
  assert.ok(repaired.result.pieces.length >= 2, JSON.stringify(repaired.result));
  assert.ok(
    repaired.result.repairs.some((r) => r.code === "cut_non_manifold_edges" && r.count === 1),
    JSON.stringify(repaired.result.repairs),
  );
  const job = await client.submit(obj, { filename: "fan.obj", options: { strategy: "TU", strict: true } });
  const done = await client.wait(job.id);
  assert.equal(done.status, "failed");
  assert.equal(done.error.code, "invalid_mesh");
  await assert.rejects(client.netSvg(job.id), (e) => e.code === "invalid_mesh" && e.status === 422);
});

test("cancel a queued job; cancelling a finished one is job_finished (409)", async () => {
  // The single worker is busy with a long job, so the second one waits in the queue.
  const busy = await client.submit(sample("Duck.glb"), {
    filename: "busy.glb",
    options: { strategy: "TU", seed: 11, time_limit: 30, detail: "full" },
  });
  const queued = await client.submit(sample("sample.obj"), { filename: "q.obj", options: { strategy: "TU", seed: 12 } });
  const cancelled = await client.cancel(queued.id);
  assert.ok(cancelled.status === "cancelled" || cancelled.cancel_requested, JSON.stringify(cancelled));
  const final = await client.wait(queued.id);
  assert.equal(final.status, "cancelled");
  await assert.rejects(client.netJson(queued.id), (e) => e.code === "job_cancelled");
  // The busy job may have finished by now (then cancelling it is refused) or stops soon.
  await client.cancel(busy.id).catch((e) => assert.equal(e.code, "job_finished"));
  assert.ok(["cancelled", "succeeded", "approximated"].includes((await client.wait(busy.id)).status));
  // A job that succeeded cannot be cancelled.
  const small = await client.submit(sample("sample.obj"), {
    filename: "s.obj",
    options: { strategy: "TU", seed: 13, detail: "full" },
  });
  assert.equal((await client.wait(small.id)).status, "succeeded");
  await assert.rejects(client.cancel(small.id), (e) => e instanceof PapernetError && e.code === "job_finished" && e.status === 409);
});

test("breaking out of the event iterator closes the stream", async () => {
  const job = await client.submit(sample("thingi10k_65004.stl"), { filename: "t.stl", options: { strategy: "TU", seed: 21 } });
  for await (const update of client.events(job.id)) {
    assert.equal(update.id, job.id);
    break;
  }
  const done = await client.wait(job.id);
  assert.ok(isFinal(done.status));
  const list = await client.jobs({ limit: 100 });
  assert.ok(list.jobs.some((j) => j.id === job.id));
});

function streamOf(chunks) {
  const enc = new TextEncoder();
  return new ReadableStream({
    start(c) {
      for (const ch of chunks) c.enqueue(typeof ch === "string" ? enc.encode(ch) : ch);
      c.close();
    },
  });
}

test("parseSse: chunk boundaries, CRLF, comments, multi-line data, split UTF-8", async () => {
  const euro = new TextEncoder().encode("data: €\n\n");
  const events = [];
  for await (const e of parseSse(
    streamOf([": hello\r\n", "id: 1\r", "\nevent: progress\r\nda", "ta: {\"a\":\n", "data: 1}\n\n", "event: done\ndata:x\n\n", euro.slice(0, 7), euro.slice(7), "data: unterminated"]),
  )) {
    events.push(e);
  }
  assert.deepEqual(events, [
    { event: "progress", data: '{"a":\n1}', id: "1" },
    { event: "done", data: "x", id: "1" },
    { event: "message", data: "€", id: "1" },
  ]);
});

test("parseLevel reads X-Papernet-Level", () => {
  assert.deepEqual(parseLevel("intermediate; faces=40; input-faces=400"), { kind: "intermediate", faces: 40, inputFaces: 400 });
  assert.equal(parseLevel(null), null);
});

test("multipart bodies are encoded in full: Content-Length, closing boundary with CRLF", async () => {
  let sent;
  const fake = new PapernetClient("http://papernet.invalid", {
    fetch: async (url, init) => {
      sent = { url, init };
      return new Response(JSON.stringify({ id: "x" }), { status: 202, headers: { "Content-Type": "application/json" } });
    },
  });
  await fake.submit('{"asset":{}}', { filename: 'a"b.gltf', buffers: { "b.bin": new Uint8Array([0, 1, 2]) }, options: { seed: 4 } });
  const boundary = /boundary=(.+)$/.exec(sent.init.headers["Content-Type"])[1];
  const text = await new Response(sent.init.body).text();
  assert.ok(sent.init.body instanceof Blob, "a Blob body, sent with a Content-Length");
  assert.ok(text.endsWith(`\r\n--${boundary}--\r\n`));
  assert.match(text, /name="mesh"; filename="a%22b.gltf"\r\nContent-Type: model\/gltf\+json\r\n\r\n\{"asset":\{\}\}\r\n/);
  assert.match(text, /name="buffers"; filename="b.bin"\r\nContent-Type: application\/octet-stream\r\n\r\n\0\x01\x02\r\n/);
  assert.match(text, /name="options"; filename="options.json"\r\nContent-Type: application\/json\r\n\r\n\{"seed":4\}\r\n/);
  assert.equal(sent.url, "http://papernet.invalid/v1/jobs");
});

test("apiKey: a server with --api-keys answers the key's tenant; no key is missing_api_key", async (t) => {
  const { mkdtempSync, rmSync, writeFileSync } = await import("node:fs");
  const { createHash } = await import("node:crypto");
  const { tmpdir } = await import("node:os");
  const { join } = await import("node:path");
  if (process.env.PAPERNET_URL) return t.skip("needs a server of its own (PAPERNET_URL is set)");
  const dir = mkdtempSync(join(tmpdir(), "papernet-keys-"));
  const keys = join(dir, "keys.txt");
  const hash = (key) => createHash("sha256").update(key).digest("hex");
  writeFileSync(keys, `shop-a ${hash("key-a")}\nshop-b ${hash("key-b")}\n`);
  const keyed = await startServer(["--workers", "1", "--access-log", "false", "--api-keys", keys]);
  try {
    const a = new PapernetClient(keyed.url, { apiKey: "key-a" });
    const b = new PapernetClient(keyed.url, { apiKey: "key-b" });
    await assert.rejects(new PapernetClient(keyed.url).jobs(), (e) => e.code === "missing_api_key" && e.status === 401);
    await assert.rejects(new PapernetClient(keyed.url, { apiKey: "nope" }).jobs(), (e) => e.code === "invalid_api_key");
    const job = await a.submit(sample("sample.obj"), { filename: "a.obj", options: { strategy: "TU", detail: "full" } });
    assert.equal((await a.wait(job.id)).status, "succeeded");
    checkNet(await a.netJson(job.id));
    await assert.rejects(b.job(job.id), (e) => e.code === "job_not_found" && e.status === 404);
    assert.deepEqual((await b.jobs()).jobs, []);
    assert.equal((await a.jobs()).jobs[0].id, job.id);
    // A retried submit with its Idempotency-Key resolves to the first job.
    const once = await a.submit(sample("sample.obj"), { filename: "o.obj", options: { seed: 9 }, idempotencyKey: "order-9" });
    const again = await a.submit(sample("sample.obj"), { filename: "o.obj", options: { seed: 9 }, idempotencyKey: "order-9" });
    assert.equal(again.id, once.id);
    await assert.rejects(
      a.submit(sample("sample.obj"), { filename: "o.obj", options: { seed: 10 }, idempotencyKey: "order-9" }),
      (e) => e.code === "idempotency_key_reused" && e.status === 422,
    );
  } finally {
    await keyed.stop();
    rmSync(dir, { recursive: true, force: true });
  }
});

test("callbackUrl: a signed POST of the final status reaches a receiver the server allows", async (t) => {
  const { createServer } = await import("node:http");
  const { createHmac, timingSafeEqual } = await import("node:crypto");
  if (process.env.PAPERNET_URL) return t.skip("needs a server of its own (PAPERNET_URL is set)");
  const secret = "whsec-js-test";
  let got;
  const arrived = new Promise((resolveCall) => {
    got = resolveCall;
  });
  const receiver = createServer((req, res) => {
    let body = "";
    req.setEncoding("utf8");
    req.on("data", (c) => (body += c));
    req.on("end", () => {
      res.end("ok");
      got({ signature: req.headers["x-papernet-signature"], body });
    });
  });
  await new Promise((r) => receiver.listen(0, "127.0.0.1", r));
  const hooked = await startServer([
    "--workers", "1", "--access-log", "false", "--webhook-hosts", "127.0.0.1", "--webhook-secret", secret,
  ]);
  try {
    const c = new PapernetClient(hooked.url);
    const hook = `http://127.0.0.1:${receiver.address().port}/hook`;
    const job = await c.submit(sample("sample.obj"), { filename: "w.obj", options: { strategy: "TU" }, callbackUrl: hook });
    assert.equal(job.options.callback_url, hook);
    const call = await arrived;
    // The documented check: HMAC-SHA256 of "<t>.<body>" under the secret, in hex.
    const [, t, v1] = /^t=(\d+),v1=([0-9a-f]{64})$/.exec(call.signature);
    const mac = createHmac("sha256", secret).update(`${t}.${call.body}`).digest("hex");
    assert.ok(timingSafeEqual(Buffer.from(mac), Buffer.from(v1)));
    assert.ok(Math.abs(Date.now() / 1000 - Number(t)) < 300);
    assert.equal(JSON.parse(call.body).id, job.id);
    let status = await c.job(job.id);
    for (let i = 0; i < 100 && status.callback?.state === "pending"; ++i) {
      await new Promise((r) => setTimeout(r, 50));
      status = await c.job(job.id);
    }
    assert.equal(status.callback.state, "delivered");
    assert.equal(status.callback.attempts[0].status, 200);
    // A loopback host the server does not list is refused, naming the option.
    await assert.rejects(
      c.submit(sample("sample.obj"), { filename: "w.obj", callbackUrl: "http://localhost:1/hook" }),
      (e) => e.code === "callback_url_refused" && e.status === 422 && e.problem.option === "callback_url",
    );
  } finally {
    await hooked.stop();
    receiver.close();
  }
});
