#pragma once
// Helpers shared by the XML readers (G+Smo, VTK): where a node is, for messages, and the
// whitespace-separated tokens of an element's character data.
#include <algorithm>
#include <cstddef>
#include <string>
#include <string_view>
#include <vector>

#include <pugixml.hpp>

namespace volspline::detail {

// Locating nodes for messages: "line L, /xml/Geometry[2]/Basis/KnotVector".

class Locator {
 public:
  explicit Locator(std::string_view text) : text_(text) {}

  std::string where(const pugi::xml_node& node) const {
    std::string path;
    for (pugi::xml_node n = node; n && n.type() == pugi::node_element; n = n.parent()) {
      std::string part = n.name();
      int index = 0;
      int count = 0;
      for (pugi::xml_node s = n.parent().child(n.name()); s; s = s.next_sibling(n.name())) {
        ++count;
        if (s == n) index = count;
      }
      // Appending, not operator+(const char*, std::string&&): GCC 12 gives a false -Wrestrict on
      // the latter (GCC bug 105329) where a unity build inlines this function.
      if (count > 1) {
        part += '[';
        part += std::to_string(index);
        part += ']';
      }
      part.insert(part.begin(), '/');
      path.insert(0, part);
    }
    const std::ptrdiff_t offset = node.offset_debug();
    if (offset < 0) return path;
    return "line " + std::to_string(line_of(static_cast<std::size_t>(offset))) + ", " + path;
  }

  std::string line_and_column(std::size_t offset) const {
    std::size_t line = 1;
    std::size_t start = 0;
    for (std::size_t i = 0; i < std::min(offset, text_.size()); ++i) {
      if (text_[i] == '\n') {
        ++line;
        start = i + 1;
      }
    }
    return "line " + std::to_string(line) + ", column " + std::to_string(offset - start + 1);
  }

 private:
  std::size_t line_of(std::size_t offset) const {
    return static_cast<std::size_t>(std::count(text_.begin(), text_.begin() + static_cast<std::ptrdiff_t>(std::min(offset, text_.size())), '\n')) + 1;
  }

  std::string_view text_;
};

/// Deepest nesting of elements the XML readers accept. pugixml parses iteratively, so no depth
/// exhausts the stack there, but the readers and what they hand on (paths in messages, VTK) walk
/// up and down the tree; G+Smo and VTK files need 6 levels, the rest is room for extensions.
inline constexpr std::size_t kMaxXmlDepth = 64;

/// The first element (in document order) nested deeper than kMaxXmlDepth below `root`, or an
/// empty node. Iterative: a document of a million nested elements is walked without recursion.
inline pugi::xml_node element_deeper_than_limit(const pugi::xml_node& root) {
  std::size_t depth = 0;
  pugi::xml_node n = root.first_child();
  if (n) depth = 1;
  while (n) {
    if (n.type() == pugi::node_element && depth > kMaxXmlDepth) return n;
    if (pugi::xml_node c = n.first_child()) {
      n = c;
      ++depth;
      continue;
    }
    while (n && !n.next_sibling() && n != root) {
      n = n.parent();
      --depth;
    }
    if (!n || n == root) break;
    n = n.next_sibling();
  }
  return {};
}

/// The character data of an element (all its text and CDATA children, comments skipped).
inline std::string element_text(const pugi::xml_node& node) {
  std::string text;
  for (pugi::xml_node child = node.first_child(); child; child = child.next_sibling()) {
    if (child.type() == pugi::node_pcdata || child.type() == pugi::node_cdata) {
      text += child.value();
      text += ' ';
    }
  }
  return text;
}

inline std::vector<std::string_view> tokens_of(std::string_view text) {
  std::vector<std::string_view> tokens;
  std::size_t i = 0;
  const auto space = [](char c) { return c == ' ' || c == '\t' || c == '\n' || c == '\r'; };
  while (i < text.size()) {
    while (i < text.size() && space(text[i])) ++i;
    const std::size_t start = i;
    while (i < text.size() && !space(text[i])) ++i;
    if (i > start) tokens.push_back(text.substr(start, i - start));
  }
  return tokens;
}


}  // namespace volspline::detail
