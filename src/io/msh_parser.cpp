#include "msh_parser.hpp"

#include "fissure/base/error.hpp"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstring>
#include <limits>
#include <set>

namespace fissure::io_detail {
namespace {

// Element types 1–31 of the gmsh manual (§10.1): nodes per element and dimension.
constexpr std::array<std::pair<int, int>, 32> kElementTypes{{
    {-1, -1}, {2, 1},  {3, 2},  {4, 2},  {4, 3},  {8, 3},  {6, 3},  {5, 3},  {3, 1},  {6, 2},  {9, 2},
    {10, 3},  {27, 3}, {18, 3}, {14, 3}, {1, 0},  {8, 2},  {20, 3}, {15, 3}, {13, 3}, {9, 2},  {10, 2},
    {12, 2},  {15, 2}, {15, 2}, {21, 2}, {4, 1},  {5, 1},  {6, 1},  {20, 3}, {35, 3}, {56, 3},
}};

// Tags must fit an int for gmsh and for us; node counts are bounded by the file size.
constexpr std::int64_t kMaxTag = std::numeric_limits<std::int32_t>::max();

class Reader {
public:
  Reader(const std::string& bytes, const std::string& name) : m_bytes(bytes), m_name(name) {}

  [[noreturn]] void fail(const std::string& what) const {
    throw IoError(m_name + ": corrupt MSH file: " + what + " (" + m_section + ", byte " + std::to_string(m_pos) + ")");
  }
  void section(const std::string& s) { m_section = s; }
  bool at_end() {
    skip_space();
    return m_pos >= m_bytes.size();
  }
  std::size_t remaining() const { return m_bytes.size() - m_pos; }

  void skip_space() {
    while (m_pos < m_bytes.size() && std::isspace(static_cast<unsigned char>(m_bytes[m_pos]))) ++m_pos;
  }
  std::string word() {
    skip_space();
    const std::size_t start = m_pos;
    while (m_pos < m_bytes.size() && !std::isspace(static_cast<unsigned char>(m_bytes[m_pos]))) ++m_pos;
    if (start == m_pos) fail("truncated: unexpected end of file");
    return m_bytes.substr(start, m_pos - start);
  }
  std::string rest_of_line() {
    const std::size_t start = m_pos;
    while (m_pos < m_bytes.size() && m_bytes[m_pos] != '\n') ++m_pos;
    return m_bytes.substr(start, m_pos - start);
  }
  template <class T>
  T number() {
    const std::string w = word();
    T value{};
    const char* first = w.data();
    const char* last = w.data() + w.size();
    auto [end, ec] = std::from_chars(first, last, value);
    if constexpr (std::is_floating_point_v<T>) {
      // Past double's range ("1e400", "1e-400"): what strtod gives (±inf, ±0), read through
      // long double, so that the caller's finiteness check names the node.
      if (ec == std::errc::result_out_of_range) {
        long double wide = 0;
        const auto wide_result = std::from_chars(first, last, wide);
        end = wide_result.ptr;
        if (wide_result.ec == std::errc::result_out_of_range) {  // beyond long double too
          const std::size_t e = w.find_first_of("eE");
          wide = e != std::string::npos && e + 1 < w.size() && w[e + 1] == '-' ? 0.0L : HUGE_VALL;
          if (w[0] == '-') wide = -wide;
        }
        value = static_cast<T>(wide);
        ec = std::errc();
      }
    }
    // Non-finite values ("nan", "inf") are returned: the caller knows which node holds them.
    if (ec != std::errc() || end != last) fail("'" + w.substr(0, 40) + "' is not a number");
    return value;
  }
  template <class T>
  T binary() {
    if (remaining() < sizeof(T)) fail("truncated: unexpected end of binary data");
    T value;
    std::memcpy(&value, m_bytes.data() + m_pos, sizeof(T));
    m_pos += sizeof(T);
    return value;
  }
  // Binary data starts right after the newline that ends the text before it: skip exactly that
  // one (a whitespace-skipping read could eat binary bytes that happen to be 0x09–0x0d or 0x20).
  void skip_newline() {
    if (m_pos < m_bytes.size() && m_bytes[m_pos] == '\r') ++m_pos;
    if (m_pos < m_bytes.size() && m_bytes[m_pos] == '\n') ++m_pos;
  }
  // After a binary block gmsh writes a newline before the $End marker.
  void expect_marker(const std::string& marker) {
    const std::string w = word();
    if (w != marker) fail("expected " + marker + ", found '" + w.substr(0, 40) + "'");
  }
  // Skips an unknown section up to its end marker.
  void skip_to(const std::string& marker) {
    const std::size_t at = m_bytes.find(marker, m_pos);
    if (at == std::string::npos) fail("no " + marker);
    m_pos = at + marker.size();
  }
  // A count read from the file must fit in the bytes left (each item takes ≥ min_bytes).
  std::int64_t count(std::int64_t value, std::size_t min_bytes, const char* what) {
    if (value < 0 || static_cast<std::uint64_t>(value) > remaining() / std::max<std::size_t>(min_bytes, 1)) {
      fail(value < 0 ? std::string(what) + " count " + std::to_string(value) + " is negative"
                     : "truncated: " + std::string(what) + " count " + std::to_string(value) + " needs more bytes than the file has left");
    }
    return value;
  }
  std::int64_t tag(std::int64_t value, const char* what) {
    if (value < 1 || value > kMaxTag) fail(std::string(what) + " tag " + std::to_string(value) + " is out of range");
    return value;
  }
  // A physical tag's sign is an orientation; −2³¹ has no positive counterpart.
  int physical_tag(int value) {
    if (value == std::numeric_limits<int>::min()) fail("physical tag " + std::to_string(value) + " is out of range");
    return std::abs(value);
  }

private:
  const std::string& m_bytes;
  const std::string& m_name;
  std::string m_section = "header";
  std::size_t m_pos = 0;
};

struct Entity {
  std::vector<int> physicals;
};

void read_physical_names(Reader& r, MshContent& c) {
  r.section("$PhysicalNames");
  const std::int64_t n = r.count(r.number<std::int64_t>(), 6, "physical name");
  for (std::int64_t i = 0; i < n; ++i) {
    const int dim = r.number<int>();
    const int tag = r.number<int>();
    if (dim < 0 || dim > 3) r.fail("physical group dimension " + std::to_string(dim));
    if (tag < 1) r.fail("physical group tag " + std::to_string(tag));
    r.skip_space();
    std::string line = r.rest_of_line();
    while (!line.empty() && (line.back() == '\r' || line.back() == ' ')) line.pop_back();
    if (line.size() < 2 || line.front() != '"' || line.back() != '"') r.fail("physical name is not quoted");
    c.physical_names[{dim, tag}] = line.substr(1, line.size() - 2);
  }
  r.expect_marker("$EndPhysicalNames");
}

void read_entities_41(Reader& r, bool binary, std::map<std::pair<int, int>, Entity>& entities) {
  r.section("$Entities");
  std::int64_t counts[4];
  for (auto& n : counts) n = binary ? static_cast<std::int64_t>(r.binary<std::uint64_t>()) : r.number<std::int64_t>();
  for (int dim = 0; dim < 4; ++dim) {
    r.count(counts[dim], binary ? 20 : 8, "entity");
    for (std::int64_t i = 0; i < counts[dim]; ++i) {
      const int tag = binary ? r.binary<int>() : r.number<int>();
      const int box = dim == 0 ? 3 : 6;
      for (int k = 0; k < box; ++k) binary ? (void)r.binary<double>() : (void)r.number<double>();
      const std::int64_t nphys =
          r.count(binary ? static_cast<std::int64_t>(r.binary<std::uint64_t>()) : r.number<std::int64_t>(), 2, "physical tag");
      Entity& e = entities[{dim, tag}];
      for (std::int64_t k = 0; k < nphys; ++k) {
        const int p = binary ? r.binary<int>() : r.number<int>();
        e.physicals.push_back(r.physical_tag(p));
      }
      if (dim > 0) {
        const std::int64_t nbound =
            r.count(binary ? static_cast<std::int64_t>(r.binary<std::uint64_t>()) : r.number<std::int64_t>(), 2, "bounding entity");
        for (std::int64_t k = 0; k < nbound; ++k) binary ? (void)r.binary<int>() : (void)r.number<int>();
      }
    }
  }
  r.expect_marker("$EndEntities");
}

void read_nodes_41(Reader& r, bool binary, MshContent& c) {
  r.section("$Nodes");
  auto size = [&] { return binary ? static_cast<std::int64_t>(r.binary<std::uint64_t>()) : r.number<std::int64_t>(); };
  const std::int64_t blocks = r.count(size(), 16, "node block");
  const std::int64_t total = r.count(size(), binary ? 32 : 8, "node");
  size();
  size();  // min and max tag
  std::int64_t seen = 0;
  for (std::int64_t b = 0; b < blocks; ++b) {
    const int dim = binary ? r.binary<int>() : r.number<int>();
    binary ? (void)r.binary<int>() : (void)r.number<int>();
    const int parametric = binary ? r.binary<int>() : r.number<int>();
    const std::int64_t n = r.count(size(), binary ? 32 : 8, "node");
    if (dim < 0 || dim > 3 || parametric < 0 || parametric > 1) r.fail("bad node block header");
    std::vector<std::int64_t> tags(static_cast<std::size_t>(n));
    for (auto& t : tags) t = r.tag(size(), "node");
    const int per_node = 3 + (parametric ? dim : 0);
    for (std::int64_t i = 0; i < n; ++i) {
      std::array<double, 3> xyz{};
      for (int k = 0; k < per_node; ++k) {
        const double v = binary ? r.binary<double>() : r.number<double>();
        if (!std::isfinite(v)) r.fail("node " + std::to_string(tags[static_cast<std::size_t>(i)]) + " has a non-finite coordinate");
        if (k < 3) xyz[static_cast<std::size_t>(k)] = v;
      }
      if (!c.nodes.emplace(tags[static_cast<std::size_t>(i)], xyz).second) {
        r.fail("node tag " + std::to_string(tags[static_cast<std::size_t>(i)]) + " appears twice");
      }
    }
    seen += n;
  }
  if (seen != total) r.fail("node blocks hold " + std::to_string(seen) + " nodes, the header says " + std::to_string(total));
  r.expect_marker("$EndNodes");
}

void read_elements_41(Reader& r, bool binary, const std::map<std::pair<int, int>, Entity>& entities, MshContent& c) {
  r.section("$Elements");
  auto size = [&] { return binary ? static_cast<std::int64_t>(r.binary<std::uint64_t>()) : r.number<std::int64_t>(); };
  const std::int64_t blocks = r.count(size(), 16, "element block");
  const std::int64_t total = r.count(size(), binary ? 16 : 4, "element");
  size();
  size();
  std::int64_t seen = 0;
  for (std::int64_t b = 0; b < blocks; ++b) {
    const int dim = binary ? r.binary<int>() : r.number<int>();
    const int entity = binary ? r.binary<int>() : r.number<int>();
    const int type = binary ? r.binary<int>() : r.number<int>();
    const std::int64_t n = r.count(size(), binary ? 16 : 4, "element");
    const int per = msh_nodes_per_element(type);
    if (per < 0) r.fail("unknown element type " + std::to_string(type));
    if (dim != msh_element_dimension(type)) r.fail("element block of dimension " + std::to_string(dim) + " holds type " + std::to_string(type));
    std::vector<int> physicals;
    if (const auto it = entities.find({dim, entity}); it != entities.end()) physicals = it->second.physicals;
    for (std::int64_t i = 0; i < n; ++i) {
      MshElement e;
      e.tag = r.tag(size(), "element");
      e.type = type;
      e.dimension = dim;
      e.entity = entity;
      e.physicals = physicals;
      e.nodes.resize(static_cast<std::size_t>(per));
      for (auto& v : e.nodes) v = r.tag(size(), "node");
      c.elements.push_back(std::move(e));
    }
    seen += n;
  }
  if (seen != total) r.fail("element blocks hold " + std::to_string(seen) + " elements, the header says " + std::to_string(total));
  r.expect_marker("$EndElements");
}

void read_nodes_22(Reader& r, bool binary, MshContent& c) {
  r.section("$Nodes");
  const std::int64_t n = r.count(r.number<std::int64_t>(), binary ? 28 : 8, "node");
  if (binary) r.skip_newline();
  for (std::int64_t i = 0; i < n; ++i) {
    const std::int64_t tag = r.tag(binary ? r.binary<int>() : r.number<std::int64_t>(), "node");
    std::array<double, 3> xyz{};
    for (double& v : xyz) {
      v = binary ? r.binary<double>() : r.number<double>();
      if (!std::isfinite(v)) r.fail("node " + std::to_string(tag) + " has a non-finite coordinate");
    }
    if (!c.nodes.emplace(tag, xyz).second) r.fail("node tag " + std::to_string(tag) + " appears twice");
  }
  r.expect_marker("$EndNodes");
}

void read_elements_22(Reader& r, bool binary, MshContent& c) {
  r.section("$Elements");
  const std::int64_t n = r.count(r.number<std::int64_t>(), binary ? 12 : 8, "element");
  auto add = [&](std::int64_t tag, int type, const std::vector<int>& tags, std::vector<std::int64_t> nodes) {
    MshElement e;
    e.tag = r.tag(tag, "element");
    e.type = type;
    e.dimension = msh_element_dimension(type);
    if (!tags.empty() && tags[0] != 0) e.physicals.push_back(r.physical_tag(tags[0]));
    e.entity = tags.size() > 1 ? tags[1] : 0;
    for (auto& v : nodes) v = r.tag(v, "node");
    e.nodes = std::move(nodes);
    c.elements.push_back(std::move(e));
  };
  if (!binary) {
    for (std::int64_t i = 0; i < n; ++i) {
      const std::int64_t tag = r.number<std::int64_t>();
      const int type = r.number<int>();
      const int per = msh_nodes_per_element(type);
      if (per < 0) r.fail("unknown element type " + std::to_string(type));
      const int ntags = r.number<int>();
      if (ntags < 0 || ntags > 64) r.fail("element " + std::to_string(tag) + " has " + std::to_string(ntags) + " tags");
      std::vector<int> tags(static_cast<std::size_t>(ntags));
      for (int& t : tags) t = r.number<int>();
      std::vector<std::int64_t> nodes(static_cast<std::size_t>(per));
      for (auto& v : nodes) v = r.number<std::int64_t>();
      add(tag, type, tags, std::move(nodes));
    }
  } else {
    r.skip_newline();
    std::int64_t done = 0;
    while (done < n) {
      const int type = r.binary<int>();
      const std::int64_t count = r.count(r.binary<int>(), 8, "element");
      const int ntags = r.binary<int>();
      const int per = msh_nodes_per_element(type);
      if (per < 0) r.fail("unknown element type " + std::to_string(type));
      if (ntags < 0 || ntags > 64 || count == 0 || done + count > n) r.fail("bad element block header");
      for (std::int64_t i = 0; i < count; ++i) {
        const std::int64_t tag = r.binary<int>();
        std::vector<int> tags(static_cast<std::size_t>(ntags));
        for (int& t : tags) t = r.binary<int>();
        std::vector<std::int64_t> nodes(static_cast<std::size_t>(per));
        for (auto& v : nodes) v = r.binary<int>();
        add(tag, type, tags, std::move(nodes));
      }
      done += count;
    }
  }
  r.expect_marker("$EndElements");
}

}  // namespace

int msh_nodes_per_element(int type) {
  return type >= 1 && type < static_cast<int>(kElementTypes.size()) ? kElementTypes[static_cast<std::size_t>(type)].first : -1;
}

int msh_element_dimension(int type) {
  return type >= 1 && type < static_cast<int>(kElementTypes.size()) ? kElementTypes[static_cast<std::size_t>(type)].second : -1;
}

MshContent parse_msh(const std::string& bytes, const std::string& name) {
  Reader r(bytes, name);
  MshContent c;
  if (r.at_end()) throw IoError(name + ": file is empty");
  if (r.word() != "$MeshFormat") throw IoError(name + ": not a gmsh MSH file (no $MeshFormat header)");
  const std::string version = r.word();
  if (version != "2.2" && version != "4.1") {
    throw IoError(name + ": unsupported MSH version '" + version.substr(0, 20) + "' (Fissure reads 2.2 and 4.1)");
  }
  c.version = version == "2.2" ? 2.2 : 4.1;
  const int file_type = r.number<int>();
  const int data_size = r.number<int>();
  if (file_type != 0 && file_type != 1) r.fail("file type " + std::to_string(file_type));
  if (data_size != 8) r.fail("data size " + std::to_string(data_size) + " (only 8 is supported)");
  c.binary = file_type == 1;
  if (c.binary) {
    r.rest_of_line();
    r.skip_newline();  // gmsh writes "\n" then the int 1
    if (r.binary<int>() != 1) r.fail("big-endian binary files are not supported");
  }
  r.expect_marker("$EndMeshFormat");

  std::map<std::pair<int, int>, Entity> entities;
  bool have_nodes = false, have_elements = false;
  while (!r.at_end()) {
    const std::string marker = r.word();
    if (marker.empty() || marker[0] != '$') r.fail("expected a section, found '" + marker.substr(0, 40) + "'");
    if (c.binary && c.version > 4) r.skip_newline();
    if (marker == "$PhysicalNames") {
      read_physical_names(r, c);
    } else if (marker == "$Entities" && c.version > 4) {
      read_entities_41(r, c.binary, entities);
    } else if (marker == "$Nodes") {
      if (have_nodes) r.fail("a second $Nodes section");
      if (c.version > 4) read_nodes_41(r, c.binary, c); else read_nodes_22(r, c.binary, c);
      have_nodes = true;
    } else if (marker == "$Elements") {
      if (have_elements) r.fail("a second $Elements section");
      if (c.version > 4) read_elements_41(r, c.binary, entities, c); else read_elements_22(r, c.binary, c);
      have_elements = true;
    } else if (marker == "$PartitionedEntities") {
      throw IoError(name + ": partitioned meshes are not supported (save the mesh unpartitioned)");
    } else {
      r.section(marker);
      r.skip_to("$End" + marker.substr(1));  // views, periodic links, comments
    }
  }
  if (!have_nodes || !have_elements) {
    throw IoError(name + ": truncated or corrupt MSH file (no " + std::string(have_nodes ? "$Elements" : "$Nodes") + " section)");
  }
  // Element tags are unique (they name the tets in every message), and every element's nodes exist.
  std::vector<std::int64_t> element_tags;
  element_tags.reserve(c.elements.size());
  for (const MshElement& e : c.elements) element_tags.push_back(e.tag);
  std::sort(element_tags.begin(), element_tags.end());
  const auto twice = std::adjacent_find(element_tags.begin(), element_tags.end());
  if (twice != element_tags.end()) {
    throw IoError(name + ": corrupt MSH file: element tag " + std::to_string(*twice) + " appears twice ($Elements)");
  }
  for (const MshElement& e : c.elements) {
    for (std::int64_t v : e.nodes) {
      if (!c.nodes.count(v)) {
        throw IoError(name + ": corrupt MSH file: element " + std::to_string(e.tag) + " references node " + std::to_string(v) +
                      ", which is not defined");
      }
    }
  }
  return c;
}

}  // namespace fissure::io_detail
