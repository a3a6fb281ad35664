// Starts a real `papernet serve` on a free loopback port for the tests, or uses the server at
// PAPERNET_URL (e.g. the compose service). PAPERNET_BIN names the binary (set by ctest);
// PAPERNET_TEST_DATA the directory of sample meshes (default: the repository's tests/data).
import { spawn } from "node:child_process";
import { mkdtempSync, rmSync, readFileSync } from "node:fs";
import { tmpdir } from "node:os";
import { dirname, join, resolve } from "node:path";
import { fileURLToPath } from "node:url";

const here = dirname(fileURLToPath(import.meta.url));
export const dataDir = process.env.PAPERNET_TEST_DATA ?? resolve(here, "../../../tests/data");

export function sample(name) {
  return readFileSync(join(dataDir, name));
}

/**
 * Resolves to {url, stop()}. `args` are extra flags for `papernet serve`.
 * Fails with the server's output when it does not start within 20 s.
 */
export async function startServer(args = []) {
  if (process.env.PAPERNET_URL) {
    return { url: process.env.PAPERNET_URL.replace(/\/+$/, ""), stop: async () => {}, external: true };
  }
  const bin = process.env.PAPERNET_BIN;
  if (!bin) throw new Error("set PAPERNET_BIN to the papernet binary (or PAPERNET_URL to a running server)");
  const data = mkdtempSync(join(tmpdir(), "papernet-js-"));
  const child = spawn(bin, ["serve", "--host", "127.0.0.1", "--port", "0", "--data", data, ...args], {
    stdio: ["ignore", "pipe", "pipe"],
  });
  let output = "";
  const url = await new Promise((resolveUrl, reject) => {
    const timer = setTimeout(() => reject(new Error(`papernet serve did not start in 20 s:\n${output}`)), 20000);
    const onData = (chunk) => {
      output += chunk;
      const m = /listening on (http:\/\/[0-9.:]+)/.exec(output);
      if (m) {
        clearTimeout(timer);
        resolveUrl(m[1]);
      }
    };
    child.stdout.on("data", onData);
    child.stderr.on("data", (c) => (output += c));
    child.on("exit", (code) => {
      clearTimeout(timer);
      reject(new Error(`papernet serve exited with ${code}:\n${output}`));
    });
  });
  child.stdout.resume();
  child.stderr.resume();
  const stop = async () => {
    if (child.exitCode === null) {
      const exited = new Promise((r) => child.once("exit", r));
      child.kill("SIGTERM");
      const timer = setTimeout(() => child.kill("SIGKILL"), 15000);
      await exited;
      clearTimeout(timer);
    }
    rmSync(data, { recursive: true, force: true });
  };
  return { url, stop, output: () => output };
}
