// papernet client: a dependency-free ES module for browsers and Node >= 18 (global fetch).
//
//   import { PapernetClient } from "./papernet.js";
//   const client = new PapernetClient("http://127.0.0.1:8080");
//   const job = await client.submit(bytes, { filename: "duck.glb", options: { strategy: "QQ" } });
//   for await (const update of client.events(job.id)) console.log(update.progress);
//   const net = await client.netJson(job.id);
//
// Every failing answer of the server (application/problem+json) becomes a PapernetError whose
// `code` is the server's stable problem code (e.g. "invalid_mesh", "queue_full").

/** Job states after which nothing changes any more. */
export const FINAL_STATUSES = Object.freeze(["succeeded", "approximated", "failed", "cancelled"]);

/** The result files a job offers, by the name the server uses in its links. */
export const RESULT_FILES = Object.freeze(["net.json", "net.svg", "net.pdf", "mesh.glb"]);

const FORMAT_TYPES = {
  glb: "model/gltf-binary",
  gltf: "model/gltf+json",
  drc: "model/x-draco",
  obj: "model/obj",
  off: "model/x-off",
  ply: "model/x-ply",
  stl: "model/stl",
};

/** True when `status` is final (the job will not change any more). */
export function isFinal(status) {
  return FINAL_STATUSES.includes(status);
}

/**
 * The share of a job done, 0 to 1, every phase counted (load, collapse, unfold, uncollapse,
 * tabs, layout, write): the server's `progress.fraction`, which never goes back while the job
 * runs; 1 once the job is final.
 */
export function progressFraction(job) {
  if (isFinal(job.status)) return 1;
  return job.progress?.fraction ?? 0;
}

/**
 * The name the server gives a result file (its Content-Disposition: "Kitchen Duck.pdf" for a kit
 * titled so, "page-2.svg" for a page), for saving it; null when the response names none.
 */
export function fileNameOf(response) {
  const disposition = response.headers.get("Content-Disposition") ?? "";
  const utf8 = /filename\*=UTF-8''([^;\s]+)/i.exec(disposition);
  if (utf8) {
    try {
      return decodeURIComponent(utf8[1]);
    } catch {
      // a malformed escape: the plain name below
    }
  }
  const plain = /filename="([^"]*)"/i.exec(disposition);
  return plain ? plain[1] : null;
}

/** The mesh format a file name implies ("duck.GLB" -> "glb"), or undefined. */
export function formatOfFileName(name) {
  const m = /\.([A-Za-z0-9]+)$/.exec(name ?? "");
  const ext = m ? m[1].toLowerCase() : "";
  return ext in FORMAT_TYPES ? ext : undefined;
}

/**
 * An error answer of the server (problem details, RFC 9457), or a failure to reach it
 * (code "network_error"), or an answer that is not what the API promises ("bad_response").
 */
export class PapernetError extends Error {
  constructor(problem, { status = 0, retryAfter = null, cause } = {}) {
    super(problem.detail || problem.title || problem.code, cause ? { cause } : undefined);
    this.name = "PapernetError";
    /** The server's stable problem code, e.g. "invalid_mesh". */
    this.code = problem.code;
    /** HTTP status (0 when the server was not reached). */
    this.status = problem.status ?? status;
    this.title = problem.title;
    this.detail = problem.detail;
    /** Seconds to wait before retrying (Retry-After), or null. */
    this.retryAfter = retryAfter;
    /** The whole problem document. */
    this.problem = problem;
  }
}

/** Turns a non-2xx response into a PapernetError (reads the body). */
async function errorFromResponse(res) {
  const retry = res.headers.get("Retry-After");
  const retryAfter = retry !== null && retry !== "" && !Number.isNaN(Number(retry)) ? Number(retry) : null;
  let problem = null;
  const text = await res.text().catch(() => "");
  try {
    const doc = JSON.parse(text);
    if (doc && typeof doc === "object" && typeof doc.code === "string") problem = doc;
  } catch {
    // not JSON: described below
  }
  if (!problem) {
    problem = {
      code: "bad_response",
      status: res.status,
      title: `HTTP ${res.status}`,
      detail: `HTTP ${res.status} without a problem document: ${text.slice(0, 200)}`,
    };
  }
  return new PapernetError(problem, { status: res.status, retryAfter });
}

function networkError(err, url) {
  return new PapernetError(
    { code: "network_error", status: 0, title: "network error", detail: `${url}: ${err?.message ?? err}` },
    { cause: err },
  );
}

function abortError(signal) {
  return signal?.reason ?? new DOMException("The operation was aborted.", "AbortError");
}

function sleep(ms, signal) {
  return new Promise((resolve, reject) => {
    if (signal?.aborted) return reject(abortError(signal));
    const timer = setTimeout(() => {
      signal?.removeEventListener("abort", onAbort);
      resolve();
    }, ms);
    const onAbort = () => {
      clearTimeout(timer);
      reject(abortError(signal));
    };
    signal?.addEventListener("abort", onAbort, { once: true });
  });
}

/** Query string of the options (booleans as true/false, undefined/null left out). */
function optionsQuery(options) {
  const q = new URLSearchParams();
  for (const [k, v] of Object.entries(options ?? {})) {
    if (v === undefined || v === null) continue;
    q.set(k, String(v));
  }
  return q;
}

/**
 * Parses a Server-Sent Events stream (a ReadableStream of bytes, e.g. `response.body`) into
 * events `{event, data, id}` as the HTML standard describes: fields per line, events end at a
 * blank line, `data` lines joined by "\n", comments (":") ignored, CR/LF/CRLF line ends.
 */
export async function* parseSse(stream) {
  const reader = stream.getReader();
  const decoder = new TextDecoder("utf-8");
  let buffer = "";
  let event = "";
  let data = [];
  let id = null;
  let sawField = false;
  const dispatch = function* () {
    if (sawField && data.length > 0) yield { event: event || "message", data: data.join("\n"), id };
    event = "";
    data = [];
    sawField = false;
  };
  const line = function* (text) {
    if (text === "") {
      yield* dispatch();
      return;
    }
    if (text.startsWith(":")) return;
    const colon = text.indexOf(":");
    const field = colon < 0 ? text : text.slice(0, colon);
    let value = colon < 0 ? "" : text.slice(colon + 1);
    if (value.startsWith(" ")) value = value.slice(1);
    sawField = true;
    if (field === "event") event = value;
    else if (field === "data") data.push(value);
    else if (field === "id" && !value.includes("\0")) id = value;
  };
  try {
    for (;;) {
      const { value, done } = await reader.read();
      buffer += done ? decoder.decode() : decoder.decode(value, { stream: true });
      // Split off complete lines; a trailing "\r" may still be half of "\r\n".
      for (;;) {
        const m = /\r\n|\r|\n/.exec(buffer);
        if (!m || (m[0] === "\r" && m.index === buffer.length - 1 && !done)) break;
        const text = buffer.slice(0, m.index);
        buffer = buffer.slice(m.index + m[0].length);
        yield* line(text);
      }
      if (done) break;
    }
    // A stream that ends without a blank line does not dispatch its last event (as browsers do).
  } finally {
    reader.releaseLock?.();
  }
}

export class PapernetClient {
  /**
   * @param baseUrl the server, e.g. "http://127.0.0.1:8080" ("" in a page the server serves)
   * @param options.fetch a fetch implementation (default: the global one)
   * @param options.apiKey the API key of a server started with --api-keys (sent as
   *   Authorization: Bearer), or undefined for an open server
   */
  constructor(baseUrl = "", { fetch: fetchImpl, apiKey } = {}) {
    this.baseUrl = String(baseUrl).replace(/\/+$/, "");
    this._fetch = fetchImpl ?? globalThis.fetch.bind(globalThis);
    this.apiKey = apiKey;
  }

  /** Absolute URL of a server path ("/v1/jobs"). */
  url(path) {
    return this.baseUrl + path;
  }

  async _request(path, init = {}) {
    const url = this.url(path);
    if (this.apiKey) init = { ...init, headers: { ...init.headers, Authorization: `Bearer ${this.apiKey}` } };
    let res;
    try {
      res = await this._fetch(url, init);
    } catch (err) {
      if (err?.name === "AbortError" || init.signal?.aborted) throw err;
      throw networkError(err, url);
    }
    if (!res.ok) throw await errorFromResponse(res);
    return res;
  }

  async _json(path, init) {
    const res = await this._request(path, init);
    return res.json();
  }

  /**
   * Submits a mesh. `mesh` is a Blob/File, ArrayBuffer, typed array or string.
   * - Without `buffers`: the raw body, options as query parameters; the format comes from
   *   `format`, else the file name's extension, else the server sniffs it.
   * - With `buffers` (the external files of a .gltf, `{name: data}` or `[{name, data}]`):
   *   multipart/form-data with `mesh`, one `buffers` part per file and an `options` JSON part.
   * `multipart: true` forces multipart. `idempotencyKey` (e.g. crypto.randomUUID(), kept for
   * the retries of one submission): a retry resolves to the first job instead of a new one.
   * `callbackUrl` (the option callback_url): the server POSTs the job's final status there,
   * signed, when the job ends (README "Webhooks"); the job's `callback` shows the attempts.
   * Resolves to the job (202, or 200 for a retry).
   */
  async submit(
    mesh,
    { options = {}, filename, format, buffers, multipart, idempotencyKey, callbackUrl, signal } = {},
  ) {
    if (callbackUrl !== undefined && callbackUrl !== null) options = { ...options, callback_url: String(callbackUrl) };
    const idem = idempotencyKey ? { "Idempotency-Key": String(idempotencyKey) } : {};
    filename ??= typeof mesh?.name === "string" ? mesh.name : undefined;
    format ??= formatOfFileName(filename);
    const bufferList = Array.isArray(buffers)
      ? buffers
      : Object.entries(buffers ?? {}).map(([name, data]) => ({ name, data }));
    if (bufferList.length > 0 || multipart) {
      const type = (format && FORMAT_TYPES[format]) || "application/octet-stream";
      const parts = [
        { name: "mesh", filename: filename ?? (format ? `mesh.${format}` : "mesh"), type, data: mesh },
        ...bufferList.map(({ name, data }) => ({ name: "buffers", filename: name, type: "application/octet-stream", data })),
        { name: "options", filename: "options.json", type: "application/json", data: JSON.stringify(options) },
      ];
      const { headers, body } = encodeMultipart(parts);
      return this._json("/v1/jobs", { method: "POST", headers: { ...headers, ...idem }, body, signal });
    }
    const q = optionsQuery(options);
    const query = q.toString();
    const headers = { "Content-Type": (format && FORMAT_TYPES[format]) || "application/octet-stream", ...idem };
    return this._json(`/v1/jobs${query ? `?${query}` : ""}`, {
      method: "POST",
      headers,
      body: toBody(mesh),
      signal,
    });
  }

  /** The job's status and progress. */
  job(id, { signal } = {}) {
    return this._json(`/v1/jobs/${encodeURIComponent(id)}`, { signal });
  }

  /** Recent jobs, newest first: `{jobs, next}`. */
  jobs({ limit, cursor, signal } = {}) {
    const q = optionsQuery({ limit, cursor }).toString();
    return this._json(`/v1/jobs${q ? `?${q}` : ""}`, { signal });
  }

  /** Cancels a job; resolves to the job (cancelled or stopping). */
  cancel(id, { signal } = {}) {
    return this._json(`/v1/jobs/${encodeURIComponent(id)}`, { method: "DELETE", signal });
  }

  /**
   * Live progress as an async iterator of job documents: one per change (event "progress"),
   * the last one final (event "done"), then the iteration ends. Works in Node without
   * EventSource (parses the stream of fetch). Breaking out of the loop closes the stream.
   */
  async *events(id, { signal } = {}) {
    const controller = new AbortController();
    const onAbort = () => controller.abort(abortError(signal));
    if (signal?.aborted) throw abortError(signal);
    signal?.addEventListener("abort", onAbort, { once: true });
    try {
      const res = await this._request(`/v1/jobs/${encodeURIComponent(id)}/events`, {
        headers: { Accept: "text/event-stream" },
        signal: controller.signal,
      });
      if (!res.body) throw new PapernetError({ code: "bad_response", detail: "event stream has no body" });
      for await (const ev of parseSse(res.body)) {
        if (ev.event !== "progress" && ev.event !== "done") continue;
        let job;
        try {
          job = JSON.parse(ev.data);
        } catch (err) {
          throw new PapernetError(
            { code: "bad_response", detail: `event data is not JSON: ${ev.data.slice(0, 100)}` },
            { cause: err },
          );
        }
        if (job === null) throw new PapernetError({ code: "job_not_found", status: 404, detail: `no job ${id}` });
        yield job;
        if (ev.event === "done") return;
      }
    } finally {
      signal?.removeEventListener("abort", onAbort);
      controller.abort();
    }
  }

  /**
   * Polls the job every `interval` ms (honouring Retry-After) until it is final; calls
   * `onProgress(job)` on every answer. Resolves to the final job.
   */
  async poll(id, { interval = 500, timeout = Infinity, onProgress, signal } = {}) {
    const deadline = Date.now() + timeout;
    for (;;) {
      const job = await this.job(id, { signal });
      onProgress?.(job);
      if (isFinal(job.status)) return job;
      if (Date.now() >= deadline) {
        throw new PapernetError({ code: "timeout", detail: `job ${id} still ${job.status} after ${timeout} ms` });
      }
      await sleep(Math.min(interval, Math.max(0, deadline - Date.now())), signal);
    }
  }

  /**
   * Waits until the job is final, following the event stream and falling back to polling
   * when the server refuses a stream (too_many_streams) or it breaks. Resolves to the final job.
   */
  async wait(id, { onProgress, signal, interval = 500 } = {}) {
    try {
      let last = null;
      for await (const job of this.events(id, { signal })) {
        last = job;
        onProgress?.(job);
      }
      if (last && isFinal(last.status)) return last;
    } catch (err) {
      if (signal?.aborted) throw err;
      if (!(err instanceof PapernetError) || err.code === "job_not_found") throw err;
    }
    return this.poll(id, { onProgress, signal, interval });
  }

  /**
   * A result file as a Response (status checked): `name` is one of RESULT_FILES, or `pages/k`
   * (a printed page, k from 1) or `textures/k` (k from 0). fileNameOf(response) is the name
   * the server gives it.
   */
  async result(id, name, { signal } = {}) {
    if (!RESULT_FILES.includes(name) && !/^(pages\/[1-9][0-9]*|textures\/(0|[1-9][0-9]*))$/.test(name)) {
      throw new TypeError(`unknown result file ${name}`);
    }
    return this._request(`/v1/jobs/${encodeURIComponent(id)}/${name}`, { signal });
  }

  /** The net (papernet.net/2) with `level` parsed from X-Papernet-Level. */
  async netJson(id, opts) {
    const res = await this.result(id, "net.json", opts);
    const net = await res.json();
    Object.defineProperty(net, "level", { value: parseLevel(res.headers.get("X-Papernet-Level")), enumerable: false });
    return net;
  }

  /** The print-ready SVG as text. */
  async netSvg(id, opts) {
    return (await this.result(id, "net.svg", opts)).text();
  }

  /** The print-ready PDF bytes. */
  async netPdf(id, opts) {
    return new Uint8Array(await (await this.result(id, "net.pdf", opts)).arrayBuffer());
  }

  /** The mesh the net folds into, as GLB bytes. */
  async meshGlb(id, opts) {
    return new Uint8Array(await (await this.result(id, "mesh.glb", opts)).arrayBuffer());
  }

  /** Texture k of the net JSON's `textures` (its image bytes and content type). */
  async texture(id, k, { signal } = {}) {
    if (!Number.isInteger(k) || k < 0) throw new TypeError(`bad texture index ${k}`);
    const res = await this._request(`/v1/jobs/${encodeURIComponent(id)}/textures/${k}`, { signal });
    return { contentType: res.headers.get("Content-Type"), bytes: new Uint8Array(await res.arrayBuffer()) };
  }

  /** Printed page k (from 1, as the page says "page k of n") as SVG text: the net JSON's
   *  `print.placements[i].page` p is page p + 1. */
  async page(id, k, { signal } = {}) {
    if (!Number.isInteger(k) || k < 1) throw new TypeError(`bad page number ${k}`);
    return (await this._request(`/v1/jobs/${encodeURIComponent(id)}/pages/${k}`, { signal })).text();
  }

    /** GET /healthz and /readyz: true when the server answers 200. */
  async ready({ signal } = {}) {
    try {
      await this._request("/readyz", { signal });
      return true;
    } catch (err) {
      if (err instanceof PapernetError) return false;
      throw err;
    }
  }
}

/** Parses "complete; faces=10; input-faces=20" into {kind, faces, inputFaces}. */
export function parseLevel(header) {
  if (!header) return null;
  const [kind, ...rest] = header.split(";").map((s) => s.trim());
  const out = { kind, faces: null, inputFaces: null };
  for (const kv of rest) {
    const [k, v] = kv.split("=");
    if (k === "faces") out.faces = Number(v);
    else if (k === "input-faces") out.inputFaces = Number(v);
  }
  return out;
}

/**
 * multipart/form-data of `parts` ({name, filename, type, data}) as one Blob, encoded here rather
 * than by FormData: Node 18's fetch leaves out the CRLF after the closing boundary, which the
 * server's multipart parser (cpp-httplib 0.11) refuses, and a Blob body gets a Content-Length.
 */
function encodeMultipart(parts) {
  // (Node 18 has no global crypto; a boundary needs to be unlikely in the data, not secret.)
  const random = Array.from({ length: 4 }, () => Math.floor(Math.random() * 2 ** 32).toString(16).padStart(8, "0"));
  const boundary = `----papernet${random.join("")}`;
  // As browsers do: quotes and line breaks in names are percent-encoded.
  const quote = (v) => String(v).replace(/"/g, "%22").replace(/\r/g, "%0D").replace(/\n/g, "%0A");
  const chunks = [];
  for (const p of parts) {
    chunks.push(
      `--${boundary}\r\nContent-Disposition: form-data; name="${quote(p.name)}"; filename="${quote(p.filename)}"\r\n` +
        `Content-Type: ${p.type}\r\n\r\n`,
      toBody(p.data),
      "\r\n",
    );
  }
  chunks.push(`--${boundary}--\r\n`);
  return {
    headers: { "Content-Type": `multipart/form-data; boundary=${boundary}` },
    body: new Blob(chunks),
  };
}

function toBody(data) {
  if (data instanceof ArrayBuffer || ArrayBuffer.isView(data) || typeof data === "string") return data;
  if (typeof Blob !== "undefined" && data instanceof Blob) return data;
  throw new TypeError("mesh must be a Blob, ArrayBuffer, typed array or string");
}
