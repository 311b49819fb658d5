// Runs one WGSL compute shader in headless Chromium's WebGPU (Tint compiles it), for zhf verify's
// WebGPU runner (verify/src/runners/webgpu_runner.cc):
//   node run_compute.mjs DIR WORKGROUPS RESULT_BYTES
// DIR holds shader.wgsl (entry point main; bind group 0: bindings 0 and 1 read-only storage, 2
// read-write storage) and input0.bin and input1.bin; writes DIR/result.bin (binding 2 after the
// dispatch of WORKGROUPS groups in x). Exit 1 with the compiler's or the device's message.
import { readFileSync, writeFileSync } from "node:fs";
import { join } from "node:path";
import { pathToFileURL } from "node:url";
import { launchChromium } from "./chromium.mjs";

const [dir, workgroups, resultBytes] = process.argv.slice(2);
writeFileSync(join(dir, "page.html"), "<!doctype html><title>zhf compute</title>");
const browser = await launchChromium();
try {
  const page = await browser.newPage();
  await page.goto(pathToFileURL(join(dir, "page.html")).href);
  const result = await page.evaluate(async (code, inputs, groups, bytes) => {
    const decode = (b64) => Uint8Array.from(atob(b64), (c) => c.charCodeAt(0));
    const adapter = await navigator.gpu?.requestAdapter();
    if (!adapter) return { error: "no WebGPU adapter" };
    const device = await adapter.requestDevice({ requiredLimits: {
      maxStorageBufferBindingSize: adapter.limits.maxStorageBufferBindingSize, maxBufferSize: adapter.limits.maxBufferSize } });
    device.pushErrorScope("validation");
    const module = device.createShaderModule({ code });
    const info = await module.getCompilationInfo();
    const error = info.messages.find((m) => m.type === "error");
    if (error) return { error: `Tint refused the WGSL: ${error.lineNum}:${error.linePos}: ${error.message}` };
    const pipeline = device.createComputePipeline({ layout: "auto", compute: { module, entryPoint: "main" } });
    const storage = (data) => {
      const buffer = device.createBuffer({ size: Math.max(4, data.byteLength), usage: GPUBufferUsage.STORAGE | GPUBufferUsage.COPY_DST });
      device.queue.writeBuffer(buffer, 0, data);
      return buffer;
    };
    const buffers = inputs.map((b64) => storage(decode(b64)));
    const output = device.createBuffer({ size: bytes, usage: GPUBufferUsage.STORAGE | GPUBufferUsage.COPY_SRC });
    const readback = device.createBuffer({ size: bytes, usage: GPUBufferUsage.MAP_READ | GPUBufferUsage.COPY_DST });
    const group = device.createBindGroup({ layout: pipeline.getBindGroupLayout(0), entries: [
      { binding: 0, resource: { buffer: buffers[0] } }, { binding: 1, resource: { buffer: buffers[1] } },
      { binding: 2, resource: { buffer: output } }] });
    const encoder = device.createCommandEncoder();
    const pass = encoder.beginComputePass();
    pass.setPipeline(pipeline);
    pass.setBindGroup(0, group);
    pass.dispatchWorkgroups(groups);
    pass.end();
    encoder.copyBufferToBuffer(output, 0, readback, 0, bytes);
    device.queue.submit([encoder.finish()]);
    const invalid = await device.popErrorScope();
    if (invalid) return { error: `WebGPU: ${invalid.message}` };
    await readback.mapAsync(GPUMapMode.READ);
    const out = new Uint8Array(readback.getMappedRange());
    let binary = "";
    for (let k = 0; k < out.length; k += 0x8000) binary += String.fromCharCode(...out.subarray(k, k + 0x8000));
    return { result: btoa(binary) };
  }, readFileSync(join(dir, "shader.wgsl"), "utf8"), [0, 1].map((k) => readFileSync(join(dir, `input${k}.bin`)).toString("base64")),
  Number(workgroups), Number(resultBytes));
  if (result.error) {
    console.error(result.error);
    process.exitCode = 1;
  } else {
    writeFileSync(join(dir, "result.bin"), Buffer.from(result.result, "base64"));
  }
} finally {
  await browser.close();
}
