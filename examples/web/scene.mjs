// The page's scene readers, in plain JavaScript (Node runs them too): a 3D Gaussian Splatting .ply
// (binary little-endian, the 3DGS tools' layout) or a .spz (versions 2 to 4), into positions and
// colours in the .ply's layout. zhf's own readers (splat/, `zhf splat`) read more (ASCII and
// compressed .ply, .splat, .glb, SOG, .spz extension records); convert with them for the page.
//
// A scene: { count, degree, positions: Float32Array(3 count), colours: Float32Array(count 3 (degree + 1)^2) }
// with each splat's colours as band 0's R, G, B (f_dc_0..2), then bands 1.. of R, of G and of B
// (f_rest, channel by channel); values as stored (the file's axes).

const kPlyTypes = {
  char: ["getInt8", 1], int8: ["getInt8", 1], uchar: ["getUint8", 1], uint8: ["getUint8", 1],
  short: ["getInt16", 2], int16: ["getInt16", 2], ushort: ["getUint16", 2], uint16: ["getUint16", 2],
  int: ["getInt32", 4], int32: ["getInt32", 4], uint: ["getUint32", 4], uint32: ["getUint32", 4],
  float: ["getFloat32", 4], float32: ["getFloat32", 4], double: ["getFloat64", 8], float64: ["getFloat64", 8],
};
const kRestPerDegree = [0, 9, 24, 45, 72];  // f_rest values of SH degree 0..4 (3 channels)
const kMaxHeaderBytes = 1 << 16;

class SceneError extends Error {}

function degreeOfRest(rest, name) {
  const degree = kRestPerDegree.indexOf(rest);
  if (degree < 0) throw new SceneError(`${name}: ${rest} f_rest values; a scene has ${kRestPerDegree.join(", ")}`);
  return degree;
}

/** A binary little-endian 3DGS .ply. */
export function readPly(buffer, name = "scene.ply") {
  const bytes = new Uint8Array(buffer);
  const head = new TextDecoder().decode(bytes.subarray(0, Math.min(bytes.length, kMaxHeaderBytes)));
  const end = head.indexOf("end_header\n");
  if (!head.startsWith("ply\n") || end < 0) throw new SceneError(`${name}: not a .ply file (no ply header)`);
  const lines = head.slice(0, end).split("\n").map((l) => l.trim());
  if (!lines.includes("format binary_little_endian 1.0"))
    throw new SceneError(`${name}: only binary little-endian .ply is read here (convert with zhf splat)`);
  let count = -1, element = "", properties = [];
  for (const line of lines) {
    const words = line.split(/\s+/);
    if (words[0] === "element") {
      if (element === "vertex") break;  // the vertices' properties are complete
      element = words[1];
      if (element !== "vertex") throw new SceneError(`${name}: element '${element}' before the vertices (a compressed .ply? convert with zhf splat)`);
      count = Number(words[2]);
    } else if (words[0] === "property" && element === "vertex") {
      if (!kPlyTypes[words[1]]) throw new SceneError(`${name}: property ${words.slice(1).join(" ")}: not a scalar type`);
      properties.push({ type: kPlyTypes[words[1]], name: words[2] });
    }
  }
  if (!Number.isSafeInteger(count) || count < 0) throw new SceneError(`${name}: no vertex count`);
  let stride = 0;
  const offset = {};
  for (const p of properties) offset[p.name] = [stride, p.type], stride += p.type[1];
  for (const required of ["x", "y", "z", "f_dc_0", "f_dc_1", "f_dc_2"])
    if (!offset[required]) throw new SceneError(`${name}: no ${required} property`);
  let rest = 0;
  while (offset[`f_rest_${rest}`]) ++rest;
  const degree = degreeOfRest(rest, name);
  const start = end + "end_header\n".length;
  if (bytes.length < start + count * stride) throw new SceneError(`${name}: truncated: ${count} splats need ${count * stride} bytes`);
  const view = new DataView(buffer, start);
  const read = (s, property) => {
    const [at, [getter]] = offset[property];
    return view[getter](s * stride + at, true);
  };
  const per = 3 * (degree + 1) ** 2;
  const positions = new Float32Array(3 * count), colours = new Float32Array(per * count);
  for (let s = 0; s < count; ++s) {
    for (let k = 0; k < 3; ++k) positions[3 * s + k] = read(s, "xyz"[k]);
    for (let c = 0; c < 3; ++c) colours[per * s + c] = read(s, `f_dc_${c}`);
    for (let k = 0; k < rest; ++k) colours[per * s + 3 + k] = read(s, `f_rest_${k}`);
  }
  return { count, degree, positions, colours };
}

/** A .spz: versions 2 and 3 (one gzip stream) and version 4 (a zstd frame per attribute, when the
 * caller passes `zstd`, a decompressor of one frame: the page uses npm's fzstd). Values as stored;
 * extension records (the file's axes among them) are not read. */
export async function readSpz(buffer, name = "scene.spz", { zstd } = {}) {
  const bytes = new Uint8Array(buffer);
  let attributes;  // the six attributes' bytes, one after another from attributes.start
  let header;
  if (bytes[0] === 0x1f && bytes[1] === 0x8b) {
    const inflated = new Uint8Array(await new Response(new Blob([buffer]).stream().pipeThrough(new DecompressionStream("gzip"))).arrayBuffer());
    header = inflated.subarray(0, 16);
    attributes = { data: inflated, start: 16 };
  } else {
    header = bytes.subarray(0, 32);
  }
  const h = new DataView(header.buffer, header.byteOffset, header.byteLength);
  if (header.length < 16 || h.getUint32(0, true) !== 0x5053474e) throw new SceneError(`${name}: not a .spz file (the magic is not NGSP)`);
  const version = h.getUint32(4, true), count = h.getUint32(8, true), degree = h.getUint8(12), bits = h.getUint8(13);
  if (attributes ? version !== 2 && version !== 3 : version !== 4) throw new SceneError(`${name}: .spz version ${version} is not read here`);
  if (degree > kRestPerDegree.length - 1) throw new SceneError(`${name}: SH degree ${degree}`);
  const dim = (degree + 1) ** 2 - 1, per = 3 * (degree + 1) ** 2;
  const sizes = [9, 1, 3, 3, version >= 3 ? 4 : 3, 3 * dim].map((b) => b * count);
  if (!attributes) {
    if (!zstd) throw new SceneError(`${name}: .spz version 4 (zstd) needs a zstd decoder here`);
    const streams = h.getUint8(15), table = h.getUint32(16, true);
    const parts = [];
    let offset = table + 16 * streams, entry = table;
    for (const size of sizes) {
      if (size === 0 && streams !== sizes.length) continue;
      const compressed = Number(new DataView(buffer).getBigUint64(entry, true));
      parts.push(zstd(bytes.subarray(offset, offset + compressed)));
      offset += compressed;
      entry += 16;
    }
    const data = new Uint8Array(sizes.reduce((a, b) => a + b, 0));
    let at = 0;
    for (const part of parts) data.set(part, at), at += part.length;
    attributes = { data, start: 0 };
  }
  const starts = sizes.reduce((a, size) => [...a, a[a.length - 1] + size], [attributes.start]);
  const b = attributes.data;
  if (b.length < starts[6]) throw new SceneError(`${name}: truncated: ${count} splats need ${starts[6] - attributes.start} bytes`);
  const positions = new Float32Array(3 * count), colours = new Float32Array(per * count);
  const scale = 1 / (1 << bits);
  for (let s = 0; s < count; ++s) {
    for (let k = 0; k < 3; ++k) {
      const at = starts[0] + 9 * s + 3 * k;
      positions[3 * s + k] = (((b[at] | (b[at + 1] << 8) | (b[at + 2] << 16)) << 8) >> 8) * scale;
      colours[per * s + k] = (b[starts[2] + 3 * s + k] / 255 - 0.5) / 0.15;
    }
    for (let k = 0; k < dim; ++k)
      for (let c = 0; c < 3; ++c) colours[per * s + 3 + c * dim + k] = (b[starts[5] + 3 * dim * s + 3 * k + c] - 128) / 128;
  }
  return { count, degree, positions, colours };
}

/** A scene from a file's name and bytes: .ply or .spz (options: readSpz's). */
export async function readScene(name, buffer, options = {}) {
  if (/\.ply$/i.test(name)) return readPly(buffer, name);
  if (/\.spz$/i.test(name)) return readSpz(buffer, name, options);
  throw new SceneError(`${name}: not a .ply or .spz file`);
}
