// glTF 2.0 binary (.glb) with the Khronos extension KHR_gaussian_splatting: a 12-byte header
// (magic "glTF", version 2, file length; uint32), a JSON chunk and a BIN chunk (each: length,
// type, data padded to 4 bytes). The splats are one POINTS primitive whose attributes are
// accessors into the BIN chunk:
//   POSITION                          VEC3 float
//   KHR_gaussian_splatting:ROTATION   VEC4 x y z w: float, or signed byte/short normalized
//   KHR_gaussian_splatting:SCALE      VEC3 linear (exp of the .ply's log-scales): float, or
//                                     unsigned byte/short, plain or normalized
//   KHR_gaussian_splatting:OPACITY    SCALAR in [0, 1] (sigmoid of the .ply's logit): float, or
//                                     unsigned byte/short normalized
//   KHR_gaussian_splatting:SH_DEGREE_l_COEF_n   VEC3 float, RGB of the coefficient m = n - l,
//                                     the 3DGS tools' SH (same basis and signs as the .ply)
// glTF's axes are y up, z forward, x left; the 3DGS tools' .ply is x right, y down, z forward:
// the scene turned half a turn about z. zhf turns it at the edge as a rotation of the scene
// (positions' x and y negated, the quaternion multiplied on the left by the half turn,
// SH coefficients of odd m negated), as @playcanvas/splat-transform does, so the two read each
// other's files alike. The node that places the mesh may carry a transform: translation,
// rotation and uniform scale are applied on reading (splats come out in the scene's space);
// anything else is refused. Written: float attributes, one region each, kernel "ellipse",
// colour space "srgb_rec709_display" (3DGS training's); the colour space read is not carried.
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <limits>
#include <optional>
#include <vector>

#include "format_io.h"
#include "scene_io.h"
#include "splat_math.h"
#include "zhf/io/errors.h"
#include "zhf/io/limits.h"
#include "zhf/io/json.h"
#include "zhf/runtime/rotation.h"
#include "zhf/splat/limits.h"

namespace zhf::splat {
namespace {

using io::InputError;
using io::json::Field;

constexpr std::uint32_t kGlbMagic = 0x46546c67, kJsonChunk = 0x4e4f534a, kBinChunk = 0x004e4942;
constexpr std::uint64_t kGlbHeaderBytes = 12, kChunkHeaderBytes = 8;
constexpr int kFloat = 5126, kByte = 5120, kUnsignedByte = 5121, kShort = 5122, kUnsignedShort = 5123;
constexpr const char* kExtension = "KHR_gaussian_splatting";
constexpr std::uint64_t kSubBlock = 4096;  // splats read per attribute at a time: bounded memory

int component_bytes(int type) { return type == kFloat ? 4 : type == kShort || type == kUnsignedShort ? 2 : 1; }

// The attributes in the canonical record's terms. Kinds in the order zhf writes them.
enum class Kind { kPosition, kRotation, kScale, kOpacity, kSh };
struct AttributeSpec {
  Kind kind;
  int components;  // VEC3, VEC4, SCALAR
  int coefficient; // SH: k in l (l + 1) + m, 0 for f_dc
};

std::string sh_name(int l, int n) { return std::string(kExtension) + ":SH_DEGREE_" + std::to_string(l) + "_COEF_" + std::to_string(n); }
const char* type_name(int components) { return components == 1 ? "SCALAR" : components == 3 ? "VEC3" : "VEC4"; }

// Names in write order for a scene of SH degree `degree`.
std::vector<std::pair<std::string, AttributeSpec>> attribute_names(int degree) {
  const std::string k = std::string(kExtension) + ":";
  std::vector<std::pair<std::string, AttributeSpec>> names = {{"POSITION", {Kind::kPosition, 3, 0}},
                                                              {k + "ROTATION", {Kind::kRotation, 4, 0}},
                                                              {k + "SCALE", {Kind::kScale, 3, 0}},
                                                              {k + "OPACITY", {Kind::kOpacity, 1, 0}}};
  for (int l = 0; l <= degree; ++l)
    for (int n = 0; n <= 2 * l; ++n) names.push_back({sh_name(l, n), {Kind::kSh, 3, l * l + n}});
  return names;
}

// Allowed (component type, normalized) per kind, from the extension's table.
bool allowed(Kind kind, int type, bool normalized) {
  switch (kind) {
    case Kind::kPosition:
    case Kind::kSh: return type == kFloat && !normalized;
    case Kind::kRotation: return (type == kFloat && !normalized) || ((type == kByte || type == kShort) && normalized);
    case Kind::kScale: return (type == kFloat && !normalized) || type == kUnsignedByte || type == kUnsignedShort;
    case Kind::kOpacity: return (type == kFloat && !normalized) || ((type == kUnsignedByte || type == kUnsignedShort) && normalized);
  }
  return false;
}

double component(const unsigned char* at, int type, bool normalized) {
  switch (type) {
    case kFloat: return get_float(at);
    case kByte: return std::max(static_cast<std::int8_t>(at[0]) / 127.0, -1.0);
    case kUnsignedByte: return normalized ? at[0] / 255.0 : at[0];
    case kShort: {
      std::int16_t s;
      std::memcpy(&s, at, sizeof s);
      return std::max(s / 32767.0, -1.0);
    }
    default: {
      std::uint16_t u;
      std::memcpy(&u, at, sizeof u);
      return normalized ? u / 65535.0 : u;
    }
  }
}

// The half turn about z between glTF's axes and the .ply's, on a canonical record in place.
// to_gltf: q -> h q; back: q -> h^-1 q (h = the quaternion k), so a round trip is exact.
void turn_half_about_z(double* v, const Canonical& c, bool to_gltf) {
  v[Canonical::kPosition] = -v[Canonical::kPosition];
  v[Canonical::kPosition + 1] = -v[Canonical::kPosition + 1];
  double* q = v + c.rotation();
  const double w = q[0], x = q[1], y = q[2], z = q[3];
  if (to_gltf) {
    q[0] = -z, q[1] = -y, q[2] = x, q[3] = w;
  } else {
    q[0] = z, q[1] = y, q[2] = -x, q[3] = -w;
  }
  const std::array<double, kMaxRestPerChannel>& sign = half_turn_signs(Axis::kZ);
  const int per_channel = c.rest / 3;
  for (int ch = 0; ch < 3; ++ch)
    for (int k = 0; k < per_channel; ++k) v[Canonical::kRest + ch * per_channel + k] *= sign[k];
}

struct Attribute {
  std::string name;
  AttributeSpec spec;
  int type = kFloat;
  bool normalized = false;
  std::uint64_t offset = 0, stride = 0, element = 0;  // in the file
  std::vector<unsigned char> bytes;
};

// 4x4 affine matrices, row-major, for the node hierarchy.
using Affine = std::array<double, 16>;
constexpr Affine kIdentity = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1};

Affine multiply(const Affine& a, const Affine& b) {
  Affine out{};
  for (int i = 0; i < 4; ++i)
    for (int j = 0; j < 4; ++j)
      for (int k = 0; k < 4; ++k) out[4 * i + j] += a[4 * i + k] * b[4 * k + j];
  return out;
}

// A node's own transform: "matrix" (column-major) or translation * rotation (x y z w) * scale.
Affine local_transform(const Field& node) {
  if (std::optional<Field> matrix = node.find("matrix")) {
    if (node.find("translation") || node.find("rotation") || node.find("scale")) node.fail("has both a matrix and translation/rotation/scale");
    const std::vector<Field> m = matrix->items(16);
    Affine a{};
    for (int col = 0; col < 4; ++col)
      for (int row = 0; row < 4; ++row) a[4 * row + col] = m[4 * col + row].number();
    if (a[12] != 0 || a[13] != 0 || a[14] != 0 || a[15] != 1) matrix->fail("last row is not 0 0 0 1");
    return a;
  }
  double t[3] = {0, 0, 0}, q[4] = {0, 0, 0, 1}, s[3] = {1, 1, 1};
  if (std::optional<Field> f = node.find("translation")) {
    const std::vector<Field> v = f->items(3);
    for (int i = 0; i < 3; ++i) t[i] = v[i].number();
  }
  if (std::optional<Field> f = node.find("rotation")) {
    const std::vector<Field> v = f->items(4);
    for (int i = 0; i < 4; ++i) q[i] = v[i].number(-1, 1);
    const double norm = std::sqrt(q[0] * q[0] + q[1] * q[1] + q[2] * q[2] + q[3] * q[3]);
    if (std::abs(norm - 1) > runtime::tolerance::kRotationDefect) f->fail("is not a unit quaternion (norm " + runtime::format_number(norm) + ")");
  }
  if (std::optional<Field> f = node.find("scale")) {
    const std::vector<Field> v = f->items(3);
    for (int i = 0; i < 3; ++i) s[i] = v[i].number();
  }
  runtime::Matrix3 r{};
  runtime::rotation_from_quaternion(q[3], q[0], q[1], q[2], r);  // glTF stores x y z w
  Affine a = kIdentity;
  for (int i = 0; i < 3; ++i) {
    for (int j = 0; j < 3; ++j) a[4 * i + j] = r[3 * i + j] * s[j];
    a[4 * i + 3] = t[i];
  }
  return a;
}

class GlbReader : public SceneReader {
 public:
  explicit GlbReader(const std::string& path) : path_(path), file_(open_input(path)) {
    const std::uint64_t size = regular_file_size(path, "a .glb is read by offsets into it");
    unsigned char header[kGlbHeaderBytes + kChunkHeaderBytes];
    if (size < sizeof header) throw InputError(path + ": " + std::to_string(size) + " bytes: too short for a .glb header");
    fill(0, header, sizeof header);
    if (get_uint32(header) != kGlbMagic) throw InputError(path + ": not a .glb (no \"glTF\" magic)");
    if (get_uint32(header + 4) != 2) throw InputError(path + ": .glb version " + std::to_string(get_uint32(header + 4)) + "; zhf reads version 2");
    if (get_uint32(header + 8) != size)
      throw InputError(path + ": the header says " + std::to_string(get_uint32(header + 8)) + " bytes, the file has " + std::to_string(size));
    const std::uint64_t json_bytes = get_uint32(header + 12);
    if (get_uint32(header + 16) != kJsonChunk) throw InputError(path + ": the first chunk is not JSON");
    if (json_bytes > splat::kMaxGlbJsonBytes)
      throw InputError(path + ": JSON chunk of " + std::to_string(json_bytes) + " bytes; at most " + std::to_string(splat::kMaxGlbJsonBytes));
    if (json_bytes > size - sizeof header) throw InputError(path + ": the JSON chunk runs past the end of the file");
    std::string text(json_bytes, '\0');
    fill(sizeof header, reinterpret_cast<unsigned char*>(text.data()), json_bytes);
    // Chunks after the JSON: the first may be BIN (the buffer); others are ignored, as glTF says.
    std::uint64_t at = sizeof header + json_bytes, bin_at = 0, bin_bytes = 0;
    for (int chunk = 1; at < size; ++chunk) {
      if (chunk > splat::kMaxGlbChunks) throw InputError(path + ": more than " + std::to_string(splat::kMaxGlbChunks) + " chunks");
      if (size - at < kChunkHeaderBytes) throw InputError(path + ": chunk " + std::to_string(chunk) + ": truncated header");
      unsigned char chunk_header[kChunkHeaderBytes];
      fill(at, chunk_header, sizeof chunk_header);
      const std::uint64_t bytes = get_uint32(chunk_header);
      if (bytes > size - at - kChunkHeaderBytes) throw InputError(path + ": chunk " + std::to_string(chunk) + " runs past the end of the file");
      if (chunk == 1 && get_uint32(chunk_header + 4) == kBinChunk) bin_at = at + kChunkHeaderBytes, bin_bytes = bytes;
      at += kChunkHeaderBytes + bytes;
    }
    io::json::Limits limits;
    limits.max_depth = kMaxGlbJsonDepth;
    limits.max_values = kMaxGlbJsonValues;
    const io::json::Json json = io::json::parse(text, path + ": JSON chunk", limits);
    interpret(Field(json, path), bin_at, bin_bytes);
  }

  void read(std::uint64_t first, std::uint64_t count, double* records) override {
    const Canonical c(degree_);
    for (std::uint64_t done = 0; done < count;) {
      const std::uint64_t n = std::min(kSubBlock, count - done);
      for (Attribute& a : attributes_) {
        a.bytes.resize((n - 1) * a.stride + a.element);
        fill(a.offset + (first + done) * a.stride, a.bytes.data(), a.bytes.size());
      }
      for (std::uint64_t s = 0; s < n; ++s) decode(first + done + s, s, records + (done + s) * c.size(), c);
      done += n;
    }
  }

  void finish() override {}  // the header's length is the file's: nothing follows

 private:
  void fill(std::uint64_t offset, unsigned char* to, std::uint64_t bytes) {
    file_.seekg(std::streamoff(offset));
    file_.read(reinterpret_cast<char*>(to), std::streamsize(bytes));
    if (std::uint64_t(file_.gcount()) != bytes) throw InputError(path_ + ": truncated (the file shrank)");
  }

  void interpret(const Field& root, std::uint64_t bin_at, std::uint64_t bin_bytes) {
    const Field asset = root.member("asset");
    const std::string& version = asset.member("version").string();
    if (version.rfind("2.", 0) != 0) asset.member("version").fail("glTF " + io::excerpt(version) + "; zhf reads 2.x");
    if (std::optional<Field> required = root.find("extensionsRequired"))
      for (const Field& e : required->items(0, kMaxGltfRequiredExtensions))
        if (e.string() != kExtension) e.fail("requires " + io::excerpt(e.string()) + ", which zhf does not read");
    // The one splat primitive.
    int mesh_index = -1;
    std::optional<Field> primitive;
    if (std::optional<Field> meshes = root.find("meshes")) {
      const std::vector<Field> list = meshes->items(0, splat::kMaxGlbObjects);
      for (std::size_t m = 0; m < list.size(); ++m)
        for (const Field& p : list[m].member("primitives").items(1, splat::kMaxGlbObjects)) {
          std::optional<Field> extensions = p.find("extensions");
          if (!extensions || !extensions->find(kExtension)) continue;
          if (primitive) p.fail("a second splat primitive; zhf reads files with one");
          primitive = p;
          mesh_index = int(m);
        }
    }
    if (!primitive) throw InputError(path_ + ": no mesh primitive with " + kExtension);
    const Field extension = primitive->member("extensions").member(kExtension);
    if (extension.member("kernel").string() != "ellipse")
      extension.member("kernel").fail("'" + io::excerpt(extension.member("kernel").string()) + "'; zhf reads the \"ellipse\" kernel");
    extension.member("colorSpace").string();
    if (!primitive->find("mode") || primitive->member("mode").integer(0, 6) != 0) primitive->fail("mode is not POINTS (0)");
    if (primitive->find("indices")) primitive->member("indices").fail("indexed splats are not read");

    // Attributes: the required ones, SH degrees complete from 0 up, nothing unknown of the extension's.
    const Field attributes = primitive->member("attributes");
    attributes.expect(io::json::Kind::kObject);
    degree_ = 0;
    while (degree_ < 3 && attributes.find(sh_name(degree_ + 1, 0))) ++degree_;
    const auto names = attribute_names(degree_);
    for (const auto& [key, value] : attributes.value().items()) {
      if (key.rfind(std::string(kExtension) + ":", 0) != 0) continue;  // POSITION, COLOR_0, ...: glTF's own
      bool known = false;
      for (const auto& name : names) known = known || name.first == key;
      if (!known) attributes.member(key).fail("not an attribute of a degree-" + std::to_string(degree_) + " scene");
    }
    const std::vector<Field> accessors = root.member("accessors").items(1, splat::kMaxGlbObjects);
    const std::vector<Field> views = root.member("bufferViews").items(1, splat::kMaxGlbObjects);
    const std::vector<Field> buffers = root.member("buffers").items(1, splat::kMaxGlbObjects);
    std::optional<std::uint64_t> count;
    for (const auto& [name, spec] : names) {
      std::optional<Field> index = attributes.find(name);
      if (!index) attributes.fail("no " + name + (spec.kind == Kind::kSh ? " (SH degrees are complete or absent)" : ""));
      const Field accessor = accessors[std::size_t(index->integer(0, int(accessors.size()) - 1))];
      Attribute a;
      a.name = name;
      a.spec = spec;
      a.type = accessor.member("componentType").integer(kByte, kFloat);
      a.normalized = accessor.find("normalized") && accessor.member("normalized").boolean();
      if (!allowed(spec.kind, a.type, a.normalized))
        accessor.member("componentType").fail(std::to_string(a.type) + (a.normalized ? " normalized" : "") + " is not allowed for " + name);
      if (accessor.member("type").string() != type_name(spec.components))
        accessor.member("type").fail("must be " + std::string(type_name(spec.components)) + " for " + name);
      if (accessor.find("sparse")) accessor.member("sparse").fail("sparse accessors are not read");
      const std::uint64_t n = std::uint64_t(accessor.member("count").integer(1LL, (long long)io::kMaxPlyVertices));
      if (count && n != *count) accessor.member("count").fail(std::to_string(n) + " for " + name + ", " + std::to_string(*count) + " for POSITION");
      count = n;
      const Field view = views[std::size_t(accessor.member("bufferView").integer(0, int(views.size()) - 1))];
      const long long buffer = view.member("buffer").integer(0LL, (long long)buffers.size() - 1);
      if (buffer != 0 || buffers[0].find("uri") || bin_bytes == 0)
        view.member("buffer").fail("not the .glb's own BIN chunk (external buffers are not read)");
      const std::uint64_t buffer_bytes = std::uint64_t(buffers[0].member("byteLength").integer(1LL, (long long)bin_bytes));
      const std::uint64_t view_offset = view.find("byteOffset") ? std::uint64_t(view.member("byteOffset").integer(0LL, (long long)buffer_bytes)) : 0;
      const std::uint64_t view_bytes = std::uint64_t(view.member("byteLength").integer(1LL, (long long)(buffer_bytes - view_offset)));
      a.element = std::uint64_t(spec.components) * component_bytes(a.type);
      a.stride = view.find("byteStride") ? std::uint64_t(view.member("byteStride").integer(kMinGltfByteStride, kMaxGltfByteStride)) : a.element;
      if (a.stride < a.element || a.stride % 4 != 0) view.member("byteStride").fail("must be a multiple of 4 of at least " + std::to_string(a.element));
      const std::uint64_t offset = accessor.find("byteOffset") ? std::uint64_t(accessor.member("byteOffset").integer(0LL, (long long)view_bytes)) : 0;
      if ((n - 1) * a.stride + a.element > view_bytes - offset)
        accessor.fail(std::to_string(n) + " elements of " + name + " run past the end of their buffer view");
      a.offset = bin_at + view_offset + offset;
      attributes_.push_back(std::move(a));
    }
    splats_ = *count;
    node_transform(root, mesh_index);
  }

  // The global transform of the node that places the mesh, as SplatMath (identity: none).
  void node_transform(const Field& root, int mesh_index) {
    std::optional<Field> nodes_field = root.find("nodes");
    if (!nodes_field) return;
    const std::vector<Field> nodes = nodes_field->items(0, splat::kMaxGlbObjects);
    std::vector<int> parent(nodes.size(), -1);
    int placing = -1;
    for (std::size_t i = 0; i < nodes.size(); ++i) {
      if (std::optional<Field> mesh = nodes[i].find("mesh"); mesh && mesh->integer(0, splat::kMaxGlbObjects) == mesh_index) {
        if (placing >= 0) mesh->fail("a second node places the splat mesh; zhf reads one instance");
        placing = int(i);
      }
      if (std::optional<Field> children = nodes[i].find("children"))
        for (const Field& child : children->items(0, nodes.size())) {
          const int k = child.integer(0, int(nodes.size()) - 1);
          if (parent[k] >= 0 || k == int(i)) child.fail("node " + std::to_string(k) + " has two parents");
          parent[k] = int(i);
        }
    }
    if (placing < 0) return;
    Affine global = kIdentity;
    std::size_t steps = 0;
    for (int k = placing; k >= 0; k = parent[k]) {
      if (++steps > nodes.size()) nodes_field->fail("the nodes' children form a cycle");
      global = multiply(local_transform(nodes[k]), global);
    }
    if (global == kIdentity) return;
    // Translation, then a rotation times a uniform scale.
    const Field& where = nodes[placing];
    std::array<double, 3> lengths{};
    for (int j = 0; j < 3; ++j)
      lengths[j] = std::sqrt(global[j] * global[j] + global[4 + j] * global[4 + j] + global[8 + j] * global[8 + j]);
    const double scale = (lengths[0] + lengths[1] + lengths[2]) / 3;
    if (!(scale > 0) || !std::isfinite(scale)) where.fail("its transform has no finite positive scale");
    for (double length : lengths)
      if (std::abs(length - scale) > runtime::tolerance::kRotationDefect * scale)
        where.fail("its transform scales unevenly (" + runtime::format_number(lengths[0]) + ", " + runtime::format_number(lengths[1]) + ", " +
                   runtime::format_number(lengths[2]) + "); splats keep their shape under a uniform scale only");
    double r[9];
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j) r[3 * i + j] = global[4 * i + j] / scale;
    const runtime::RotationCheck check = runtime::validate_rotation(r);
    if (!check.ok) where.fail("its transform: " + check.message);
    runtime::nearest_rotation(r, r);
    for (int i = 0; i < 9; ++i) transform_.r[i] = r[i];
    transform_.scale = scale;
    transform_.translation = {global[3], global[7], global[11]};
    layout_ = layout_of(canonical_header(degree_, splats_), "canonical record");
    math_.emplace(layout_, transform_);
  }

  void decode(std::uint64_t splat, std::uint64_t s, double* v, const Canonical& c) {
    bool nonfinite = false;
    for (const Attribute& a : attributes_) {
      const unsigned char* at = a.bytes.data() + s * a.stride;
      double x[4];
      for (int i = 0; i < a.spec.components; ++i) {
        x[i] = component(at + i * component_bytes(a.type), a.type, a.normalized);
        if (!std::isfinite(x[i]) && !keep_nonfinite_) throw InputError(where(path_, splat, a.name) + " is " + runtime::format_number(x[i]));
        nonfinite = nonfinite || !std::isfinite(x[i]);
      }
      switch (a.spec.kind) {
        case Kind::kPosition:
          for (int i = 0; i < 3; ++i) v[Canonical::kPosition + i] = x[i], v[Canonical::kNormal + i] = 0;
          break;
        case Kind::kRotation:
          if (x[0] == 0 && x[1] == 0 && x[2] == 0 && x[3] == 0) throw InputError(where(path_, splat, a.name) + " is a zero quaternion");
          v[c.rotation()] = x[3];
          for (int i = 0; i < 3; ++i) v[c.rotation() + 1 + i] = x[i];
          break;
        case Kind::kScale:
          for (int i = 0; i < 3; ++i) {
            if (x[i] < 0 && std::isfinite(x[i])) throw InputError(where(path_, splat, a.name) + " is " + runtime::format_number(x[i]) + ", below 0");
            // Zero reads as a quarter of the least float: its log stays finite and writes back as 0.
            v[c.scale() + i] = std::log(std::max(x[i], double(std::numeric_limits<float>::denorm_min()) / 4));
          }
          break;
        case Kind::kOpacity:
          if (std::isfinite(x[0]) && (x[0] < 0 || x[0] > 1)) throw InputError(where(path_, splat, a.name) + " is " + runtime::format_number(x[0]) + ", outside [0, 1]");
          v[c.opacity()] = opacity_of_alpha(x[0]);
          break;
        case Kind::kSh:
          for (int ch = 0; ch < 3; ++ch)
            v[a.spec.coefficient == 0 ? Canonical::kDc + ch : Canonical::kRest + ch * (c.rest / 3) + a.spec.coefficient - 1] = x[ch];
          break;
      }
    }
    // A kept non-finite value may map to a finite one (a scale of -inf to the least log-scale):
    // the opacity, which nothing turns, marks the splat for the caller to leave out.
    if (nonfinite) v[c.opacity()] = std::numeric_limits<double>::quiet_NaN();
    if (math_) math_->apply(v);
    turn_half_about_z(v, c, false);
  }

  std::string path_;
  std::ifstream file_;
  std::vector<Attribute> attributes_;
  Transform transform_;
  Layout layout_;
  std::optional<SplatMath> math_;  // the node's transform, when it is not the identity
};

class GlbWriter : public SceneWriter {
 public:
  GlbWriter(io::PendingFile& out, int degree, std::uint64_t splats) : out_(out), c_(degree), splats_(splats), names_(attribute_names(degree)) {
    if (splats == 0) throw InputError("a .glb holds at least one splat (glTF accessors are not empty)");
    std::uint64_t bin = 0;
    for (const auto& name : names_) {
      regions_.push_back(bin);
      bin += splats * 4 * std::uint64_t(name.second.components);
    }
    bin_bytes_ = bin;
    const std::uint64_t most = (std::numeric_limits<std::uint32_t>::max() - 4096) / (bin / splats);
    if (splats > most)
      throw InputError(std::to_string(splats) + " splats of SH degree " + std::to_string(degree) + " do not fit a .glb (4 GiB); at most " + std::to_string(most));
    // The JSON's room, with the widest position bounds a float prints as.
    json_bytes_ = (json(std::array<float, 6>{}, true).size() + 3) / 4 * 4;
    bin_at_ = kGlbHeaderBytes + kChunkHeaderBytes + json_bytes_ + kChunkHeaderBytes;
  }

  void write(std::uint64_t count, const double* records) override {
    std::vector<std::vector<unsigned char>> regions(names_.size());
    for (std::size_t a = 0; a < names_.size(); ++a) regions[a].resize(count * 4 * names_[a].second.components);
    std::vector<double> v(c_.size());
    for (std::uint64_t s = 0; s < count; ++s) {
      std::copy(records + s * c_.size(), records + (s + 1) * c_.size(), v.begin());
      turn_half_about_z(v.data(), c_, true);
      for (std::size_t a = 0; a < names_.size(); ++a) {
        const AttributeSpec& spec = names_[a].second;
        unsigned char* at = regions[a].data() + s * 4 * spec.components;
        double x[4];
        switch (spec.kind) {
          case Kind::kPosition: std::copy(v.begin(), v.begin() + 3, x); break;
          case Kind::kRotation: {
            const double* q = &v[c_.rotation()];
            const double norm = std::sqrt(q[0] * q[0] + q[1] * q[1] + q[2] * q[2] + q[3] * q[3]);
            x[3] = q[0] / norm;
            for (int i = 0; i < 3; ++i) x[i] = q[1 + i] / norm;
            break;
          }
          case Kind::kScale:
            for (int i = 0; i < 3; ++i) x[i] = std::exp(v[c_.scale() + i]);
            break;
          case Kind::kOpacity: x[0] = sigmoid(v[c_.opacity()]); break;
          case Kind::kSh:
            for (int ch = 0; ch < 3; ++ch)
              x[ch] = v[spec.coefficient == 0 ? Canonical::kDc + ch : Canonical::kRest + ch * (c_.rest / 3) + spec.coefficient - 1];
            break;
        }
        for (int i = 0; i < spec.components; ++i) {
          const float value = clamped_float(x[i], clamped_);
          put_float(at + 4 * i, value);
          if (spec.kind == Kind::kSh) stored(spec.coefficient == 0 ? 0 : Canonical::band(spec.coefficient - 1), x[i], value);
          if (spec.kind == Kind::kPosition) {
            bounds_[i] = std::min(bounds_[i], value);
            bounds_[3 + i] = std::max(bounds_[3 + i], value);
          }
        }
      }
    }
    for (std::size_t a = 0; a < names_.size(); ++a)
      out_.write_at(bin_at_ + regions_[a] + written_ * 4 * names_[a].second.components, reinterpret_cast<const char*>(regions[a].data()), regions[a].size());
    written_ += count;
  }

  void finish() override {
    std::string text = json(bounds_, false);
    text.resize(json_bytes_, ' ');
    std::vector<unsigned char> head(kGlbHeaderBytes + kChunkHeaderBytes);
    put_uint32(&head[0], kGlbMagic);
    put_uint32(&head[4], 2);
    put_uint32(&head[8], std::uint32_t(bin_at_ + bin_bytes_));
    put_uint32(&head[12], std::uint32_t(json_bytes_));
    put_uint32(&head[16], kJsonChunk);
    out_.write_at(0, reinterpret_cast<const char*>(head.data()), head.size());
    out_.write_at(head.size(), text.data(), text.size());
    unsigned char bin_header[kChunkHeaderBytes];
    put_uint32(bin_header, std::uint32_t(bin_bytes_));
    put_uint32(bin_header + 4, kBinChunk);
    out_.write_at(bin_at_ - kChunkHeaderBytes, reinterpret_cast<const char*>(bin_header), sizeof bin_header);
  }


 private:
  // The glTF JSON; widest: every bound printed as the longest float text.
  std::string json(const std::array<float, 6>& bounds, bool widest) const {
    auto number = [&](float x) {
      char text[32];  // nine digits: the float exactly; the least normal float prints longest
      std::snprintf(text, sizeof text, "%.9g", widest ? -double(std::numeric_limits<float>::min()) : double(x));
      return std::string(text);
    };
    std::string attributes, views, accessors;
    for (std::size_t a = 0; a < names_.size(); ++a) {
      const std::string i = std::to_string(a);
      const AttributeSpec& spec = names_[a].second;
      attributes += (a ? "," : "") + ("\"" + names_[a].first + "\":" + i);
      views += (a ? "," : "") + ("{\"buffer\":0,\"byteOffset\":" + std::to_string(regions_[a]) + ",\"byteLength\":" +
                                 std::to_string(splats_ * 4 * spec.components) + ",\"target\":34962}");
      accessors += (a ? "," : "") + ("{\"bufferView\":" + i + ",\"componentType\":5126,\"count\":" + std::to_string(splats_) +
                                     ",\"type\":\"" + type_name(spec.components) + "\"");
      if (spec.kind == Kind::kPosition)
        accessors += ",\"min\":[" + number(bounds[0]) + "," + number(bounds[1]) + "," + number(bounds[2]) + "],\"max\":[" +
                     number(bounds[3]) + "," + number(bounds[4]) + "," + number(bounds[5]) + "]";
      accessors += "}";
    }
    return "{\"asset\":{\"version\":\"2.0\",\"generator\":\"zhf splat\"},\"extensionsUsed\":[\"" + std::string(kExtension) +
           "\"],\"scene\":0,\"scenes\":[{\"nodes\":[0]}],\"nodes\":[{\"mesh\":0}],\"meshes\":[{\"primitives\":[{\"attributes\":{" +
           attributes + "},\"mode\":0,\"extensions\":{\"" + kExtension +
           "\":{\"kernel\":\"ellipse\",\"colorSpace\":\"srgb_rec709_display\"}}}]}],\"buffers\":[{\"byteLength\":" +
           std::to_string(bin_bytes_) + "}],\"bufferViews\":[" + views + "],\"accessors\":[" + accessors + "]}";
  }

  io::PendingFile& out_;
  Canonical c_;
  std::uint64_t splats_;
  std::vector<std::pair<std::string, AttributeSpec>> names_;
  std::vector<std::uint64_t> regions_;  // each attribute's offset in the BIN chunk
  std::uint64_t bin_bytes_ = 0, json_bytes_ = 0, bin_at_ = 0, written_ = 0;
  std::array<float, 6> bounds_{INFINITY, INFINITY, INFINITY, -INFINITY, -INFINITY, -INFINITY};
};

}  // namespace

std::unique_ptr<SceneReader> open_glb_reader(const std::string& path, const Formats&) { return std::make_unique<GlbReader>(path); }
std::unique_ptr<SceneWriter> open_glb_writer(io::PendingFile& out, const WriteOptions& options) {
  return std::make_unique<GlbWriter>(out, options.degree, options.splats);
}

}  // namespace zhf::splat
