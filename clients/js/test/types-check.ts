// Compiled (not run) by `tsc --noEmit`: the declarations describe the client as it is used.
import { PapernetClient, PapernetError, isFinal, type Job, type NetDocument } from "../papernet.js";

async function example(bytes: Uint8Array): Promise<NetDocument | null> {
  const client = new PapernetClient("http://127.0.0.1:8080");
  const job: Job = await client.submit(bytes, { filename: "duck.glb", options: { strategy: "QQ", size_mm: 150, paper: "A4" } });
  for await (const update of client.events(job.id)) {
    const level = `${update.progress.faces ?? "?"} / ${update.progress.input_faces ?? "?"}`;
    if (isFinal(update.status)) console.log(level);
  }
  try {
    const net = await client.netJson(job.id);
    const root: number = net.net.faces.findIndex((f) => f.parent === -1);
    console.log(root, net.level?.kind);
    const first = net.print?.placements[0];
    if (first && first.page >= 0) console.log((await client.page(job.id, first.page + 1)).length);
    const pages: string[] | undefined = (await client.job(job.id)).links.pages;
    console.log(pages?.length);
    return net;
  } catch (e) {
    if (e instanceof PapernetError && e.code === "invalid_mesh") return null;
    throw e;
  }
}
void example;
// @ts-expect-error: unknown strategies are refused by the types too
void new PapernetClient().submit("", { options: { strategy: "XYZ" } });

async function withCallback(client: PapernetClient): Promise<boolean> {
  const job = await client.submit("", { callbackUrl: "http://hooks.shop.example/papernet" });
  const seen = await client.job(job.id);
  return seen.callback?.state === "delivered" && seen.callback.attempts.every((a) => a.at.length > 0);
}
void withCallback;
