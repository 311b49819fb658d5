// Headless Chromium with WebGPU, for zhf's tests, its verify runner and its benchmark: the one place
// that knows how to start it. Debian's chromium runs WebGPU without a GPU on SwiftShader (a CPU
// implementation of Vulkan: right results, no GPU timings), driven by puppeteer-core from the
// checkout's tools/node (scripts/setup_web.sh). The compositor goes through ANGLE on that Vulkan
// too: on its default GL a WebGPU canvas finds no shared-image backing and the GPU process dies
// at the first frame. The background services Chromium starts are off: a machine without a
// network refuses their connections.
import { createRequire } from "node:module";
import { existsSync } from "node:fs";
import { delimiter, join } from "node:path";
import { fileURLToPath, pathToFileURL } from "node:url";

const kToolsModules = fileURLToPath(new URL("../../tools/node/node_modules/", import.meta.url));

export const kChromiumFlags = [
  "--headless=new", "--no-sandbox", "--enable-unsafe-webgpu", "--enable-features=Vulkan", "--use-vulkan=swiftshader",
  "--use-webgpu-adapter=swiftshader", "--use-angle=vulkan", "--no-first-run", "--disable-background-networking", "--disable-component-update",
  "--disable-sync", "--disable-default-apps", "--disable-extensions",
];

// The browser: $ZHF_CHROMIUM, else chromium on PATH.
export function chromiumPath() {
  if (process.env.ZHF_CHROMIUM) return process.env.ZHF_CHROMIUM;
  for (const dir of (process.env.PATH ?? "").split(delimiter)) {
    const candidate = join(dir, "chromium");
    if (dir && existsSync(candidate)) return candidate;
  }
  throw new Error("chromium not found on PATH (scripts/setup_web.sh installs it)");
}

// puppeteer-core from modules (default: the checkout's tools/node).
export async function puppeteer(modules = process.env.ZHF_NODE_MODULES ?? kToolsModules) {
  const require = createRequire(join(modules, "zhf.js"));
  let entry;
  try {
    entry = require.resolve("puppeteer-core");
  } catch {
    throw new Error(`puppeteer-core not found in ${modules} (scripts/setup_web.sh installs it)`);
  }
  return (await import(pathToFileURL(entry).href)).default;
}

// A headless Chromium with WebGPU, in a private profile that is removed when it closes.
export async function launchChromium() {
  const driver = await puppeteer();
  return driver.launch({ executablePath: chromiumPath(), headless: true, args: kChromiumFlags });
}
