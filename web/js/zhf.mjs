// zhf for JavaScript: rotation of real spherical-harmonic (SH) vectors in a WebAssembly module, for
// browsers and Node. zhf's SIMD128 module where the engine runs SIMD128, its scalar one elsewhere;
// both are zhf::dispatch behind the C API of web/include/zhf/web/zhf_web.h.
//
// Conventions (docs/conventions.md): real orthonormal SH, index l(l+1)+m; order N = N bands = N^2
// coefficients; a rotation is 9 numbers, row-major, mapping v to R v, given in the axes of the
// convention named (default "zhf"; "3dgs" for 3D Gaussian Splatting data) and applied to
// coefficients in that convention; the result holds the coefficients of f(R^T w).
//
// Every call checks its arguments first and throws a TypeError (a wrong type or length) or a
// RangeError (a value out of range: an order, a degree, NaN, a matrix that is not a rotation) whose
// message names the function and the argument; a call that throws leaves every output unchanged.

// A module of one function returning a v128 constant: valid only where SIMD128 is.
const kSimdProbe = new Uint8Array([0, 97, 115, 109, 1, 0, 0, 0, 1, 5, 1, 96, 0, 1, 123, 3, 2, 1, 0, 10, 22, 1, 20, 0, 253, 12,
  0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 11]);
const kModuleFiles = { simd128: "zhf_simd128.wasm", generic: "zhf_generic.wasm" };

/** Whether this engine runs WebAssembly SIMD128 (load() then takes the "simd128" module). */
export function simdSupported() {
  return WebAssembly.validate(kSimdProbe);
}

async function moduleBytes(url) {
  if (url.protocol === "file:") {
    const { readFile } = await import("node:fs/promises");
    return readFile(url);
  }
  const response = await fetch(url);
  if (!response.ok) throw new Error(`zhf.load: ${url}: ${response.status} ${response.statusText}`);
  return response.arrayBuffer();
}

/**
 * Loads zhf's WebAssembly module. options.isa: "simd128" or "generic" (default: simd128 where the
 * engine runs it); options.module: the module's bytes or a compiled WebAssembly.Module (default:
 * the file beside this one, read from disk in Node and fetched in a browser).
 */
export async function load(options = {}) {
  const isa = options.isa ?? (simdSupported() ? "simd128" : "generic");
  if (!Object.hasOwn(kModuleFiles, isa)) throw new RangeError(`zhf.load: isa: '${String(isa)}' is not simd128 or generic`);
  let module = options.module;
  if (module === undefined) module = await moduleBytes(new URL(kModuleFiles[isa], import.meta.url));
  if (!(module instanceof WebAssembly.Module)) module = await WebAssembly.compile(module);
  let memory = null;
  const view = () => new DataView(memory.buffer);
  // The module's imports: the WASI calls its C++ library names (an empty environment; an exit
  // stops the call that made it) and Emscripten's growth notice.
  const imports = {
    env: { emscripten_notify_memory_growth() {} },
    wasi_snapshot_preview1: {
      environ_sizes_get(count, size) {
        view().setUint32(count, 0, true);
        view().setUint32(size, 0, true);
        return 0;
      },
      environ_get() {
        return 0;
      },
      proc_exit(code) {
        throw new Error(`zhf: the WebAssembly module stopped (exit ${code})`);
      },
    },
  };
  const instance = await WebAssembly.instantiate(module, imports);
  memory = instance.exports.memory;
  instance.exports._initialize();
  return new Zhf(instance.exports);
}

const kTypes = { f32: Float32Array, f64: Float64Array };

function kindOf(array) {
  if (array instanceof Float32Array) return "f32";
  if (array instanceof Float64Array) return "f64";
  return null;
}

/** An array inside the module's memory: the calls read and write it in place, without copies. */
export class WasmArray {
  #zhf;
  #pointer;
  /** @internal */
  constructor(zhf, kind, length, pointer) {
    this.#zhf = zhf;
    this.kind = kind;
    this.length = length;
    this.#pointer = pointer;
  }
  /** A view of the values (made anew on each read: the module's memory may have grown). */
  get array() {
    if (!this.#pointer) throw new TypeError("zhf.WasmArray: used after free()");
    return new kTypes[this.kind](this.#zhf.memory.buffer, this.#pointer, this.length);
  }
  /** @internal */
  get pointer() {
    if (!this.#pointer) throw new TypeError("zhf.WasmArray: used after free()");
    return this.#pointer;
  }
  free() {
    if (this.#pointer) this.#zhf.exports.zhf_web_free(this.#pointer);
    this.#pointer = 0;
  }
}

function cString(memory, pointer) {
  const bytes = new Uint8Array(memory.buffer, pointer);
  return new TextDecoder().decode(bytes.subarray(0, bytes.indexOf(0)));
}

export class Zhf {
  #scratch = new Map();  // role -> { pointer, bytes }: staging areas, grown as calls need

  /** @internal */
  constructor(exports) {
    this.exports = exports;
    this.memory = exports.memory;
    /** "simd128" or "generic": the module loaded. */
    this.isa = cString(this.memory, exports.zhf_web_isa());
    /** The largest order rotate and rotateEach take, and the largest degree rotateSplats takes. */
    this.maxOrder = exports.zhf_web_max_order();
    this.maxSplatDegree = exports.zhf_web_max_splat_degree();
    /** The conventions' names (runtime/conventions.h). */
    this.conventions = Array.from({ length: exports.zhf_web_convention_count() }, (_, k) =>
      cString(this.memory, exports.zhf_web_convention_name(k)));
  }

  /** An array of `length` values of kind "f32" or "f64" inside the module (free() it when done). */
  allocate(kind, length) {
    if (!Object.hasOwn(kTypes, kind)) throw new TypeError(`zhf.allocate: kind: '${String(kind)}' is not f32 or f64`);
    if (!Number.isSafeInteger(length) || length < 0) throw new RangeError(`zhf.allocate: length: ${length} is not a count`);
    const pointer = this.#alloc("zhf.allocate", "length", length * kTypes[kind].BYTES_PER_ELEMENT);
    return new WasmArray(this, kind, length, pointer);
  }

  /** The rotation matrix (9 numbers, row-major) of a quaternion of any nonzero length. order: "wxyz" (default) or "xyzw". */
  rotationFromQuaternion(quaternion, { order = "wxyz" } = {}) {
    const fn = "zhf.rotationFromQuaternion";
    const q = Float64Array.from(numbers(fn, "quaternion", quaternion, 4));
    if (order === "xyzw") q.set([q[3], q[0], q[1], q[2]]);
    else if (order !== "wxyz") throw new RangeError(`${fn}: order: '${String(order)}' is not wxyz or xyzw`);
    return this.#call(fn, [{ value: q, kind: "f64" }, { value: new Float64Array(9), kind: "f64", output: true }],
      ([qp, out]) => this.exports.zhf_web_rotation_from_quaternion(qp, out))[1];
  }

  /** A rotation in the convention's axes, for its coefficients, as zhf's kernels (and the WGSL ones) take it. */
  rotationInZhfTerms(rotation, { convention = "zhf" } = {}) {
    const fn = "zhf.rotationInZhfTerms";
    const c = this.#convention(fn, convention);
    const r = numbers(fn, "rotation", rotation, 9);
    return this.#call(fn, [{ value: r, kind: "f64" }, { value: new Float64Array(9), kind: "f64", output: true }],
      ([rp, out]) => this.exports.zhf_web_rotation_in_zhf_terms(c, rp, out))[1];
  }

  /**
   * Rotates every vector of `coefficients` (Float32Array, Float64Array or a WasmArray: count
   * vectors of order^2 values) by one rotation. Returns `out` (default: a new array).
   */
  rotate(rotation, coefficients, { order, convention = "zhf", out } = {}) {
    const fn = "zhf.rotate";
    this.#order(fn, order);
    const c = this.#convention(fn, convention);
    const r = numbers(fn, "rotation", rotation, 9);
    const { kind, length } = floats(fn, "coefficients", coefficients);
    const count = vectors(fn, "coefficients", length, order * order, `order ${order}`);
    return this.#call(fn, [{ value: r, kind: "f64" }, { value: coefficients, kind }, output(fn, out, coefficients, kind, length)],
      ([rp, inp, outp]) => this.exports[`zhf_web_rotate_${kind}`](order, c, rp, count, inp, outp))[2];
  }

  /**
   * Rotates vector v of `coefficients` by rotation v of `rotations` (9 numbers each, row-major,
   * in any array of numbers; converted to the coefficients' type). Returns `out`.
   */
  rotateEach(rotations, coefficients, { order, convention = "zhf", out } = {}) {
    const fn = "zhf.rotateEach";
    this.#order(fn, order);
    const c = this.#convention(fn, convention);
    const { kind, length } = floats(fn, "coefficients", coefficients);
    const count = vectors(fn, "coefficients", length, order * order, `order ${order}`);
    const r = numbers(fn, "rotations", rotations, 9 * count, kTypes[kind]);
    return this.#call(fn, [{ value: r, kind }, { value: coefficients, kind }, output(fn, out, coefficients, kind, length)],
      ([rp, inp, outp]) => this.exports[`zhf_web_rotate_each_${kind}`](order, c, count, rp, inp, outp))[2];
  }

  /**
   * Rotates the colour SH of 3D Gaussian Splatting splats (a Float32Array or f32 WasmArray) in the
   * .ply's layout, 3 (degree + 1)^2 values a splat: band 0's R, G, B, then bands 1.. of R, of G and
   * of B. The rotation is in the scene's axes (convention "3dgs", the default). Returns `out`;
   * `out` may be `splats` (in place).
   */
  rotateSplats(rotation, splats, { degree, convention = "3dgs", out } = {}) {
    const fn = "zhf.rotateSplats";
    if (!Number.isInteger(degree) || degree < 0 || degree > this.maxSplatDegree)
      throw new RangeError(`${fn}: degree: ${String(degree)} is not an integer 0..${this.maxSplatDegree}`);
    const c = this.#convention(fn, convention);
    const r = numbers(fn, "rotation", rotation, 9);
    const { kind, length } = floats(fn, "splats", splats);
    if (kind !== "f32") throw new TypeError(`${fn}: splats: a Float32Array or an f32 WasmArray`);
    const count = vectors(fn, "splats", length, 3 * (degree + 1) ** 2, `degree ${degree}`);
    return this.#call(fn, [{ value: r, kind: "f64" }, { value: splats, kind }, output(fn, out, splats, kind, length)],
      ([rp, inp, outp]) => this.exports.zhf_web_rotate_splats_f32(degree, c, rp, count, inp, outp))[2];
  }

  #order(fn, order) {
    if (!Number.isInteger(order) || order < 1 || order > this.maxOrder)
      throw new RangeError(`${fn}: order: ${String(order)} is not an integer 1..${this.maxOrder}`);
  }

  #convention(fn, name) {
    const index = this.conventions.indexOf(name);
    if (index < 0) throw new RangeError(`${fn}: convention: '${String(name)}' is not one of ${this.conventions.join(", ")}`);
    return index;
  }

  #alloc(fn, what, bytes) {
    const pointer = bytes <= 0xffffffff ? this.exports.zhf_web_alloc(bytes) : 0;
    if (!pointer) throw new RangeError(`${fn}: ${what}: ${bytes} bytes do not fit in the module's memory`);
    return pointer;
  }

  // A staging area of at least `bytes` for one role of a call.
  #stage(fn, role, bytes) {
    const held = this.#scratch.get(role);
    if (held && held.bytes >= bytes) return held.pointer;
    if (held) this.exports.zhf_web_free(held.pointer);
    this.#scratch.delete(role);
    const pointer = this.#alloc(fn, role, Math.max(bytes, 64));
    this.#scratch.set(role, { pointer, bytes: Math.max(bytes, 64) });
    return pointer;
  }

  // Runs call(pointers) on args ({value, kind, output}): a WasmArray in place, an argument that is
  // an earlier one's own array in that one's staging area, any other array staged (inputs copied
  // in once every area is held, since a growing memory moves its views); the outputs are copied
  // back only when the call succeeded. Returns the values.
  #call(fn, args, call) {
    const pointers = [];
    args.forEach((a, k) => {
      const earlier = args.findIndex((b) => b.value === a.value);
      if (a.value instanceof WasmArray) pointers.push(a.value.pointer);
      else if (earlier < k) pointers.push(pointers[earlier]);
      else pointers.push(this.#stage(fn, `argument ${k}`, a.value.byteLength));
    });
    args.forEach((a, k) => {
      if (!a.output && !(a.value instanceof WasmArray)) copyIn(this.memory, a, pointers[k]);
    });
    if (call(pointers) !== 0) throw new RangeError(`${fn}: ${cString(this.memory, this.exports.zhf_web_error())}`);
    args.forEach((a, k) => {
      if (a.output && !(a.value instanceof WasmArray)) copyOut(this.memory, a, pointers[k]);
    });
    return args.map((a) => a.value);
  }
}

function copyIn(memory, a, pointer) {
  new kTypes[a.kind](memory.buffer, pointer, a.value.length).set(a.value);
}

function copyOut(memory, a, pointer) {
  a.value.set(new kTypes[a.kind](memory.buffer, pointer, a.value.length));
}

// A float array's kind and length (typed arrays and WasmArrays), or a TypeError naming it.
function floats(fn, name, value) {
  if (value instanceof WasmArray) return { kind: value.kind, length: value.length };
  const kind = kindOf(value);
  if (!kind) throw new TypeError(`${fn}: ${name}: a Float32Array, a Float64Array or a WasmArray`);
  return { kind, length: value.length };
}

function vectors(fn, name, length, per, what) {
  if (length % per !== 0) throw new TypeError(`${fn}: ${name}: length ${length} is not a multiple of ${per} (${what})`);
  return length / per;
}

// `length` numbers from any array-like, as a new typed array of `Type` (default Float64Array).
function numbers(fn, name, value, length, Type = Float64Array) {
  if (value === null || typeof value !== "object" || typeof value.length !== "number")
    throw new TypeError(`${fn}: ${name}: an array of ${length} numbers`);
  if (value.length !== length) throw new TypeError(`${fn}: ${name}: ${value.length} numbers, not ${length}`);
  if (value instanceof Type) return value;
  const out = new Type(length);
  for (let k = 0; k < length; ++k) {
    if (typeof value[k] !== "number") throw new TypeError(`${fn}: ${name}[${k}]: not a number`);
    out[k] = value[k];
  }
  return out;
}

// The output argument: `out` checked against the input, or a new array; an output that is the
// input's own array is written in place.
function output(fn, out, input, kind, length) {
  if (out === undefined) return { value: new kTypes[kind](length), kind, output: true };
  const outKind = out instanceof WasmArray ? out.kind : kindOf(out);
  if (outKind !== kind || out.length !== length)
    throw new TypeError(`${fn}: out: a ${kTypes[kind].name} (or ${kind} WasmArray) of length ${length}, as the input`);
  return { value: out, kind, output: true };
}
