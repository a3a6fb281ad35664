// TypeScript declarations of papernet.js (the papernet HTTP API client).

export type Strategy = "AUTO" | "QQ" | "SEMP" | "SEQ" | "TU";
/** A4, A3, A5, Letter, Legal, Tabloid, a size "WxHmm" (e.g. "300x200mm"), or none (the SVG sized to the net). */
export type Paper =
  | "A4"
  | "Letter"
  | "A3"
  | "A5"
  | "Legal"
  | "Tabloid"
  | "none"
  | `${number}x${number}mm`;
export type MeshFormat = "glb" | "gltf" | "drc" | "obj" | "off" | "ply" | "stl";
export type JobStatus = "queued" | "running" | "succeeded" | "approximated" | "failed" | "cancelled";
export type ResultFile = "net.json" | "net.svg" | "net.pdf" | "mesh.glb";

/** Job options (api/openapi.json #/components/schemas/Options); unknown names are refused. */
export interface Options {
  strategy?: Strategy;
  seed?: number;
  target_faces?: number;
  /** Faces printed: "auto" (default; a model denser than a person can build at its size is
   * collapsed to fewer, larger faces), "full" (every face) or a face count. Collapsed: approximate. */
  detail?: "auto" | "full" | number;
  /** @deprecated older name of `detail: N` */
  simplify?: number;
  time_limit?: number;
  /** Longest side of the model in millimetres (exclusive with scale). */
  size_mm?: number;
  /** Millimetres per mesh unit (exclusive with size_mm). */
  scale?: number;
  paper?: Paper;
  margin_mm?: number;
  /** Overlap of the tiles of a net larger than a page, in millimetres. */
  overlap_mm?: number;
  /** Layout fit: what the choice of pieces saves first, "sheets" (default) or "pieces" to cut out. */
  prefer?: "sheets" | "pieces";
  /** Glue: "auto" (tabs where they fit, strips elsewhere), "strips", "none"; true = "auto", false = "none". */
  tabs?: "auto" | "strips" | "none" | boolean;
  /** Tallest glue tab and widest strip half in millimetres (default 6; 0: no glue). */
  tab_height_mm?: number;
  /** Lowest glue tab printed in millimetres (default 2). */
  min_tab_height_mm?: number;
  /** Moves the pass that makes room for tabs may try (default 100000; 0: no pass). */
  tab_room_budget?: number;
  flat_fold_degrees?: number;
  /** Matching numbers on both sides of each cut edge (default true). */
  labels?: boolean;
  /** Layout fit: a first page mapping the sheets, the pieces on each, the model as built (two
   *  views, each piece numbered where it shows) and the build order (default: when the print has
   *  more than one piece). */
  overview?: boolean;
  /** The kit's name, printed on every page beside its number ("Duck · page 2 of 5"), as the
   *  overview's title and as the PDF's title: at most 80 characters, no control characters. */
  title?: string;
  /** "all" (default): every connected part its own piece; "largest": only the largest part. */
  components?: "all" | "largest";
  /** Refuse a mesh that needs repair instead of repairing it (default false). */
  strict?: boolean;
  /** Service only: POST the job's final status, signed, to this http:// URL when it ends. */
  callback_url?: string | null;
}

/** A job's callback delivery (README "Webhooks"). */
export interface Callback {
  url: string;
  state: "pending" | "delivered" | "failed";
  delivered: boolean;
  /** Every attempt: the receiver's HTTP status, or why it failed. */
  attempts: Array<{ at: string; status?: number; error?: string }>;
  next_attempt: string | null;
}

/** RFC 9457 problem details with papernet's stable code. */
export interface Problem {
  type?: string;
  title?: string;
  status?: number;
  code: string;
  detail?: string;
  instance?: string;
  option?: string;
  reasons?: Array<Record<string, unknown>>;
  [extra: string]: unknown;
}

export interface Progress {
  phase?: string;
  /** Faces of the mesh being worked on now (the approximation level). */
  faces?: number | null;
  input_faces?: number | null;
  overlaps?: number | null;
  iterations?: number | null;
  elapsed_seconds?: number;
  /** 1 = next; null when not queued. */
  queue_position?: number | null;
  /** The piece being unfolded (1-based) and how many there are, while one is. */
  piece?: number;
  pieces?: number;
  /** The share of the whole job done, 0 to 1, every phase counted; never goes back, 1 once
   *  the job ended. */
  fraction?: number;
}

export interface Job {
  id: string;
  status: JobStatus;
  created: string;
  started?: string | null;
  finished?: string | null;
  input: { format?: string; bytes?: number; faces?: number | null };
  options: Required<Pick<Options, "strategy" | "seed" | "paper">> & Options;
  progress: Progress;
  cancel_requested?: boolean;
  result?: {
    kind: "complete" | "approximate";
    faces: number;
    input_faces: number;
    overlaps: number;
    pieces: Piece[];
    repairs: Repair[];
    /** The net JSON's metrics, the print's (pages, cut_edges, glue_tabs, glue_strips) and, with
     *  tabs auto, what the pass that makes room for tabs did. */
    metrics?: Record<string, number> & { tab_room?: Record<string, number> };
  } | null;
  intermediate?: { faces: number; input_faces: number; overlaps: number };
  error?: Problem | null;
  /** Only for a job with a callback_url. */
  callback?: Callback;
  /** self, events, the result files by name; `textures` and `pages` (page 1 first) as arrays. */
  links: { [name: string]: string | string[] | undefined; textures?: string[]; pages?: string[] };
}

/** X-Papernet-Level of a result file. */
export interface Level {
  kind: "complete" | "approximate" | "intermediate" | string;
  faces: number | null;
  inputFaces: number | null;
}

/** A repair made to the input, or a note of what loading skipped or what was dropped. */
export interface Repair {
  code: string;
  count: number;
  message: string;
}

/** A part of the input unfolded on its own into one piece; printed with layout fit, a piece cut
 *  out of part `component` to fit a sheet (its result and hausdorff are the part's). */
export interface Piece {
  component: number;
  result: "complete" | "approximate";
  faces: number;
  hausdorff: number;
}

/** The net document, papernet.net/2 (README.md, "The net"). */
export interface NetDocument {
  format: "papernet.net/2";
  result: "complete" | "approximate";
  strategy?: string;
  input?: { vertices: number; faces: number; components: number; genus?: number; boundaries?: number };
  repairs: Repair[];
  pieces: Piece[];
  mesh: {
    vertices: Array<[number, number, number]>;
    faces: Array<[number, number, number]>;
    /** Per face, its corners' texture coordinates (glTF convention: origin top left); null without. */
    uvs?: Array<Array<[number, number]> | null>;
    /** Per face, its corners' vertex colours [r, g, b, a]; null without. */
    colors?: Array<Array<[number, number, number, number]> | null>;
    /** Per face, an index into `materials` (-1: none). */
    face_materials?: number[];
  };
  materials?: Array<{
    name: string;
    base_color: [number, number, number, number];
    texture: number | null;
    /** glTF alphaMode: what is see-through prints as paper (OPAQUE when absent). */
    alpha_mode?: "OPAQUE" | "MASK" | "BLEND";
    alpha_cutoff?: number;
  }>;
  /** The images are served beside the document: PapernetClient.texture(id, k). */
  textures?: Array<{
    name: string;
    mime_type: string;
    width: number;
    height: number;
    sampler?: { wrap_s: number; wrap_t: number; mag_filter: number; min_filter: number };
  }>;
  /** One tree per piece: `parent` is -1 for its root, else a face of the same piece. */
  net: { faces: Array<{ piece: number; parent: number; points: Array<[number, number]> }> };
  /** Present when the run printed on paper; `pieces` are then the pieces as printed. */
  print?: NetPrint;
  metrics?: Record<string, number>;
  /** Parsed from the X-Papernet-Level header (not enumerable). */
  readonly level: Level | null;
  [extra: string]: unknown;
}

/** Where the pieces lie on the printed pages (README.md, "The net"). */
export interface NetPrint {
  paper: string;
  page_size_mm: [number, number];
  margin_mm: number;
  mm_per_unit: number;
  pages: number;
  layout: "fit" | "tile";
  /** The option `title` (the kit's name every page prints), when it was given. */
  title?: string;
  /** One per piece: `transform` [a, b, c, d, e, f] maps a net point (u, v) of the piece to
   *  (a·u + c·v + e, b·u + d·v + f) mm from the top-left corner of page `page` (0-based; -1 when
   *  tiled: then into the tile grid's frame, see `tiles`). */
  placements: Array<{ piece: number; page: number; transform: [number, number, number, number, number, number] }>;
  /** Layout tile: the window [x, y, width, height] of the tile grid's frame each page shows. */
  tiles?: Array<{ page: number; window_mm: [number, number, number, number] }>;
  /** The overview page (0-based; absent without one): the pieces then lie on pages 1 and on. */
  overview_page?: number;
  /** The overview's pages from overview_page on (written with it): 1, or more for a print of
   *  many sheets and pieces. */
  overview_pages?: number;
}

export interface SseEvent {
  event: string;
  data: string;
  id: string | null;
}

export type BinaryLike = Blob | ArrayBuffer | ArrayBufferView | string;

export interface SubmitOptions {
  options?: Options;
  /** File name (its extension gives the format); default: the Blob/File's name. */
  filename?: string;
  format?: MeshFormat;
  /** External files of a .gltf by the relative URI it uses; sends multipart/form-data. */
  buffers?: Record<string, BinaryLike> | Array<{ name: string; data: BinaryLike }>;
  /** Send multipart/form-data even without buffers. */
  multipart?: boolean;
  /** Idempotency-Key: retries of one submission with this key resolve to its first job. */
  idempotencyKey?: string;
  /** Sets the option callback_url: where the server POSTs the job's final status, signed. */
  callbackUrl?: string;
  signal?: AbortSignal;
}

export interface RequestOptions {
  signal?: AbortSignal;
}

export const FINAL_STATUSES: readonly JobStatus[];
export const RESULT_FILES: readonly ResultFile[];
/** The name the server gives a result file (its Content-Disposition), or null. */
export function fileNameOf(response: Response): string | null;
export function isFinal(status: string): boolean;
/** The share of a job done, 0 to 1 (progress.fraction; 1 once final). */
export function progressFraction(job: Job): number;
export function formatOfFileName(name: string | undefined | null): MeshFormat | undefined;
export function parseLevel(header: string | null | undefined): Level | null;
/** Server-Sent Events from a byte stream (e.g. a fetch Response's body). */
export function parseSse(stream: ReadableStream<Uint8Array>): AsyncGenerator<SseEvent, void, undefined>;

/** An error answer of the server, or "network_error" / "bad_response" / "timeout". */
export class PapernetError extends Error {
  constructor(problem: Problem, init?: { status?: number; retryAfter?: number | null; cause?: unknown });
  readonly name: "PapernetError";
  /** The server's stable problem code, e.g. "invalid_mesh", "queue_full". */
  readonly code: string;
  /** HTTP status; 0 when the server was not reached. */
  readonly status: number;
  readonly title?: string;
  readonly detail?: string;
  /** Seconds from Retry-After, or null. */
  readonly retryAfter: number | null;
  readonly problem: Problem;
}

export class PapernetClient {
  /** `baseUrl` e.g. "http://127.0.0.1:8080"; "" for the page the server serves. */
  /** `apiKey`: the key of a server started with --api-keys (sent as Authorization: Bearer). */
  constructor(baseUrl?: string, init?: { fetch?: typeof fetch; apiKey?: string });
  readonly baseUrl: string;
  apiKey: string | undefined;
  url(path: string): string;
  submit(mesh: BinaryLike, init?: SubmitOptions): Promise<Job>;
  job(id: string, init?: RequestOptions): Promise<Job>;
  jobs(init?: { limit?: number; cursor?: string; signal?: AbortSignal }): Promise<{ jobs: Job[]; next: string | null }>;
  cancel(id: string, init?: RequestOptions): Promise<Job>;
  /** One job document per change; the last is final. */
  events(id: string, init?: RequestOptions): AsyncGenerator<Job, void, undefined>;
  poll(
    id: string,
    init?: { interval?: number; timeout?: number; onProgress?: (job: Job) => void; signal?: AbortSignal },
  ): Promise<Job>;
  /** Events, falling back to polling; resolves to the final job. */
  wait(id: string, init?: { interval?: number; onProgress?: (job: Job) => void; signal?: AbortSignal }): Promise<Job>;
  /** A result file: one of RESULT_FILES, a printed page (pages/k, k from 1) or a texture
   *  (textures/k, k from 0). */
  result(id: string, name: ResultFile | `pages/${number}` | `textures/${number}`, init?: RequestOptions): Promise<Response>;
  netJson(id: string, init?: RequestOptions): Promise<NetDocument>;
  netSvg(id: string, init?: RequestOptions): Promise<string>;
  netPdf(id: string, init?: RequestOptions): Promise<Uint8Array>;
  meshGlb(id: string, init?: RequestOptions): Promise<Uint8Array>;
  /** Texture k of the net's `textures`: GET /v1/jobs/{id}/textures/{k}. */
  texture(id: string, k: number, init?: RequestOptions): Promise<{ contentType: string | null; bytes: Uint8Array }>;
  /** Printed page k (from 1) as SVG text: GET /v1/jobs/{id}/pages/{k}. */
  page(id: string, k: number, init?: RequestOptions): Promise<string>;
    /** GET /readyz answers 200. */
  ready(init?: RequestOptions): Promise<boolean>;
}
