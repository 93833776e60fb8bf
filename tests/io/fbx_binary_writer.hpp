#pragma once
// Test-only writer of binary FBX (the layout assimp's FBXBinaryTokenizer.cpp reads and Blender
// documents): assimp 5.2.5 cannot re-read its own binary FBX export, so the import and its fuzz
// test need binary files written independently of assimp.
//
// A file is the 23-byte magic "Kaydara FBX Binary  \0\x1a\0", a uint32 version, then records:
// [end offset, property count, property list bytes] (uint32 before version 7500, uint64 from
// it), a name length byte, the name, the typed properties, then the nested records and a null
// record (all zero) closing them; a null record ends the top level, a footer follows.

#include "surface_files.hpp"

#include <cstdint>
#include <string>
#include <vector>

namespace fissure::test {

/// One record with its typed properties and nested records.
class FbxRecord {
public:
  explicit FbxRecord(std::string name) : m_name(std::move(name)) {}

  FbxRecord& int16(std::int16_t v);    // 'Y'
  FbxRecord& boolean(bool v);          // 'C'
  FbxRecord& int32(std::int32_t v);    // 'I'
  FbxRecord& float32(float v);         // 'F'
  FbxRecord& float64(double v);        // 'D'
  FbxRecord& int64(std::int64_t v);    // 'L'
  FbxRecord& string(const std::string& v);  // 'S' (may hold NUL, as "Name\0\x01Class" does)
  FbxRecord& raw(const std::string& v);     // 'R'
  /// Arrays 'f', 'd', 'i', 'l': encoding 0 stores the values, encoding 1 their zlib stream.
  FbxRecord& float32_array(const std::vector<float>& v, bool compressed = false);
  FbxRecord& float64_array(const std::vector<double>& v, bool compressed = false);
  FbxRecord& int32_array(const std::vector<std::int32_t>& v, bool compressed = false);
  FbxRecord& int64_array(const std::vector<std::int64_t>& v, bool compressed = false);
  FbxRecord& child(FbxRecord record);

  struct Property {
    char type;
    std::string payload;  // the bytes after the type code
    bool array = false;   // payload starts with count, encoding, stored length (uint32 each)
  };
  const std::string& name() const { return m_name; }
  const std::vector<Property>& properties() const { return m_properties; }
  const std::vector<FbxRecord>& children() const { return m_children; }

private:
  template <class T>
  FbxRecord& array(char type, const std::vector<T>& values, bool compressed);

  std::string m_name;
  std::vector<Property> m_properties;
  std::vector<FbxRecord> m_children;
};

/// Where the length and offset fields of a written file lie (byte positions), so a fuzzer can
/// aim at the fields readers trust to size their reads.
struct FbxFields {
  int width = 4;  // bytes of the record header fields: 4, or 8 from version 7500
  std::vector<std::size_t> end_offsets, property_counts, property_bytes, name_lengths;
  std::vector<std::size_t> array_counts, array_encodings, array_stored_lengths;  // uint32 each
  std::vector<std::size_t> compressed_stored_lengths;  // the stored length of encoding-1 arrays
  std::vector<std::size_t> string_lengths;             // 'S' and 'R' (uint32 each)
};

/// The file holding `records` at top level, in FBX `version` (7400: 32-bit record fields).
std::string write_binary_fbx(const std::vector<FbxRecord>& records, std::uint32_t version = 7400,
                             FbxFields* fields = nullptr);

/// A minimal FBX 7.4 scene with the polygons as one mesh, the way exporters lay it out:
/// FBXHeaderExtension (FBXVersion 7400), GlobalSettings, Objects holding a Geometry "Mesh"
/// (Vertices as doubles, PolygonVertexIndex with each polygon's last index stored as −(i+1),
/// a normal layer) and a Model moved by `translation` (Lcl Translation), and Connections "C"
/// "OO" geometry → model → root. PolygonVertexIndex is zlib-compressed (encoding 1), the other
/// arrays stored plain (encoding 0). A record of every other property type rides along at the
/// top level (ignored by readers) so that each type code is in the fuzzed file.
std::string binary_fbx_of(const Polygons& polygons, const Eigen::Vector3d& translation, std::uint32_t version = 7400,
                          FbxFields* fields = nullptr);

}  // namespace fissure::test
