#include "fbx_binary_writer.hpp"

#include <Eigen/Geometry>
#include <zlib.h>

#include <stdexcept>

namespace fissure::test {
namespace {

template <class T>
std::string bytes_of(T value) {
  std::string out;
  put(out, value, false);  // FBX is little-endian throughout
  return out;
}

void put_field(std::string& out, std::uint64_t value, int width) {
  if (width == 8) put(out, value, false);
  else put(out, static_cast<std::uint32_t>(value), false);
}

void patch_field(std::string& out, std::size_t at, std::uint64_t value, int width) {
  std::string field;
  put_field(field, value, width);
  out.replace(at, field.size(), field);
}

std::string zlib_stream(const std::string& plain) {
  uLongf length = compressBound(static_cast<uLong>(plain.size()));
  std::string out(length, '\0');
  if (compress2(reinterpret_cast<Bytef*>(out.data()), &length, reinterpret_cast<const Bytef*>(plain.data()),
                static_cast<uLong>(plain.size()), Z_BEST_COMPRESSION) != Z_OK) {
    throw std::runtime_error("zlib compress2 failed");
  }
  out.resize(length);
  return out;
}

void write_record(std::string& out, const FbxRecord& r, int width, FbxFields* fields) {
  const std::size_t start = out.size();
  put_field(out, 0, width);  // end offset, patched below
  put_field(out, r.properties().size(), width);
  const std::size_t property_bytes_at = out.size();
  put_field(out, 0, width);  // property list bytes, patched below
  if (r.name().size() > 255) throw std::invalid_argument("FBX record names are at most 255 bytes");
  out += static_cast<char>(r.name().size());
  out += r.name();
  if (fields) {
    fields->end_offsets.push_back(start);
    fields->property_counts.push_back(start + width);
    fields->property_bytes.push_back(property_bytes_at);
    fields->name_lengths.push_back(property_bytes_at + width);
  }
  const std::size_t properties_at = out.size();
  for (const FbxRecord::Property& p : r.properties()) {
    out += p.type;
    if (fields && p.array) {
      fields->array_counts.push_back(out.size());
      fields->array_encodings.push_back(out.size() + 4);
      fields->array_stored_lengths.push_back(out.size() + 8);
      if (p.payload[4] == 1) fields->compressed_stored_lengths.push_back(out.size() + 8);
    }
    if (fields && (p.type == 'S' || p.type == 'R')) fields->string_lengths.push_back(out.size());
    out += p.payload;
  }
  patch_field(out, property_bytes_at, out.size() - properties_at, width);
  if (!r.children().empty()) {
    for (const FbxRecord& c : r.children()) write_record(out, c, width, fields);
    out.append(3 * static_cast<std::size_t>(width) + 1, '\0');  // the null record closing them
  }
  patch_field(out, start, out.size(), width);
}

}  // namespace

FbxRecord& FbxRecord::int16(std::int16_t v) { m_properties.push_back({'Y', bytes_of(v)}); return *this; }
FbxRecord& FbxRecord::boolean(bool v) { m_properties.push_back({'C', std::string(1, v ? 'T' : 'F')}); return *this; }
FbxRecord& FbxRecord::int32(std::int32_t v) { m_properties.push_back({'I', bytes_of(v)}); return *this; }
FbxRecord& FbxRecord::float32(float v) { m_properties.push_back({'F', bytes_of(v)}); return *this; }
FbxRecord& FbxRecord::float64(double v) { m_properties.push_back({'D', bytes_of(v)}); return *this; }
FbxRecord& FbxRecord::int64(std::int64_t v) { m_properties.push_back({'L', bytes_of(v)}); return *this; }
FbxRecord& FbxRecord::string(const std::string& v) {
  m_properties.push_back({'S', bytes_of(static_cast<std::uint32_t>(v.size())) + v});
  return *this;
}
FbxRecord& FbxRecord::raw(const std::string& v) {
  m_properties.push_back({'R', bytes_of(static_cast<std::uint32_t>(v.size())) + v});
  return *this;
}

template <class T>
FbxRecord& FbxRecord::array(char type, const std::vector<T>& values, bool compressed) {
  std::string plain;
  for (const T& v : values) put(plain, v, false);
  const std::string stored = compressed ? zlib_stream(plain) : plain;
  m_properties.push_back({type,
                          bytes_of(static_cast<std::uint32_t>(values.size())) + bytes_of(std::uint32_t{compressed ? 1u : 0u}) +
                              bytes_of(static_cast<std::uint32_t>(stored.size())) + stored,
                          true});
  return *this;
}

FbxRecord& FbxRecord::float32_array(const std::vector<float>& v, bool compressed) { return array('f', v, compressed); }
FbxRecord& FbxRecord::float64_array(const std::vector<double>& v, bool compressed) { return array('d', v, compressed); }
FbxRecord& FbxRecord::int32_array(const std::vector<std::int32_t>& v, bool compressed) { return array('i', v, compressed); }
FbxRecord& FbxRecord::int64_array(const std::vector<std::int64_t>& v, bool compressed) { return array('l', v, compressed); }
FbxRecord& FbxRecord::child(FbxRecord record) {
  m_children.push_back(std::move(record));
  return *this;
}

std::string write_binary_fbx(const std::vector<FbxRecord>& records, std::uint32_t version, FbxFields* fields) {
  const int width = version >= 7500 ? 8 : 4;
  if (fields) {
    *fields = FbxFields();
    fields->width = width;
  }
  std::string out("Kaydara FBX Binary  \0\x1a\0", 23);
  put(out, version, false);
  for (const FbxRecord& r : records) write_record(out, r, width, fields);
  out.append(3 * static_cast<std::size_t>(width) + 1, '\0');  // the null record ending the top level
  // The footer the FBX SDK writes (readers ignore it): an id, zero padding to 16 bytes, the
  // version, 120 zero bytes and a fixed magic.
  out += std::string("\xfa\xbc\xab\x09\xd0\xc8\xd4\x66\xb1\x76\xfb\x83\x1c\xf7\x26\x7e", 16);
  out.append((16 - out.size() % 16) % 16 + 4, '\0');
  put(out, version, false);
  out.append(120, '\0');
  out += std::string("\xf8\x5a\x8c\x6a\xde\xf5\xd9\x7e\xec\xe9\x0c\xe3\x75\x8f\x29\x0b", 16);
  return out;
}

namespace {

// A Properties70 entry: name, type, label, flags, then its values.
FbxRecord property70(const std::string& name, const std::string& type, const std::string& label,
                     const std::string& flags = "") {
  FbxRecord p("P");
  p.string(name).string(type).string(label).string(flags);
  return p;
}

}  // namespace

std::string binary_fbx_of(const Polygons& polygons, const Eigen::Vector3d& translation, std::uint32_t version,
                          FbxFields* fields) {
  constexpr std::int64_t kGeometryId = 1001, kModelId = 2002;
  std::vector<double> vertices;
  for (Eigen::Index v = 0; v < polygons.vertices.rows(); ++v)
    for (int k = 0; k < 3; ++k) vertices.push_back(polygons.vertices(v, k));
  std::vector<std::int32_t> indices;
  std::vector<double> normals;  // one per polygon vertex (ByPolygonVertex, Direct)
  for (const auto& face : polygons.faces) {
    const Eigen::Vector3d a = polygons.vertices.row(face[0]), b = polygons.vertices.row(face[1]),
                          c = polygons.vertices.row(face[2]);
    const Eigen::Vector3d n = (b - a).cross(c - a).normalized();
    for (std::size_t k = 0; k < face.size(); ++k) {
      indices.push_back(k + 1 == face.size() ? -face[k] - 1 : face[k]);
      for (int j = 0; j < 3; ++j) normals.push_back(n[j]);
    }
  }

  std::vector<FbxRecord> top;
  top.push_back(FbxRecord("FBXHeaderExtension")
                    .child(FbxRecord("FBXHeaderVersion").int32(1003))
                    .child(FbxRecord("FBXVersion").int32(7400))
                    .child(FbxRecord("Creator").string("Fissure tests")));
  top.push_back(FbxRecord("FileId").raw(std::string("\x28\xb3\x2a\xeb\xb6\x24\xcc\xc2\xbf\xc8\xb0\x2a\xa9\x2b\xfc\xf1", 16)));
  // Every type code the scene itself does not use, in a record readers skip.
  top.push_back(FbxRecord("FissureTypeSampler")
                    .int16(-7)
                    .float32(0.25f)
                    .int64(-1234567890123LL)
                    .boolean(true)
                    .float32_array({1.0f, 2.0f, 3.0f})
                    .int64_array({5, -6, 7}, true));
  top.push_back(FbxRecord("GlobalSettings")
                    .child(FbxRecord("Version").int32(1000))
                    .child(FbxRecord("Properties70")
                               .child(property70("UpAxis", "int", "Integer").int32(1))
                               .child(property70("UnitScaleFactor", "double", "Number").float64(1.0))));
  FbxRecord layer_normals("LayerElementNormal");
  layer_normals.int32(0)
      .child(FbxRecord("Version").int32(101))
      .child(FbxRecord("Name").string(""))
      .child(FbxRecord("MappingInformationType").string("ByPolygonVertex"))
      .child(FbxRecord("ReferenceInformationType").string("Direct"))
      .child(FbxRecord("Normals").float64_array(normals));
  FbxRecord geometry("Geometry");
  geometry.int64(kGeometryId)
      .string(std::string("Solid\0\x01Geometry", 15))
      .string("Mesh")
      .child(FbxRecord("Vertices").float64_array(vertices))
      .child(FbxRecord("PolygonVertexIndex").int32_array(indices, true))
      .child(FbxRecord("GeometryVersion").int32(124))
      .child(std::move(layer_normals))
      .child(FbxRecord("Layer").int32(0).child(FbxRecord("Version").int32(100)).child(
          FbxRecord("LayerElement")
              .child(FbxRecord("Type").string("LayerElementNormal"))
              .child(FbxRecord("TypedIndex").int32(0))));
  FbxRecord model("Model");
  model.int64(kModelId)
      .string(std::string("Solid\0\x01Model", 12))
      .string("Mesh")
      .child(FbxRecord("Version").int32(232))
      .child(FbxRecord("Properties70").child(property70("Lcl Translation", "Lcl Translation", "", "A")
                                                 .float64(translation.x())
                                                 .float64(translation.y())
                                                 .float64(translation.z())))
      .child(FbxRecord("Shading").boolean(true))
      .child(FbxRecord("Culling").string("CullingOff"));
  top.push_back(FbxRecord("Objects").child(std::move(geometry)).child(std::move(model)));
  top.push_back(FbxRecord("Connections")
                    .child(FbxRecord("C").string("OO").int64(kGeometryId).int64(kModelId))
                    .child(FbxRecord("C").string("OO").int64(kModelId).int64(0)));
  return write_binary_fbx(top, version, fields);
}

}  // namespace fissure::test
