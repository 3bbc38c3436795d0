// The binary hierarchy format (layout in hierarchy_io.hpp): plain arrays written and read in
// the host's byte order, which must be little-endian.
#include "hierarchy/hierarchy_io.hpp"

#include <climits>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <limits>
#include <vector>

#include "common/error.hpp"
#include "common/file_output.hpp"

namespace progsim {
namespace {

#if defined(__BYTE_ORDER__)
static_assert(__BYTE_ORDER__ == __ORDER_LITTLE_ENDIAN__, "the hierarchy format is little-endian");
#endif
static_assert(sizeof(int) == 4 && std::numeric_limits<double>::is_iec559,
              "the hierarchy format stores int32 ids and IEEE doubles");
static_assert(sizeof(FaceCorners) == 3 * sizeof(int), "FaceCorners must be three packed ids");

constexpr char kMagic[6] = {'P', 'S', 'H', 'I', 'E', 'R'};
constexpr std::int32_t kVersion = 2;
/// Reads back as 0x01020304 only in the byte order it was written in.
constexpr std::int32_t kByteOrderMarker = 0x01020304;

// Bytes an item takes at least in the file, to bound counts by the remaining size.
constexpr std::int64_t kCountBytes = sizeof(std::int64_t);
constexpr std::int64_t kVertexBytes = 3 * sizeof(double);
constexpr std::int64_t kFaceBytes = 3 * sizeof(std::int32_t);
constexpr std::int64_t kIdBytes = sizeof(std::int32_t);
constexpr std::int64_t kLevelBytes = 3 * kCountBytes;
constexpr std::int64_t kAnchorBytes = sizeof(std::int32_t) + 3 * sizeof(double);
constexpr std::int64_t kRecordBytes = 2 * kIdBytes + 2 * kCountBytes;

// ---- Writing ----

template <class T>
void put(std::ostream& out, const T& value) {
  out.write(reinterpret_cast<const char*>(&value), sizeof(T));
}

/// n items of type T from `data`.
template <class T>
void put_array(std::ostream& out, const T* data, std::size_t n) {
  if (n > 0) out.write(reinterpret_cast<const char*>(data), n * sizeof(T));
}

void put_count(std::ostream& out, std::size_t n) {
  put(out, static_cast<std::int64_t>(n));
}

/// A count and the items of `items`.
template <class T>
void put_vector(std::ostream& out, const std::vector<T>& items) {
  put_count(out, items.size());
  put_array(out, items.data(), items.size());
}

void put_header(std::ostream& out) {
  out.write(kMagic, sizeof(kMagic));
  put(out, kVersion);
  put(out, kByteOrderMarker);
}

void put_level(std::ostream& out, const HierarchyLevel& level) {
  put_count(out, level.rest.vertices.rows());
  put_array(out, level.rest.vertices.data(), level.rest.vertices.size());
  put_count(out, level.rest.faces.rows());
  put_array(out, level.rest.faces.data(), level.rest.faces.size());
  put_vector(out, level.input_vertex);
}

/// The anchors' faces, then their weights.
void put_anchors(std::ostream& out, const SurfaceAnchors& anchors) {
  std::vector<std::int32_t> faces;
  std::vector<double> weights;
  faces.reserve(anchors.size());
  weights.reserve(3 * anchors.size());
  for (const SurfaceAnchor& anchor : anchors) {
    faces.push_back(anchor.face);
    weights.insert(weights.end(), anchor.weights.data(), anchor.weights.data() + 3);
  }
  put_count(out, anchors.size());
  put_array(out, faces.data(), faces.size());
  put_array(out, weights.data(), weights.size());
}

void put_anchor_lists(std::ostream& out, const std::vector<SurfaceAnchors>& lists) {
  put_count(out, lists.size());
  for (const SurfaceAnchors& anchors : lists) put_anchors(out, anchors);
}

void put_record(std::ostream& out, const CollapseRecord& record) {
  put(out, static_cast<std::int32_t>(record.removed));
  put(out, static_cast<std::int32_t>(record.kept));
  put_vector(out, record.before);
  put_vector(out, record.after);
}

void put_batches(std::ostream& out, const std::vector<std::vector<std::vector<int>>>& levels) {
  put_count(out, levels.size());
  for (const std::vector<std::vector<int>>& batches : levels) {
    put_count(out, batches.size());
    for (const std::vector<int>& batch : batches) put_vector(out, batch);
  }
}

void put_hierarchy(std::ostream& out, const MeshHierarchy& hierarchy) {
  put_header(out);
  put_count(out, hierarchy.levels.size());
  for (const HierarchyLevel& level : hierarchy.levels) put_level(out, level);
  put_anchor_lists(out, hierarchy.to_next);
  put_anchor_lists(out, hierarchy.to_finest);
  put_count(out, hierarchy.collapses.size());
  for (const CollapseRecord& record : hierarchy.collapses) put_record(out, record);
  put_vector(out, hierarchy.first_collapse);
  put_batches(out, hierarchy.expansion_batches);
  put_vector(out, hierarchy.input_group);
}

// ---- Reading ----

/// A hierarchy file being read: every read is checked against the bytes that remain, and
/// every failure is an io_error naming the path.
class Reader {
 public:
  explicit Reader(const std::string& path) : path_(path) {
    std::error_code error;
    if (!std::filesystem::is_regular_file(path, error))
      fail(Status::io_error, path + ": no such file (or not a regular file)");
    const std::uintmax_t size = std::filesystem::file_size(path, error);
    in_.open(path, std::ios::binary);
    if (error || !in_) fail(Status::io_error, path + ": cannot open the file for reading");
    size_ = static_cast<std::int64_t>(size);
  }

  /// Throws io_error "<path>: <problem>".
  [[noreturn]] void corrupt(const std::string& problem) const {
    fail(Status::io_error, path_ + ": " + problem);
  }

  /// Reads n items of type T into `data`; `what` names them for the message.
  template <class T>
  void array(T* data, std::size_t n, const char* what) {
    const std::int64_t bytes = static_cast<std::int64_t>(n * sizeof(T));
    if (bytes > remaining())
      corrupt("truncated file: " + std::to_string(bytes) + " bytes needed for " + what +
              " at byte " + std::to_string(offset_) + ", but only " + std::to_string(remaining()) +
              " remain");
    if (n > 0 && !in_.read(reinterpret_cast<char*>(data), bytes))
      corrupt(std::string("read error at byte ") + std::to_string(offset_) + " (" + what + ")");
    offset_ += bytes;
  }

  template <class T>
  T value(const char* what) {
    T v;
    array(&v, 1, what);
    return v;
  }

  /// Reads a count of items taking at least `item_bytes` each: io_error if it is negative,
  /// above INT_MAX (ids are int) or more than the rest of the file can hold.
  std::size_t count(std::int64_t item_bytes, const char* what) {
    const std::int64_t n = value<std::int64_t>(what);
    if (n >= 0 && n <= remaining() / item_bytes && n <= INT_MAX) return static_cast<std::size_t>(n);
    corrupt("the file declares " + std::to_string(n) + " " + what + " at byte " +
            std::to_string(offset_ - kCountBytes) + ", not a count its remaining " +
            std::to_string(remaining()) + " bytes can hold (corrupt or truncated file)");
  }

  /// io_error if bytes remain after the hierarchy.
  void expect_end() const {
    if (remaining() == 0) return;
    corrupt(std::to_string(remaining()) + " unexpected bytes after the hierarchy at byte " +
            std::to_string(offset_));
  }

 private:
  std::int64_t remaining() const { return size_ - offset_; }

  std::string path_;
  std::ifstream in_;
  std::int64_t size_ = 0;
  std::int64_t offset_ = 0;
};

void read_header(Reader& in) {
  char magic[sizeof(kMagic)];
  in.array(magic, sizeof(magic), "the magic");
  if (std::memcmp(magic, kMagic, sizeof(kMagic)) != 0)
    in.corrupt("not a progsim hierarchy file (the magic is not \"PSHIER\")");
  const std::int32_t version = in.value<std::int32_t>("the format version");
  if (version != kVersion)
    in.corrupt("unsupported hierarchy format version " + std::to_string(version) +
               " (this build reads version " + std::to_string(kVersion) + ")");
  if (in.value<std::int32_t>("the byte-order marker") != kByteOrderMarker)
    in.corrupt("the byte-order marker is not 0x01020304 (written in another byte order?)");
}

/// A count and that many items of type T.
template <class T>
std::vector<T> read_vector(Reader& in, const char* what) {
  std::vector<T> items(in.count(sizeof(T), what));
  in.array(items.data(), items.size(), what);
  return items;
}

TriangleMesh read_mesh_arrays(Reader& in) {
  TriangleMesh mesh;
  mesh.vertices.resize(in.count(kVertexBytes, "level vertices"), 3);
  in.array(mesh.vertices.data(), mesh.vertices.size(), "level vertices");
  mesh.faces.resize(in.count(kFaceBytes, "level faces"), 3);
  in.array(mesh.faces.data(), mesh.faces.size(), "level faces");
  return mesh;
}

std::vector<HierarchyLevel> read_levels(Reader& in) {
  std::vector<HierarchyLevel> levels(in.count(kLevelBytes, "levels"));
  for (HierarchyLevel& level : levels) {
    level.rest = read_mesh_arrays(in);
    level.input_vertex = read_vector<int>(in, "input_vertex entries");
  }
  return levels;
}

SurfaceAnchors read_anchors(Reader& in) {
  const std::size_t n = in.count(kAnchorBytes, "anchors");
  std::vector<std::int32_t> faces(n);
  std::vector<double> weights(3 * n);
  in.array(faces.data(), n, "anchor faces");
  in.array(weights.data(), 3 * n, "anchor weights");
  SurfaceAnchors anchors(n);
  for (std::size_t i = 0; i < n; ++i) {
    anchors[i].face = faces[i];
    anchors[i].weights = Vec3(weights[3 * i], weights[3 * i + 1], weights[3 * i + 2]);
  }
  return anchors;
}

std::vector<SurfaceAnchors> read_anchor_lists(Reader& in) {
  std::vector<SurfaceAnchors> lists(in.count(kCountBytes, "anchor lists"));
  for (SurfaceAnchors& anchors : lists) anchors = read_anchors(in);
  return lists;
}

std::vector<CollapseRecord> read_records(Reader& in) {
  std::vector<CollapseRecord> records(in.count(kRecordBytes, "collapse records"));
  for (CollapseRecord& record : records) {
    record.removed = in.value<std::int32_t>("a removed vertex");
    record.kept = in.value<std::int32_t>("a kept vertex");
    record.before = read_vector<FaceCorners>(in, "faces before a collapse");
    record.after = read_vector<FaceCorners>(in, "faces after a collapse");
  }
  return records;
}

std::vector<std::vector<std::vector<int>>> read_batches(Reader& in) {
  std::vector<std::vector<std::vector<int>>> levels(in.count(kCountBytes, "batch levels"));
  for (std::vector<std::vector<int>>& batches : levels) {
    batches.resize(in.count(kCountBytes, "batches"));
    for (std::vector<int>& batch : batches) batch = read_vector<int>(in, "batch entries");
  }
  return levels;
}

MeshHierarchy read_hierarchy(Reader& in) {
  read_header(in);
  MeshHierarchy hierarchy;
  hierarchy.levels = read_levels(in);
  hierarchy.to_next = read_anchor_lists(in);
  hierarchy.to_finest = read_anchor_lists(in);
  hierarchy.collapses = read_records(in);
  hierarchy.first_collapse = read_vector<int>(in, "first_collapse entries");
  hierarchy.expansion_batches = read_batches(in);
  hierarchy.input_group = read_vector<int>(in, "input_group entries");
  in.expect_end();
  return hierarchy;
}

}  // namespace

void save_hierarchy(const MeshHierarchy& hierarchy, const std::string& path) {
  write_file_atomically(path, [&](std::ostream& out) { put_hierarchy(out, hierarchy); });
}

MeshHierarchy load_hierarchy(const std::string& path) {
  Reader in(path);
  MeshHierarchy hierarchy = read_hierarchy(in);
  try {
    check_hierarchy(hierarchy);
  } catch (const Error& e) {
    fail(e.status(), path + ": " + e.what());
  }
  return hierarchy;
}

}  // namespace progsim
