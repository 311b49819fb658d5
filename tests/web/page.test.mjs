// The page (examples/web) in headless Chromium: it opens a scene through its file input (a .ply,
// then the same scene as .spz of version 4 and of version 3), turns it as a drag does, and its GPU (WGSL) and CPU (WebAssembly)
// colours and its turned positions must agree with the native CLI's `zhf splat --quat` on the same
// file, within the native tests' float tolerance (web_reference.json) per unit of each channel's
// norm. ZHF_PAGE_SCREENSHOT=FILE saves the page as it stands after the .ply's turn (docs/web_page.png).
// Run: ZHF_BINARY=zhf ZHF_WEB_PACKAGE=<build>/web/package ZHF_WEB_REFERENCE=<file> node --test tests/web/page.test.mjs
import { test } from "node:test";
import assert from "node:assert/strict";
import { spawnSync } from "node:child_process";
import { mkdtempSync, readFileSync, rmSync } from "node:fs";
import { tmpdir } from "node:os";
import { join } from "node:path";
import { fileURLToPath } from "node:url";
import { launchChromium } from "../../web/browser/chromium.mjs";
import { servePage } from "../../examples/web/serve.mjs";
import { readPly } from "../../examples/web/scene.mjs";

const root = fileURLToPath(new URL("../../", import.meta.url));
const zhfBinary = process.env.ZHF_BINARY;
const reference = JSON.parse(readFileSync(process.env.ZHF_WEB_REFERENCE, "utf8"));
const kSplats = 4000;
const kQuaternion = [0.877582562, 0.136978723, 0.205468084, 0.410936169];  // a turn of 1 rad about (2, 3, 6) / 7

function run(argv) {
  const r = spawnSync(argv[0], argv.slice(1), { encoding: "utf8" });
  assert.equal(r.status, 0, `${argv.join(" ")}: ${r.stderr}`);
}

const floats = (b64) => new Float32Array(Uint8Array.from(Buffer.from(b64, "base64")).buffer);

// Each splat's channels (band 0 and the rest, as the .ply's layout holds them) against the
// native values: the largest error per unit of the channel's norm, with where it is.
function worstChannelError(got, expected, degree) {
  const n = (degree + 1) ** 2, rest = n - 1, per = 3 * n;
  let worst = { error: 0, where: "" };
  for (let s = 0; s < got.length / per; ++s)
    for (let c = 0; c < 3; ++c) {
      const at = (i) => per * s + (i === 0 ? c : 3 + c * rest + i - 1);
      let norm = 0;
      for (let i = 0; i < n; ++i) norm += expected[at(i)] ** 2;
      for (let i = 0; i < n; ++i) {
        const error = Math.abs(got[at(i)] - expected[at(i)]) / Math.max(1, Math.sqrt(norm));
        if (error > worst.error) worst = { error, where: `splat ${s}, channel ${"RGB"[c]}, band ${Math.floor(Math.sqrt(i))}, index ${i}` };
      }
    }
  return worst;
}

test("the page turns a .ply and a .spz as zhf splat does, on the GPU and the CPU", async () => {
  const dir = mkdtempSync(join(tmpdir(), "zhf-page-"));
  const server = await servePage({ packageDir: process.env.ZHF_WEB_PACKAGE });
  const browser = await launchChromium();
  try {
    const ply = join(dir, "scene.ply"), spz = join(dir, "scene.spz"), spz3 = join(dir, "scene_v3.spz");
    run(["/usr/bin/python3", join(root, "examples/make_splats.py"), ply, "--splats", String(kSplats), "--seed", "7"]);
    run([zhfBinary, "splat", "--in", ply, "--out", spz]);
    run([zhfBinary, "splat", "--in", ply, "--out", spz3, "--spz-version", "3"]);
    const quat = kQuaternion.join(" ");
    for (const [from, to] of [[ply, "turned.ply"], [spz, "turned_spz.ply"], [spz3, "turned_spz3.ply"]])
      run([zhfBinary, "splat", "--in", from, "--out", join(dir, to), "--quat", quat]);

    const page = await browser.newPage();
    await page.setViewport({ width: 1100, height: 700 });
    const problems = [];
    page.on("pageerror", (e) => problems.push(e.message));
    await page.goto(`http://127.0.0.1:${server.address().port}/`);
    await page.waitForSelector("body[data-ready=true]", { timeout: 60000 });
    for (const [file, native] of [[ply, "turned.ply"], [spz, "turned_spz.ply"], [spz3, "turned_spz3.ply"]]) {
      const name = file.split("/").pop();
      await (await page.$("#file")).uploadFile(file);
      await page.waitForFunction((n) => window.zhfPage.scene()?.name === n || document.getElementById("message").textContent,
        { timeout: 60000 }, name);
      assert.equal(await page.$eval("#message", (e) => e.textContent), "", `${name}: the page's message`);
      await page.evaluate((q) => window.zhfPage.setQuaternion(q), kQuaternion);
      const results = await page.evaluate(() => window.zhfPage.results());
      const expected = readPly(readFileSync(join(dir, native)).buffer, native);
      assert.equal(expected.count, kSplats);
      const tolerance = reference.splats[expected.degree].tolerance.float;
      for (const [path, colours] of [["CPU", floats(results.cpu)], ["GPU", floats(results.gpu)]]) {
        const worst = worstChannelError(colours, expected.colours, expected.degree);
        assert.ok(worst.error <= tolerance, `${name}, ${path}: ${worst.where}: error ${worst.error} > ${tolerance} of the channel's norm`);
      }
      const positions = floats(results.positions);
      positions.forEach((p, k) => assert.ok(Math.abs(p - expected.positions[k]) <= tolerance * Math.max(1, Math.abs(p)),
        `${name}: position ${Math.floor(k / 3)}, ${"xyz"[k % 3]}: ${p} against ${expected.positions[k]}`));
      assert.ok(results.times.cpu > 0 && results.times.gpu > 0, JSON.stringify(results.times));
      const stats = await page.$eval("#stats", (e) => e.textContent);
      assert.match(stats, /CPU \(WebAssembly, simd128\): [0-9.]+ ms/);
      assert.match(stats, /GPU \(WGSL\): [0-9.]+ ms/);
      assert.match(stats, /max \|GPU - CPU\|: /);
      if (file === ply && process.env.ZHF_PAGE_SCREENSHOT) await page.screenshot({ path: process.env.ZHF_PAGE_SCREENSHOT });
    }
    assert.deepEqual(problems, []);
  } finally {
    await browser.close();
    server.close();
    rmSync(dir, { recursive: true, force: true });
  }
});
