// Serves the page on http://127.0.0.1:PORT/ (a module needs an http origin): examples/web at /, the
// zhf package (default: build/web/package, made by the build where emscripten is installed) at
// /zhf/, and npm's fzstd (for .spz version 4; scripts/setup_web.sh puts it in tools/node) at
// /vendor/fzstd/. Files only, read-only, nothing outside those folders.
//   node examples/web/serve.mjs [--port 8080] [--package DIR]
import { createServer } from "node:http";
import { readFile } from "node:fs/promises";
import { extname, join, resolve, sep } from "node:path";
import { fileURLToPath } from "node:url";

const kTypes = { ".html": "text/html", ".mjs": "text/javascript", ".js": "text/javascript", ".wasm": "application/wasm",
  ".wgsl": "text/plain", ".json": "application/json", ".css": "text/css", ".png": "image/png" };
const kPage = fileURLToPath(new URL(".", import.meta.url));
const kFzstd = fileURLToPath(new URL("../../tools/node/node_modules/fzstd/esm/", import.meta.url));

// A server of the page and the package; resolves to it listening (port 0: any free port).
export function servePage({ port = 0, packageDir = join(kPage, "../../build/web/package") } = {}) {
  const roots = [["/zhf/", resolve(packageDir)], ["/vendor/fzstd/", resolve(kFzstd)], ["/", resolve(kPage)]];
  const server = createServer(async (request, response) => {
    const path = decodeURIComponent(new URL(request.url, "http://localhost").pathname);
    const [prefix, root] = roots.find(([p]) => path.startsWith(p));
    const file = resolve(root, "." + path.slice(prefix.length - 1) + (path.endsWith("/") ? "index.html" : ""));
    if (request.method !== "GET" || (file !== root && !file.startsWith(root + sep))) {
      response.writeHead(404).end();
      return;
    }
    try {
      const body = await readFile(file);
      response.writeHead(200, { "content-type": kTypes[extname(file)] ?? "application/octet-stream" }).end(body);
    } catch {
      response.writeHead(404).end();
    }
  });
  return new Promise((done) => server.listen(port, "127.0.0.1", () => done(server)));
}

if (process.argv[1] && resolve(process.argv[1]) === fileURLToPath(import.meta.url)) {
  const option = (name, fallback) => {
    const at = process.argv.indexOf(name);
    return at > 0 ? process.argv[at + 1] : fallback;
  };
  const server = await servePage({ port: Number(option("--port", 8080)), packageDir: option("--package", undefined) });
  console.log(`zhf's page: http://127.0.0.1:${server.address().port}/`);
}
