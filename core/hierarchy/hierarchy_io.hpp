#pragma once
/// @file Saving and loading a MeshHierarchy in progsim's binary hierarchy format, so that a
/// hierarchy built once can be reused across runs.
///
/// Format (version 2), little-endian, every count a std::int64_t, ids int32, reals double:
/// the magic "PSHIER", the int32 version, the int32 byte-order marker 0x01020304; then the
/// levels (count; per level: vertex count and |V|·3 coordinates row by row, face count and
/// |F|·3 corners, input_vertex count and ids); to_next and to_finest (list count; per list:
/// anchor count, the anchors' faces, then their weights, 3 per anchor); the collapse records
/// (count; per record: removed, kept, then `before` and `after` as face count and 3 ids per
/// face); first_collapse (count and values); expansion_batches (level count; per level: batch
/// count; per batch: count and collapse indices); input_group (count and values). Nothing
/// follows.
#include <string>

#include "hierarchy/mesh_hierarchy.hpp"

namespace progsim {

/// Writes a hierarchy to `path` in progsim's binary hierarchy format (little-endian; magic
/// "PSHIER", format version, then levels, anchors, collapse records and batches). Throws
/// Error(io_error) naming the path when it cannot be written.
void save_hierarchy(const MeshHierarchy& hierarchy, const std::string& path);

/// Reads a hierarchy written by save_hierarchy. Throws Error(io_error) naming the path for a
/// missing/unreadable/truncated file, a wrong magic, an unsupported version, a count larger
/// than the rest of the file can hold or bytes after the end; then runs check_hierarchy, whose
/// Error(invalid_argument) for corrupted contents is rethrown with the path prefixed. Every
/// count is bounded by the remaining file size before anything is allocated, so a corrupt or
/// hostile file cannot make it allocate much more than the file's size.
MeshHierarchy load_hierarchy(const std::string& path);

}  // namespace progsim
