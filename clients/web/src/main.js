// The demo page: upload a mesh, follow the job, show the model folding from its net.
import * as THREE from "three";
import { OrbitControls } from "three/examples/jsm/controls/OrbitControls.js";
import { PapernetClient, PapernetError, fileNameOf, isFinal, formatOfFileName, progressFraction } from "../../js/papernet.js";
import { prepareFold, foldPositions } from "./fold.js";
import { sceneFrame, cornerUvs, cornerColors, faceGroups } from "./colour.js";

const $ = (id) => document.getElementById(id);
// The API key of a server started with --api-keys, kept for this tab (sessionStorage): the
// client sends it as Authorization: Bearer on every request, the event stream included (it
// reads the stream with fetch: EventSource cannot send headers).
const keyStore = "papernet.apiKey";
const client = new PapernetClient("", { apiKey: sessionStorage.getItem(keyStore) || undefined });
const ui = {
  drop: $("drop"), file: $("file"), dropText: $("drop-text"), strategy: $("strategy"), size: $("size"),
  paper: $("paper"), title: $("title"), prefer: $("prefer"), detail: $("detail"), components: $("components"), repairs: $("repairs"), timeLimit: $("time-limit"), start: $("start"), cancel: $("cancel"), progress: $("progress"), status: $("status"),
  model: $("model"), net: $("net"), fold: $("fold"), foldValue: $("fold-value"),
  sheet: $("sheet"), keyBox: $("key-box"), key: $("api-key"),
  downloads: { "net.svg": $("dl-svg"), "net.pdf": $("dl-pdf"), "mesh.glb": $("dl-glb"), "net.json": $("dl-json") },
};

let files = [];
let current = null; // {id, abort}
let shownFaces = -1; // face count of the net on screen

// ---- 3D view -------------------------------------------------------------------------------
const renderer = new THREE.WebGLRenderer({ antialias: true, preserveDrawingBuffer: true });
renderer.setPixelRatio(Math.min(window.devicePixelRatio, 2));
ui.model.appendChild(renderer.domElement);
const scene = new THREE.Scene();
scene.background = new THREE.Color(0xfafaf7);
const camera = new THREE.PerspectiveCamera(40, 1, 0.01, 1000);
camera.position.set(0, -3, 2);
let controls = new OrbitControls(camera, renderer.domElement);
const group = new THREE.Group();
scene.add(group);
scene.add(new THREE.HemisphereLight(0xffffff, 0x8890a0, 1.6));
const sun = new THREE.DirectionalLight(0xffffff, 1.4);
sun.position.set(2, -3, 4);
scene.add(sun);
const paper = 0xf2e6c9; // a model without colour is drawn as plain paper
const lineMaterial = new THREE.LineBasicMaterial({ color: 0x6b5b3e });
// Over a coloured model the folds are drawn faintly, so that the colour shows.
const faintLineMaterial = new THREE.LineBasicMaterial({ color: 0x3a3020, transparent: true, opacity: 0.22 });
let folding = null; // {prepared, mesh, lines, positions, linePositions, ready}

// Render on demand (orbiting, folding, resizing), not in a loop: the page stays idle otherwise.
let frameRequested = false;
function requestRender() {
  if (frameRequested) return;
  frameRequested = true;
  requestAnimationFrame(() => {
    frameRequested = false;
    renderer.render(scene, camera);
  });
}
function watchControls() {
  controls.addEventListener("change", requestRender);
}
watchControls();

function resize() {
  const w = ui.model.clientWidth || 400;
  const h = ui.model.clientHeight || 380;
  renderer.setSize(w, h, false);
  camera.aspect = w / h;
  camera.updateProjectionMatrix();
  requestRender();
}
new ResizeObserver(resize).observe(ui.model);
resize();

// ---- colour: the job's textures and the materials of the net's faces ------------------------
// glTF sampler codes to three.js's.
const WRAP = { 33071: THREE.ClampToEdgeWrapping, 33648: THREE.MirroredRepeatWrapping, 10497: THREE.RepeatWrapping };
const FILTER = {
  9728: THREE.NearestFilter, 9729: THREE.LinearFilter,
  9984: THREE.NearestMipmapNearestFilter, 9985: THREE.LinearMipmapNearestFilter,
  9986: THREE.NearestMipmapLinearFilter, 9987: THREE.LinearMipmapLinearFilter,
};
let textures = { job: null, byIndex: new Map() }; // texture k of job `job`: a promise of a THREE.Texture

// Texture k of job `id` (README "The net": GET /v1/jobs/{id}/textures/{k}), fetched through the
// client (so it carries what every other request does) and loaded once per job. glTF's texture
// coordinates have their origin at the image's top left, as the image's rows come: no flipY.
function jobTexture(id, k, info) {
  if (textures.job !== id) {
    for (const t of textures.byIndex.values()) t.then((texture) => texture?.dispose(), () => {});
    textures = { job: id, byIndex: new Map() };
  }
  if (!textures.byIndex.has(k)) {
    const load = (async () => {
      const { bytes, contentType } = await client.texture(id, k);
      const bitmap = await createImageBitmap(new Blob([bytes], { type: contentType ?? info?.mime_type }), {
        premultiplyAlpha: "none",
      });
      const texture = new THREE.Texture(bitmap);
      texture.flipY = false;
      texture.colorSpace = THREE.SRGBColorSpace;
      const sampler = info?.sampler ?? {};
      texture.wrapS = WRAP[sampler.wrap_s] ?? THREE.RepeatWrapping;
      texture.wrapT = WRAP[sampler.wrap_t] ?? THREE.RepeatWrapping;
      texture.magFilter = sampler.mag_filter === 9728 ? THREE.NearestFilter : THREE.LinearFilter;
      texture.minFilter = FILTER[sampler.min_filter] ?? THREE.LinearMipmapLinearFilter;
      texture.anisotropy = renderer.capabilities.getMaxAnisotropy();
      texture.needsUpdate = true;
      texture.userData.dominant = dominantColour(bitmap);
      return texture;
    })();
    textures.byIndex.set(k, load);
  }
  return textures.byIndex.get(k);
}

// An image's dominant colour (linear): the mean of the pixels in the most common of 512 colour
// bins, for faces of a textured material that have no texture coordinates (an approximate
// piece's): the Duck's yellow, where a mean would be darkened by its eyes.
function dominantColour(bitmap) {
  const size = 32;
  const canvas = document.createElement("canvas");
  canvas.width = canvas.height = size;
  const context = canvas.getContext("2d", { willReadFrequently: true });
  context.drawImage(bitmap, 0, 0, size, size);
  const pixels = context.getImageData(0, 0, size, size).data;
  const bins = new Map(); // bin -> [weight, r, g, b]
  const colour = new THREE.Color();
  for (let i = 0; i < pixels.length; i += 4) {
    const a = pixels[i + 3] / 255;
    if (a === 0) continue;
    const bin = ((pixels[i] >> 5) << 6) | ((pixels[i + 1] >> 5) << 3) | (pixels[i + 2] >> 5);
    colour.setRGB(pixels[i] / 255, pixels[i + 1] / 255, pixels[i + 2] / 255, THREE.SRGBColorSpace); // to linear
    const sum = bins.get(bin) ?? [0, 0, 0, 0];
    sum[0] += a;
    sum[1] += a * colour.r;
    sum[2] += a * colour.g;
    sum[3] += a * colour.b;
    bins.set(bin, sum);
  }
  let best = null;
  for (const sum of bins.values()) if (!best || sum[0] > best[0]) best = sum;
  return best ? new THREE.Color(best[1] / best[0], best[2] / best[0], best[3] / best[0]) : new THREE.Color(1, 1, 1);
}

// One material per group of faces (colour.js faceGroups): the material's base colour (linear,
// as glTF's baseColorFactor) times its texture, mapped by the faces' own coordinates, or times
// the texture's dominant colour where the faces have none; times the corners' vertex colours. Faces
// of no material are paper, or white under vertex colours. Resolves `ready` once every texture
// is in (or failed to load).
function faceMaterials(doc, groups, vertexColors, id) {
  const loads = [];
  const materials = groups.map((g) => {
    const info = g.material >= 0 ? doc.materials[g.material] : null;
    const m = new THREE.MeshStandardMaterial({ side: THREE.DoubleSide, flatShading: true, roughness: 0.9, vertexColors });
    if (!info) {
      m.color.set(vertexColors ? 0xffffff : paper); // vertex colours are the colour
      return m;
    }
    const [r, gr, b] = info.base_color ?? [1, 1, 1];
    m.color.setRGB(r, gr, b, THREE.LinearSRGBColorSpace);
    m.name = info.name ?? "";
    if (Number.isInteger(info.texture) && info.texture >= 0 && id) {
      loads.push(
        jobTexture(id, info.texture, doc.textures?.[info.texture]).then((texture) => {
          if (g.textured) m.map = texture;
          else m.color.multiply(texture.userData.dominant);
          m.needsUpdate = true;
          requestRender();
        }),
      );
    }
    return m;
  });
  const ready = Promise.allSettled(loads).then((results) => {
    const failed = results.filter((r) => r.status === "rejected");
    if (failed.length > 0) console.warn(`texture not shown: ${failed[0].reason}`);
    return loads.length - failed.length;
  });
  return { materials, ready };
}

// The net of `doc` (job `id`, its input in `format`: glTF is y up) folded in the 3D view.
function showNet3d(doc, id, format) {
  const prepared = prepareFold(doc, { frame: sceneFrame(format) });
  if (folding) {
    group.remove(folding.mesh, folding.lines);
    folding.mesh.geometry.dispose();
    for (const m of folding.mesh.material) m.dispose();
    folding.lines.geometry.dispose();
  }
  const n = prepared.faces.length;
  const geometry = new THREE.BufferGeometry();
  const positions = new Float32Array(n * 9);
  geometry.setAttribute("position", new THREE.BufferAttribute(positions, 3));
  // Corner k of face i is vertex 3i + k (foldPositions' order); drawn grouped by material.
  geometry.setAttribute("uv", new THREE.BufferAttribute(cornerUvs(doc), 2));
  const colors = cornerColors(doc);
  if (colors) geometry.setAttribute("color", new THREE.BufferAttribute(colors, 3));
  const groups = faceGroups(doc);
  const index = new Uint32Array(n * 3);
  let at = 0;
  groups.forEach((g, m) => {
    geometry.addGroup(at, g.faces.length * 3, m);
    for (const i of g.faces) index.set([3 * i, 3 * i + 1, 3 * i + 2], (at += 3) - 3);
  });
  geometry.setIndex(new THREE.BufferAttribute(index, 1));
  const { materials, ready } = faceMaterials(doc, groups, !!colors, id);
  const coloured = !!colors || groups.some((g) => g.material >= 0);
  const lineGeometry = new THREE.BufferGeometry();
  const linePositions = new Float32Array(n * 18);
  lineGeometry.setAttribute("position", new THREE.BufferAttribute(linePositions, 3));
  folding = {
    prepared,
    doc,
    mesh: new THREE.Mesh(geometry, materials),
    lines: new THREE.LineSegments(lineGeometry, coloured ? faintLineMaterial : lineMaterial),
    positions,
    linePositions,
    ready,
  };
  group.add(folding.mesh, folding.lines);
  // A new model: look at it from the front, a little from above (z is up: the folded model
  // stands as it does in its file, the flat net lies in z = 0).
  camera.up.set(0, 0, 1);
  camera.position.set(0.35, -1.1, 0.9);
  controls.target.set(0, 0, 0);
  controls.dispose();
  controls = new OrbitControls(camera, renderer.domElement);
  watchControls();
  ui.fold.disabled = false;
  applyFold();
}

function applyFold() {
  const t = Number(ui.fold.value);
  ui.foldValue.textContent = t >= 1 ? "folded" : t <= 0 ? "flat net" : `${Math.round(t * 100)} % folded`;
  if (!folding) return;
  const { positions: p, linePositions: l } = folding;
  foldPositions(folding.prepared, t, p);
  for (let i = 0; i < p.length / 9; ++i) {
    for (let k = 0; k < 3; ++k) {
      const a = i * 9 + k * 3;
      const b = i * 9 + ((k + 1) % 3) * 3;
      l.set(p.subarray(a, a + 3), i * 18 + k * 6);
      l.set(p.subarray(b, b + 3), i * 18 + k * 6 + 3);
    }
  }
  folding.mesh.geometry.attributes.position.needsUpdate = true;
  folding.mesh.geometry.computeVertexNormals();
  folding.mesh.geometry.computeBoundingSphere();
  folding.lines.geometry.attributes.position.needsUpdate = true;
  folding.lines.geometry.computeBoundingSphere();
  // Keep what is shown centred and filling the view at every stage of folding; the direction
  // the user orbited to is kept.
  const sphere = folding.mesh.geometry.boundingSphere;
  group.position.copy(sphere.center).negate();
  const radius = sphere.radius || 1;
  const direction = camera.position.clone().sub(controls.target).normalize();
  controls.target.set(0, 0, 0);
  camera.position.copy(direction.multiplyScalar(radius / Math.sin(THREE.MathUtils.degToRad(camera.fov / 2)) * 1.05));
  camera.near = radius / 100;
  camera.far = radius * 100;
  camera.updateProjectionMatrix();
  controls.update();
  requestRender();
}
ui.fold.addEventListener("input", applyFold);

// ---- files ---------------------------------------------------------------------------------
function chooseFiles(list) {
  files = Array.from(list);
  const mesh = files.find((f) => formatOfFileName(f.name));
  ui.dropText.textContent = mesh
    ? `${files.map((f) => f.name).join(", ")} (${Math.round(files.reduce((s, f) => s + f.size, 0) / 1024)} KiB)`
    : "No mesh among these files: choose a GLB / glTF / OBJ / STL / PLY / OFF";
  ui.start.disabled = !mesh;
  if (mesh) setStatus(`Ready to unfold ${mesh.name}.`);
  ui.title.placeholder = mesh ? kitTitle(mesh.name) : "";
}

// The kit's name printed on its sheets: the file's name without its extension, at most 80
// characters (the service's limit, counted in code points).
function kitTitle(fileName) {
  return Array.from(fileName.replace(/\.[^.]*$/, "").trim()).slice(0, 80).join("");
}
ui.file.addEventListener("change", () => chooseFiles(ui.file.files));
for (const type of ["dragenter", "dragover"]) {
  ui.drop.addEventListener(type, (e) => {
    e.preventDefault();
    ui.drop.classList.add("over");
  });
}
for (const type of ["dragleave", "drop"]) ui.drop.addEventListener(type, () => ui.drop.classList.remove("over"));
ui.drop.addEventListener("drop", (e) => {
  e.preventDefault();
  chooseFiles(e.dataTransfer.files);
});

// ---- job -----------------------------------------------------------------------------------
function setStatus(text, error = false) {
  ui.status.textContent = text;
  ui.status.classList.toggle("error", error);
}

function describe(job, withStatus = true) {
  const p = job.progress ?? {};
  const parts = withStatus ? [job.status] : [];
  if (p.phase && p.phase !== job.status && !isFinal(job.status)) parts.push(p.phase);
  if (job.status === "running" && p.fraction != null) parts.push(`${Math.floor(100 * p.fraction)} %`);
  if (p.pieces > 1 && !isFinal(job.status)) parts.push(`piece ${p.piece} of ${p.pieces}`);
  if (p.queue_position) parts.push(`#${p.queue_position} in queue`);
  if (p.faces != null && p.input_faces && p.faces < p.input_faces) {
    parts.push(`approximation: ${p.faces} of ${p.input_faces} faces (${((100 * p.faces) / p.input_faces).toFixed(1)} %)`);
  }
  if (p.overlaps != null) parts.push(`${p.overlaps} overlaps`);
  if (p.elapsed_seconds != null) parts.push(`${p.elapsed_seconds.toFixed(1)} s`);
  return parts.join(" · ");
}

function showProgress(job) {
  // The whole job's share done, every phase counted (README "Job status"): never goes back.
  if (job.status === "queued") ui.progress.removeAttribute("value"); // indeterminate
  else ui.progress.value = progressFraction(job);
  setStatus(describe(job));
}

// Puts an SVG from our own server (the net's cut, fold and label layers) into the net panel.
function showSvg(svg) {
  ui.net.innerHTML = svg;
  const svgElement = ui.net.querySelector("svg");
  svgElement?.removeAttribute("width");
  svgElement?.removeAttribute("height");
}

// The sheet chooser: the whole net, or each printed page of job `id` (pages/k, k from 1).
function offerSheets(id, pages) {
  ui.sheet.replaceChildren(new Option("whole net", "0"));
  for (let k = 1; k <= pages; ++k) ui.sheet.append(new Option(`sheet ${k} of ${pages}`, String(k)));
  ui.sheet.disabled = pages === 0;
  ui.sheet.onchange = async () => {
    const k = Number(ui.sheet.value);
    showSvg(k === 0 ? await client.netSvg(id) : await client.page(id, k));
    linkSvg(id, k);
  };
}

// The SVG link saves what is shown: the whole net, or sheet k alone (pages/k), as a cutting
// machine or a printer takes one sheet at a time.
function linkSvg(id, k) {
  const a = ui.downloads["net.svg"];
  a.dataset.file = k === 0 ? "net.svg" : `pages/${k}`;
  a.href = client.url(`/v1/jobs/${id}/${a.dataset.file}`);
  a.textContent = k === 0 ? "SVG" : `SVG (sheet ${k})`;
}

// The job whose final result is shown: an intermediate fetched before it ended and parsed after
// (a large net takes a while) must not replace it.
let finalShown = null;

async function showResult(id, final, format) {
  const [doc, svg] = await Promise.all([client.netJson(id), client.netSvg(id)]);
  const faces = doc.mesh.faces.length;
  if (!final && (faces === shownFaces || finalShown === id)) return;
  if (final) finalShown = id;
  shownFaces = faces;
  showSvg(svg);
  offerSheets(id, final ? doc.print?.pages ?? 0 : 0);
  showNet3d(doc, id, format);
  for (const [name, a] of Object.entries(ui.downloads)) {
    a.href = client.url(`/v1/jobs/${id}/${name}`);
    a.dataset.job = id;
    a.dataset.file = name;
  }
  linkSvg(id, 0);
  document.body.dataset.level = doc.level?.kind ?? doc.result;
}

async function run() {
  const mesh = files.find((f) => formatOfFileName(f.name));
  if (!mesh) return;
  const buffers = files.filter((f) => f !== mesh).map((f) => ({ name: f.name, data: f }));
  const options = { strategy: ui.strategy.value, paper: ui.paper.value, prefer: ui.prefer.value, components: ui.components.value };
  if (Number(ui.size.value) > 0) options.size_mm = Number(ui.size.value);
  const title = Array.from(ui.title.value.trim()).slice(0, 80).join("") || kitTitle(mesh.name);
  if (title) options.title = title;
  if (Number(ui.timeLimit.value) > 0) options.time_limit = Number(ui.timeLimit.value);
  const detail = ui.detail.value.trim().toLowerCase();
  if (detail === "full" || detail === "auto") options.detail = detail;
  else if (Number(detail) >= 4) options.detail = Math.round(Number(detail));
  current?.abort.abort();
  const abort = new AbortController();
  shownFaces = -1;
  ui.start.disabled = true;
  document.body.dataset.state = "running";
  for (const a of Object.values(ui.downloads)) a.removeAttribute("href");
  setStatus(`Uploading ${mesh.name}…`);
  ui.repairs.replaceChildren();
  try {
    const job = await client.submit(mesh, { filename: mesh.name, buffers, options, signal: abort.signal });
    current = { id: job.id, abort };
    ui.cancel.disabled = false;
    let pending = false;
    let lastShown = 0;
    const final = await client.wait(job.id, {
      signal: abort.signal,
      onProgress: (update) => {
        showProgress(update);
        // Show the latest overlap-free intermediate while the job runs.
        // At most every 2 s: drawing a net of thousands of faces takes the CPU the job needs.
        if (!isFinal(update.status) && update.intermediate && !pending && update.intermediate.faces !== shownFaces && Date.now() - lastShown > 2000) {
          pending = true;
          lastShown = Date.now();
          showResult(job.id, false, job.input?.format).catch(() => {}).finally(() => (pending = false));
        }
      },
    });
    showProgress(final);
    if (final.status === "succeeded" || final.status === "approximated") {
      await showResult(job.id, true, job.input?.format);
      const r = final.result ?? {};
      const m = r.metrics ?? {};
      const glue = m.glue_tabs === undefined ? "" : ` · ${m.glue_tabs} glue tabs, ${m.glue_strips} glue strips, ${m.pages} pages`;
      // Pieces as printed (a part too large for a sheet is cut into several), of the model's parts.
      const pieces = (r.pieces ?? []).length;
      const partCount = new Set((r.pieces ?? []).map((p) => p.component)).size;
      const parts = pieces > 1 ? ` in ${pieces} pieces${partCount > 1 ? ` of ${partCount} parts` : ""}` : "";
      // The detail printed (auto collapses a model too dense to build at its size), and warnings.
      const detail = r.detail ? ` · detail ${r.detail.mode}` : "";
      const warnings = (r.warnings ?? []).map((w) => ` · warning: ${w.message}`).join("");
      setStatus(
        `${final.status}: net of ${r.faces} faces${parts} (input ${r.input_faces})${detail}${glue}${warnings} · ${describe(final, false)}`,
      );
      // What was repaired (or skipped, or dropped), one line each.
      ui.repairs.replaceChildren(
        ...(r.repairs ?? []).map((repair) => {
          const li = document.createElement("li");
          li.dataset.code = repair.code;
          li.textContent = repair.message;
          return li;
        }),
      );
      document.body.dataset.state = "done";
    } else {
      const e = final.error;
      setStatus(e ? `${final.status}: ${e.code} — ${e.detail}` : final.status, final.status === "failed");
      document.body.dataset.state = final.status;
    }
  } catch (err) {
    if (abort.signal.aborted) return;
    if (KEY_CODES.includes(err?.code)) {
      askForKey(err.code);
      document.body.dataset.state = "key";
      return;
    }
    setStatus(err instanceof PapernetError ? `${err.code}: ${err.detail ?? err.message}` : String(err), true);
    document.body.dataset.state = "error";
  } finally {
    ui.cancel.disabled = true;
    ui.start.disabled = files.length === 0;
  }
}
ui.start.addEventListener("click", run);

// ---- API key -------------------------------------------------------------------------------
const KEY_CODES = ["missing_api_key", "invalid_api_key"];
function askForKey(code) {
  ui.keyBox.hidden = false;
  ui.key.value = client.apiKey ?? "";
  setStatus(
    code === "invalid_api_key"
      ? "This server did not accept the API key: enter another one."
      : "This server needs an API key: enter yours, then choose a mesh.",
    code === "invalid_api_key",
  );
  ui.key.focus();
}
ui.key.addEventListener("change", () => {
  const key = ui.key.value.trim();
  client.apiKey = key || undefined;
  if (key) sessionStorage.setItem(keyStore, key);
  else sessionStorage.removeItem(keyStore);
  setStatus(files.length ? "Ready to unfold." : "Choose a mesh.");
});
// A link cannot send the key: with one, a download is fetched (with the header) and saved under
// the name the server gives it (the kit's title), as a plain link's would be.
for (const [name, a] of Object.entries(ui.downloads)) {
  a.addEventListener("click", async (e) => {
    if (!client.apiKey || !a.dataset.job) return; // an open server: the plain link
    e.preventDefault();
    try {
      const res = await client.result(a.dataset.job, a.dataset.file ?? name);
      const url = URL.createObjectURL(await res.blob());
      const save = document.createElement("a");
      save.href = url;
      save.download = fileNameOf(res) ?? name;
      save.click();
      setTimeout(() => URL.revokeObjectURL(url), 60000);
    } catch (err) {
      setStatus(`${err.code ?? "error"}: ${err.detail ?? err.message}`, true);
    }
  });
}
// Does the server ask for a key (or refuse the one kept)? One small request tells.
client.jobs({ limit: 1 }).then(
  () => {
    if (!client.apiKey) return;
    ui.keyBox.hidden = false; // the kept key works: it stays in view, changeable
    ui.key.value = client.apiKey;
  },
  (err) => {
    if (KEY_CODES.includes(err?.code)) askForKey(err.code);
  },
);
ui.cancel.addEventListener("click", async () => {
  if (!current) return;
  try {
    await client.cancel(current.id);
  } catch (err) {
    setStatus(`${err.code ?? "error"}: ${err.detail ?? err.message}`, true);
  }
});
document.body.dataset.state = "idle";
// For tests and the console: the three.js objects (and two of its classes) and the current
// fold (with its net document and `ready`, a promise of the textures shown).
window.papernetDemo = { THREE: { Vector3: THREE.Vector3, Box3: THREE.Box3 }, scene, camera, renderer, get folding() { return folding; } };
