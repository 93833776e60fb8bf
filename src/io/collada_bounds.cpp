#include "assimp_precheck.hpp"

#include "fissure/base/error.hpp"

#include <pugixml.hpp>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <map>
#include <optional>
#include <set>
#include <string>
#include <vector>

// assimp 5.2.5's COLLADA reader trusts what the file says it holds. Measured on 400 corrupted
// copies of the demo street (docs/scenes.md) and read in its source (ColladaParser.cpp,
// ColladaLoader.cpp): an accessor's offset, stride or count is never compared with its array,
// so a count of -1 or an offset past the array reads outside it (SIGSEGV); a <polylist> whose
// <p> comes without a <vcount>, or a primitive without a VERTEX input, indexes past its index
// list; a <tristrips> or <linestrips> strip shorter than one primitive wraps assimp's unsigned
// primitive count (refused here by name, and a strip of 2 makes no triangle); a <p> holding anything but
// digits and separators loops forever, appending zeros until memory runs out; <instance_node>
// cycles recurse until the stack overflows; an input naming a Name_array reads floats from an
// empty vector; a COLOR accessor with more than four typed params writes past a colour; and an
// embedded <hex> image is decoded to twice its length. Skins, morphs and animations go through
// more unchecked index arithmetic (ColladaLoader.cpp, CreateMesh's controller part and
// CreateAnimation), so files holding them are refused: Fissure fractures static geometry.
//
// So this walks the document as assimp's parser will (the same pugixml options; sources,
// vertices and primitives in assimp's pre-order; accessors resolved when a <p> is read) and
// refuses, naming the element and its line, anything assimp would read out of bounds.

namespace fissure::io_detail {
namespace {

using Node = pugi::xml_node;

/// Deepest element nesting accepted: assimp's pre-order walk and scene-node reader recurse once
/// per level; real COLLADA files nest a few dozen (deep skeletons ~100).
constexpr int kMaxColladaNesting = 512;
/// After <instance_node> expansion: the node count and depth assimp's hierarchy builder makes.
constexpr std::uint64_t kMaxExpandedNodes = 1'000'000;
constexpr int kMaxExpandedDepth = 1000;
/// Index offsets of a primitive's inputs: real files use fewer than 8.
constexpr std::uint64_t kMaxInputOffset = 255;
/// Counts fit assimp's int.
constexpr std::uint64_t kMaxCount = 0x7FFFFFFF;

enum class Semantic { Invalid, Vertex, Position, Normal, Texcoord, Color, Tangent, Bitangent };

Semantic semantic_of(const std::string& s) {
  if (s == "POSITION") return Semantic::Position;
  if (s == "TEXCOORD") return Semantic::Texcoord;
  if (s == "NORMAL") return Semantic::Normal;
  if (s == "COLOR") return Semantic::Color;
  if (s == "VERTEX") return Semantic::Vertex;
  if (s == "BINORMAL" || s == "TEXBINORMAL") return Semantic::Bitangent;
  if (s == "TANGENT" || s == "TEXTANGENT") return Semantic::Tangent;
  return Semantic::Invalid;  // assimp ignores the input
}

// What assimp skips between numbers (SkipSpacesAndLineEnd): not '\f', which it stops at without
// advancing: a form feed in a <p> loops forever (found by fuzzing: 16 GB in 90 s), so a token
// holding one is refused like any other word.
bool separator(char c) { return c == ' ' || c == '\t' || c == '\r' || c == '\n'; }

std::vector<std::string_view> tokens_of(std::string_view text) {
  std::vector<std::string_view> out;
  std::size_t i = 0;
  while (i < text.size()) {
    while (i < text.size() && separator(text[i])) ++i;
    const std::size_t start = i;
    while (i < text.size() && !separator(text[i])) ++i;
    if (i > start) out.push_back(text.substr(start, i - start));
  }
  return out;
}

// A token as a message shows it: its first 20 bytes, control bytes as \xNN (a form feed is
// invisible on a terminal).
std::string shown(std::string_view token) {
  std::string out;
  for (const char c : token.substr(0, 20)) {
    const auto u = static_cast<unsigned char>(c);
    if (u < 0x20 || u == 0x7F) {
      const char* hex = "0123456789ABCDEF";
      out += {'\\', 'x', hex[u >> 4], hex[u & 15]};
    } else {
      out += c;
    }
  }
  return out;
}

std::optional<std::uint64_t> decimal(std::string_view token, std::uint64_t max) {
  if (token.empty() || token.size() > 19) return std::nullopt;
  std::uint64_t v = 0;
  for (const char c : token) {
    if (c < '0' || c > '9') return std::nullopt;
    v = v * 10 + static_cast<std::uint64_t>(c - '0');
  }
  if (v > max) return std::nullopt;
  return v;
}

struct DataArray {
  bool strings = false;
  std::uint64_t count = 0;
};

struct Accessor {
  std::uint64_t count = 0, offset = 0, stride = 1;
  std::string array;             // the id it reads, without '#'
  std::uint64_t params = 0;      // <param> elements
  std::uint64_t last_named = 0;  // highest param index assimp reads a component from
  std::uint64_t typed_size = 0;  // assimp's mSize: 16 for a float4x4 param, else 1 per typed param
  Node node;
};

struct Input {
  Semantic semantic = Semantic::Invalid;
  std::string source;  // without '#'
  std::uint64_t offset = 0;
  Node node;
};

struct MeshState {
  std::string vertex_id;
  std::vector<Input> per_vertex;
};

struct SceneNode {
  std::string id, name;
  std::vector<int> children;
  std::vector<std::string> instances;
  Node node;
};

class ColladaBounds {
 public:
  ColladaBounds(std::string_view bytes, const std::string& name) : m_bytes(bytes), m_name(name) {}

  /// After check(): every <node>'s name by its id, where it has both and they differ.
  std::map<std::string, std::string> node_names() const {
    std::map<std::string, std::string> names;
    for (const pugi::xpath_node& found : m_doc.select_nodes("//node[@id and @name]")) {
      const Node node = found.node();
      const std::string id = node.attribute("id").as_string(), name = node.attribute("name").as_string();
      if (!name.empty() && name != id) names.emplace(id, name);
    }
    return names;
  }

  void check() {
    if (const std::size_t nul = m_bytes.find('\0'); nul != std::string_view::npos) {
      // assimp parses up to the first NUL; a text format holding one is corrupt (or UTF-16).
      throw IoError(m_name + ": corrupt COLLADA: a NUL byte at byte " + std::to_string(nul) + " (line " +
                    std::to_string(line_at(nul)) + "); COLLADA is UTF-8 text");
    }
    const pugi::xml_parse_result parsed = m_doc.load_buffer(m_bytes.data(), m_bytes.size(), pugi::parse_full, pugi::encoding_utf8);
    if (!parsed) {
      throw IoError(m_name + ": corrupt COLLADA: its XML does not parse at line " +
                    std::to_string(line_at(static_cast<std::size_t>(std::max<std::ptrdiff_t>(parsed.offset, 0)))) + ": " +
                    parsed.description());
    }
    check_depth();
    const Node root = m_doc.child("COLLADA");
    if (!root) throw IoError(m_name + ": not a COLLADA file: no <COLLADA> root element");
    for (const Node library : root.children()) {
      const std::string tag = library.name();
      if (tag == "library_controllers" || tag == "library_animations" || tag == "library_animation_clips") {
        if (library.find_child([](Node n) { return n.type() == pugi::node_element; })) {
          fail(library, "<" + tag + "> holds " + (tag == "library_controllers" ? "skins or morphs" : "animations") +
                            ", which Fissure does not read (it fractures static geometry); apply or remove them before export");
        }
      } else if (tag == "asset") {
        check_asset(library);
      } else if (tag == "library_images") {
        for (const Node image : library.children()) {
          if (const Node hex = image.find_node([](Node n) { return std::string(n.name()) == "hex"; })) {
            fail(hex, "embedded <hex> images are not supported (assimp misreads them); reference the image file instead");
          }
        }
      } else if (tag == "library_geometries") {
        for (const Node geometry : library.children()) {
          if (std::string(geometry.name()) != "geometry") continue;
          const std::string id = geometry.attribute("id").as_string();
          if (!m_geometry_ids.insert(id).second) continue;  // assimp keeps the first geometry of an id
          for (const Node mesh : geometry.children()) {
            if (std::string(mesh.name()) == "mesh") check_mesh(mesh);
          }
        }
      } else if (tag == "library_visual_scenes") {
        for (const Node scene : library.children()) {
          if (std::string(scene.name()) != "visual_scene") continue;
          const int n = add_node(scene, scene.attribute("id").as_string(),
                                 scene.attribute("name") ? scene.attribute("name").as_string() : "Scene");
          m_library[m_nodes[static_cast<std::size_t>(n)].id] = n;
          read_scene_node(scene, n);
        }
      } else if (tag == "library_nodes") {
        read_scene_node(library, -1);
      } else if (tag == "scene") {
        for (const Node instance : library.children()) {
          if (std::string(instance.name()) != "instance_visual_scene") continue;
          const std::string url = instance.attribute("url").as_string();
          // assimp refuses a second instance and a url it cannot resolve itself.
          if (m_root < 0 && !url.empty() && url[0] == '#') {
            const auto it = m_library.find(url.substr(1));
            if (it != m_library.end()) m_root = it->second;
          }
        }
      }
    }
    if (m_root >= 0) check_hierarchy();
  }

 private:
  [[noreturn]] void fail(Node at, const std::string& what) const {
    throw IoError(m_name + ": corrupt COLLADA (line " + std::to_string(line_at(static_cast<std::size_t>(std::max<std::ptrdiff_t>(at.offset_debug(), 0)))) +
                  "): " + what);
  }

  std::size_t line_at(std::size_t offset) const {
    offset = std::min(offset, m_bytes.size());
    return 1 + static_cast<std::size_t>(std::count(m_bytes.begin(), m_bytes.begin() + static_cast<std::ptrdiff_t>(offset), '\n'));
  }

  // An attribute assimp reads as an integer: absent gives `fallback`; present, it must be a plain
  // decimal no larger than `max` (assimp would read "-1" or "1e9" as another number).
  std::uint64_t count_attribute(Node element, const char* key, std::uint64_t fallback, std::uint64_t max) const {
    const pugi::xml_attribute a = element.attribute(key);
    if (!a) return fallback;
    const std::string text = a.as_string();
    const std::optional<std::uint64_t> v = decimal(text, max);
    if (!v) fail(element, label(element) + " " + key + "=\"" + text.substr(0, 40) + "\" is not a whole number from 0 to " + std::to_string(max));
    return *v;
  }

  std::string label(Node element) const {
    std::string out = "<" + std::string(element.name());
    if (const pugi::xml_attribute id = element.attribute("id")) out += " id=\"" + std::string(id.as_string()).substr(0, 60) + "\"";
    return out + ">";
  }

  void check_depth() const {
    std::vector<std::pair<Node, int>> stack{{m_doc, 0}};
    while (!stack.empty()) {
      const auto [node, depth] = stack.back();
      stack.pop_back();
      if (depth > kMaxColladaNesting) {
        fail(node, "elements nest deeper than " + std::to_string(kMaxColladaNesting) + " levels; refused, as assimp would overflow its stack");
      }
      for (const Node child : node.children()) stack.emplace_back(child, depth + 1);
    }
  }

  void check_asset(Node asset) const {
    const Node unit = asset.child("unit");
    if (!unit || !unit.attribute("meter")) return;
    const std::string text = unit.attribute("meter").as_string();
    char* end = nullptr;
    const double meter = std::strtod(text.c_str(), &end);
    if (text.empty() || end != text.c_str() + text.size() || !std::isfinite(meter) || meter <= 0.0) {
      fail(unit, "<unit meter=\"" + text.substr(0, 40) + "\"> is not a positive length in metres");
    }
  }

  // assimp's XmlNodeIterator in PreOrderMode: every element below `node`, parents first.
  static std::vector<Node> preorder(Node node) {
    std::vector<Node> out;
    std::vector<Node> stack;
    for (Node c = node.last_child(); c; c = c.previous_sibling()) stack.push_back(c);
    while (!stack.empty()) {
      const Node n = stack.back();
      stack.pop_back();
      if (n.type() == pugi::node_element) out.push_back(n);
      for (Node c = n.last_child(); c; c = c.previous_sibling()) stack.push_back(c);
    }
    return out;
  }

  void check_mesh(Node mesh) {
    MeshState state;
    for (const Node element : preorder(mesh)) {
      const std::string tag = element.name();
      if (tag == "source") {
        read_source(element);
      } else if (tag == "vertices") {
        if (element.attribute("id")) state.vertex_id = element.attribute("id").as_string();
        for (const Node child : element.children()) {
          if (std::string(child.name()) != "input") fail(element, "<vertices> holds something other than <input> elements");
          read_input(child, state.per_vertex);
        }
      } else if (tag == "triangles" || tag == "lines" || tag == "linestrips" || tag == "polygons" || tag == "polylist" ||
                 tag == "trifans" || tag == "tristrips") {
        check_primitives(element, state);
      }
    }
  }

  void read_source(Node source) {
    const std::string id = source.attribute("id").as_string();
    for (const Node element : preorder(source)) {
      const std::string tag = element.name();
      if (tag == "float_array" || tag == "IDREF_array" || tag == "Name_array") {
        read_array(element, tag != "float_array");
      } else if (tag == "technique_common") {
        if (const Node accessor = element.child("accessor")) read_accessor(accessor, id);
      }
    }
  }

  void read_array(Node array, bool strings) {
    const std::string id = array.attribute("id").as_string();
    DataArray data;
    data.strings = strings;
    data.count = count_attribute(array, "count", 0, kMaxCount);
    // assimp reads exactly `count` values; one that holds another number is corrupt.
    const std::size_t held = tokens_of(array.text().as_string()).size();
    if (held != data.count) {
      fail(array, label(array) + " declares " + std::to_string(data.count) + " values but holds " + std::to_string(held));
    }
    // Ids are global in assimp's data library, and a later array of the same id replaces one an
    // accessor already points at.
    if (!m_arrays.emplace(id, data).second) fail(array, "two arrays share the id \"" + id.substr(0, 60) + "\"");
  }

  void read_accessor(Node element, const std::string& source_id) {
    Accessor a;
    a.node = element;
    const std::string source = element.attribute("source").as_string();
    if (source.empty() || source[0] != '#') fail(element, "<accessor> source=\"" + source.substr(0, 60) + "\" is not a '#id' reference");
    a.array = source.substr(1);
    a.count = count_attribute(element, "count", 0, kMaxCount);
    a.offset = count_attribute(element, "offset", 0, 0xFFFFFFFFu);
    a.stride = count_attribute(element, "stride", 1, 0xFFFFFFFFu);
    static const std::set<std::string> kComponents = {"X", "Y", "Z", "R", "G", "B", "A", "S", "T", "P", "U", "V"};
    for (const Node param : preorder(element)) {
      if (std::string(param.name()) != "param") continue;
      if (param.attribute("name") && kComponents.count(param.attribute("name").as_string())) a.last_named = a.params;
      if (param.attribute("type")) a.typed_size += std::string(param.attribute("type").as_string()) == "float4x4" ? 16 : 1;
      ++a.params;
    }
    if (a.stride == 0 || a.stride < a.params) {
      fail(element, "the accessor of source \"" + source_id.substr(0, 60) + "\" has stride " + std::to_string(a.stride) + " for " +
                        std::to_string(a.params) + " params");
    }
    if (!m_accessors.emplace(source_id, a).second) fail(element, "two sources share the id \"" + source_id.substr(0, 60) + "\"");
  }

  void read_input(Node element, std::vector<Input>& into) const {
    Input in;
    in.node = element;
    in.semantic = semantic_of(element.attribute("semantic").as_string());
    const std::string source = element.attribute("source").as_string();
    if (source.empty() || source[0] != '#') fail(element, "<input> source=\"" + source.substr(0, 60) + "\" is not a '#id' reference");
    in.source = source.substr(1);
    in.offset = count_attribute(element, "offset", 0, kMaxInputOffset);
    if (in.semantic != Semantic::Invalid) into.push_back(in);
  }

  // The accessor an input reads, which assimp resolves when a <p> is read: it must exist by then,
  // read float values, and reach no further than its array for any index below its count.
  const Accessor& resolved(const Input& in) const {
    const auto it = m_accessors.find(in.source);
    if (it == m_accessors.end()) fail(in.node, "<input> names source \"" + in.source.substr(0, 60) + "\", which is not defined before it is used");
    const Accessor& a = it->second;
    const auto array = m_arrays.find(a.array);
    if (array == m_arrays.end()) fail(a.node, "the accessor of \"" + in.source.substr(0, 60) + "\" reads array \"" + a.array.substr(0, 60) + "\", which is not defined before it is used");
    if (array->second.strings) fail(a.node, "the accessor of \"" + in.source.substr(0, 60) + "\" reads names, not numbers, for mesh data");
    if (a.count > 0) {
      // assimp reads components at offset + index * stride + (the index of each named param).
      const std::uint64_t last = a.offset + (a.count - 1) * a.stride + a.last_named;  // < 2^31 · 2^32 + 2^32: no wrap
      if (last >= array->second.count) {
        fail(a.node, "the accessor of \"" + in.source.substr(0, 60) + "\" (count " + std::to_string(a.count) + ", offset " +
                         std::to_string(a.offset) + ", stride " + std::to_string(a.stride) + ") reads value " + std::to_string(last + 1) +
                         " of array \"" + a.array.substr(0, 60) + "\", which holds " + std::to_string(array->second.count));
      }
    }
    if (in.semantic == Semantic::Color && a.typed_size > 4) fail(a.node, "a COLOR accessor with more than 4 components");
    return a;
  }

  void check_primitives(Node element, const MeshState& mesh) {
    const std::string tag = element.name();
    const std::uint64_t count = count_attribute(element, "count", 0, kMaxCount);
    std::vector<Input> per_index;
    std::vector<std::uint64_t> vcount;
    int p_number = 0;
    for (const Node child : preorder(element)) {
      const std::string name = child.name();
      if (name == "input") {
        read_input(child, per_index);
      } else if (name == "vcount" && count > 0) {
        const std::vector<std::string_view> tokens = tokens_of(child.text().as_string());
        if (tokens.size() != count) {
          fail(child, "<vcount> holds " + std::to_string(tokens.size()) + " numbers for <" + tag + " count=\"" + std::to_string(count) + "\">");
        }
        for (const std::string_view t : tokens) {
          const std::optional<std::uint64_t> v = decimal(t, 0xFFFF);
          if (!v || *v == 0) fail(child, "<vcount> holds \"" + shown(t) + "\", not a vertex count from 1 to 65535");
          vcount.push_back(*v);
        }
      } else if (name == "p") {
        check_p(child, tag, count, mesh, per_index, vcount, ++p_number);
      }
    }
  }

  void check_p(Node p, const std::string& tag, std::uint64_t count, const MeshState& mesh, const std::vector<Input>& per_index,
               const std::vector<std::uint64_t>& vcount, int p_number) const {
    const std::string where = "<p> #" + std::to_string(p_number) + " of <" + tag + ">";
    std::uint64_t offsets = 1;
    const Input* vertex = nullptr;
    for (const Input& in : per_index) {
      offsets = std::max(offsets, in.offset + 1);
      if (in.semantic == Semantic::Vertex) vertex = &in;
    }
    // assimp reads the indices only when count > 0; strips and fans then still build primitives.
    std::vector<std::uint64_t> indices;
    if (count > 0) {
      for (const std::string_view t : tokens_of(p.text().as_string())) {
        const std::optional<std::uint64_t> v = decimal(t, kMaxCount);
        if (!v) fail(p, where + " holds \"" + shown(t) + "\", not an index from 0 to " + std::to_string(kMaxCount));
        indices.push_back(*v);
      }
    }
    const std::uint64_t n = indices.size();
    std::uint64_t expected = 0;
    if (tag == "polylist") {
      if (count > 0 && vcount.size() < count) fail(p, where + " comes without a <vcount> before it");
      for (const std::uint64_t c : vcount) expected += c;
    } else if (tag == "triangles") {
      expected = 3 * count;
    } else if (tag == "lines") {
      expected = 2 * count;
    }
    // assimp corrects a <lines> count itself (SketchUp writes it wrong); any other mismatch it refuses.
    if (expected > 0 && n != expected * offsets && tag != "lines") {
      fail(p, where + " holds " + std::to_string(n) + " indices; its count and inputs call for " + std::to_string(expected * offsets));
    }
    if (n % offsets != 0) fail(p, where + " holds " + std::to_string(n) + " indices, not a multiple of its " + std::to_string(offsets) + " inputs");
    const std::uint64_t vertices = n / offsets;
    if (tag == "tristrips" && vertices < 3) fail(p, where + " is a strip of " + std::to_string(vertices) + " vertices (at least 3)");
    if (tag == "linestrips" && vertices < 2) fail(p, where + " is a strip of " + std::to_string(vertices) + " vertices (at least 2)");
    if ((tag == "trifans" || tag == "polygons") && vertices == 0) fail(p, where + " holds no vertices");
    if (vertices == 0) return;

    if (!vertex) fail(p, "<" + tag + "> has no VERTEX input");
    if (vertex->source != mesh.vertex_id) {
      fail(vertex->node, "the VERTEX input names \"" + vertex->source.substr(0, 60) + "\", not the mesh's <vertices>");
    }
    // One position per vertex (CreateMesh copies one per face corner without a bound).
    int positions = 0;
    for (const Input& in : mesh.per_vertex) positions += in.semantic == Semantic::Position ? 1 : 0;
    for (const Input& in : per_index) positions += in.semantic == Semantic::Position ? 1 : 0;
    if (positions != 1) fail(p, where + ": its mesh has " + std::to_string(positions) + " POSITION inputs (one is needed)");

    // Every index below its accessor's count (assimp checks it too, without naming the element).
    auto check_indices = [&](const Input& in, std::uint64_t at) {
      const Accessor& a = resolved(in);
      for (std::uint64_t v = 0; v < vertices; ++v) {
        const std::uint64_t index = indices[v * offsets + at];
        if (index >= a.count) {
          fail(p, where + ": vertex " + std::to_string(v + 1) + " indexes value " + std::to_string(index) + " of source \"" +
                      in.source.substr(0, 60) + "\", which has " + std::to_string(a.count));
        }
      }
    };
    for (const Input& in : mesh.per_vertex) {
      if (in.semantic != Semantic::Vertex) check_indices(in, vertex->offset);
    }
    for (const Input& in : per_index) {
      if (in.semantic != Semantic::Vertex) check_indices(in, in.offset);
    }
  }

  int add_node(Node element, std::string id, std::string name) {
    SceneNode n;
    n.id = std::move(id);
    n.name = std::move(name);
    n.node = element;
    m_nodes.push_back(std::move(n));
    return static_cast<int>(m_nodes.size()) - 1;
  }

  // assimp's ReadSceneNode: a <node> under <library_nodes> (parent -1) enters the node library by
  // id (a later one replaces an earlier); instance_node urls are kept to be resolved later.
  void read_scene_node(Node element, int parent) {
    for (const Node child : element.children()) {
      const std::string tag = child.name();
      if (tag == "node") {
        const int n = add_node(child, child.attribute("id").as_string(), child.attribute("name").as_string());
        if (parent >= 0) m_nodes[static_cast<std::size_t>(parent)].children.push_back(n);
        else m_library[m_nodes[static_cast<std::size_t>(n)].id] = n;
        read_scene_node(child, n);
      } else if (parent >= 0 && tag == "instance_node") {
        const std::string url = child.attribute("url").as_string();
        if (!url.empty() && url[0] == '#') m_nodes[static_cast<std::size_t>(parent)].instances.push_back(url.substr(1));
      }
    }
  }

  // ColladaLoader::ResolveNodeInstances: the node library by id, else the first node below the
  // root (real children only) whose name or id matches; else skipped.
  int resolve_instance(const std::string& target) const {
    if (const auto it = m_library.find(target); it != m_library.end()) return it->second;
    std::vector<int> stack{m_root};
    while (!stack.empty()) {
      const int n = stack.back();
      stack.pop_back();
      const SceneNode& node = m_nodes[static_cast<std::size_t>(n)];
      if (node.name == target || node.id == target) return n;
      for (auto c = node.children.rbegin(); c != node.children.rend(); ++c) stack.push_back(*c);
    }
    return -1;
  }

  // The hierarchy assimp's BuildHierarchy builds (children, then resolved instances), walked
  // without recursion: no cycle, and bounded in size and depth.
  void check_hierarchy() const {
    enum class State : char { New, Open, Done };
    std::vector<State> state(m_nodes.size(), State::New);
    std::vector<std::uint64_t> size(m_nodes.size(), 1);
    std::vector<int> depth(m_nodes.size(), 1);
    std::vector<std::vector<int>> next(m_nodes.size());
    for (std::size_t n = 0; n < m_nodes.size(); ++n) {
      next[n] = m_nodes[n].children;
      for (const std::string& target : m_nodes[n].instances) {
        const int r = resolve_instance(target);
        if (r >= 0) next[n].push_back(r);
      }
    }
    std::vector<std::pair<int, std::size_t>> stack{{m_root, 0}};
    state[static_cast<std::size_t>(m_root)] = State::Open;
    while (!stack.empty()) {
      auto& [n, k] = stack.back();
      const auto un = static_cast<std::size_t>(n);
      if (k < next[un].size()) {
        const int c = next[un][k++];
        const auto uc = static_cast<std::size_t>(c);
        if (state[uc] == State::Open) {
          fail(m_nodes[un].node, "node \"" + m_nodes[un].id.substr(0, 60) + "\" instances node \"" + m_nodes[uc].id.substr(0, 60) +
                                     "\", which contains it: a cycle");
        }
        if (state[uc] == State::New) {
          state[uc] = State::Open;
          stack.emplace_back(c, 0);
        }
        continue;
      }
      for (const int c : next[un]) {
        size[un] = std::min(kMaxExpandedNodes + 1, size[un] + size[static_cast<std::size_t>(c)]);
        depth[un] = std::max(depth[un], depth[static_cast<std::size_t>(c)] + 1);
      }
      if (size[un] > kMaxExpandedNodes) fail(m_nodes[un].node, "its <instance_node>s expand to more than " + std::to_string(kMaxExpandedNodes) + " nodes");
      if (depth[un] > kMaxExpandedDepth) fail(m_nodes[un].node, "its <instance_node>s nest deeper than " + std::to_string(kMaxExpandedDepth) + " levels");
      state[un] = State::Done;
      stack.pop_back();
    }
  }

  std::string_view m_bytes;
  const std::string& m_name;
  pugi::xml_document m_doc;
  std::set<std::string> m_geometry_ids;
  std::map<std::string, DataArray> m_arrays;
  std::map<std::string, Accessor> m_accessors;
  std::vector<SceneNode> m_nodes;
  std::map<std::string, int> m_library;
  int m_root = -1;
};

}  // namespace

std::map<std::string, std::string> precheck_collada(std::string_view bytes, const std::string& name) {
  ColladaBounds bounds(bytes, name);
  bounds.check();
  return bounds.node_names();
}

}  // namespace fissure::io_detail
