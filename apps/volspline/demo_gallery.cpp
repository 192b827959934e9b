#include "demo_gallery.h"

#include <algorithm>
#include <cstdio>
#include <sstream>

#include "volspline/core/error.h"
#include "volspline/io/atomic_file.h"

namespace volspline::cli {

std::string html_escape(std::string_view text) {
  std::string out;
  out.reserve(text.size());
  for (const char c : text) {
    switch (c) {
      case '&': out += "&amp;"; break;
      case '<': out += "&lt;"; break;
      case '>': out += "&gt;"; break;
      case '"': out += "&quot;"; break;
      case '\'': out += "&#39;"; break;
      default: out += c;
    }
  }
  return out;
}

std::string url_escape(std::string_view name) {
  std::string out;
  for (const char c : name) {
    const auto u = static_cast<unsigned char>(c);
    if ((u >= 'a' && u <= 'z') || (u >= 'A' && u <= 'Z') || (u >= '0' && u <= '9') || c == '-' || c == '.' || c == '_' ||
        c == '~' || c == '/') {
      out += c;
    } else {
      char hex[4];
      std::snprintf(hex, sizeof hex, "%%%02X", u);
      out += hex;
    }
  }
  return out;
}


Gallery::Gallery(std::string heading) : heading_(std::move(heading)) {}

void Gallery::add(GalleryEntry entry) { entries_.push_back(std::move(entry)); }

std::string Gallery::html() const {
  std::ostringstream page;
  page << "<!DOCTYPE html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\">\n<title>" << html_escape(heading_)
       << "</title>\n<style>\n"
       << "body { font-family: sans-serif; margin: 1.5em; }\n"
       << "main { display: grid; grid-template-columns: repeat(auto-fill, minmax(320px, 1fr)); gap: 16px; }\n"
       << "section { border: 1px solid #ccc; border-radius: 4px; padding: 8px; }\n"
       << "section h2 { font-size: 1.05em; margin: 0.3em 0; }\n"
       << "section p { font-size: 0.9em; margin: 0.3em 0; }\n"
       << "img { width: 100%; border: 1px solid #eee; }\n"
       << "div.pictures { display: flex; gap: 4px; }\n"
       << "div.pictures a { flex: 1; min-width: 0; }\n"
       << "pre { background: #f4f4f4; padding: 0.4em; white-space: pre-wrap; font-size: 0.8em; margin: 0.3em 0 0; }\n"
       << "</style>\n</head>\n<body>\n<h1>" << html_escape(heading_) << "</h1>\n"
       << "<p>" << entries_.size()
       << " examples. A picture opens the example's interactive page (turn it, cut it, switch parts, move the probes) where "
          "it has one. Each command, run in this folder, writes the pictures and the page shown with it.</p>\n<main>\n";
  for (const GalleryEntry& e : entries_) {
    page << "<section id=\"" << html_escape(e.title) << "\">\n<h2>" << html_escape(e.title) << "</h2>\n<p>"
         << html_escape(e.description) << "</p>\n<div class=\"pictures\">";
    for (const std::string& picture : e.pictures) {
      const std::string link = html_escape(url_escape(picture));
      const std::string target = e.page.empty() ? link : html_escape(url_escape(e.page));
      page << "<a href=\"" << target << "\"><img src=\"" << link << "\" alt=\"" << html_escape(e.title) << "\" loading=\"lazy\"></a>";
    }
    page << "</div>\n<pre><code>" << html_escape(e.command) << "</code></pre>\n</section>\n";
  }
  page << "</main>\n</body>\n</html>\n";
  return page.str();
}

void Gallery::write(const std::filesystem::path& folder) const { write_file_atomically(folder / "index.html", html()); }

DemoRun::DemoRun(std::filesystem::path dir, std::vector<std::string> only, Progress* progress)
    : dir_(std::move(dir)), only_(only.begin(), only.end()), progress_(progress) {}

bool DemoRun::wants(const std::string& name) {
  known_.push_back(name);
  if (only_.empty()) return true;
  if (!only_.contains(name)) return false;
  matched_.insert(name);
  return true;
}

bool DemoRun::wants_group(const std::string& prefix, const std::string& what) {
  known_.push_back(what);
  return only_.empty() || std::any_of(only_.begin(), only_.end(), [&](const std::string& n) { return n.starts_with(prefix); });
}

void DemoRun::check_selection() const {
  std::vector<std::string> unknown;
  for (const std::string& name : only_)
    if (!matched_.contains(name)) unknown.push_back(name);
  if (unknown.empty()) return;
  std::string message = "no example is called";
  for (const std::string& name : unknown) message += " '" + name + "'";
  message += "; the examples are:";
  for (const std::string& name : known_) message += " " + name;
  throw InvalidInput(message, "--only");
}

std::string DemoRun::write_page(const std::string& file, InteractivePage page, const std::string& command) const {
  if (!interactive_pages_available()) return "";
  page.command = command;
  write_file_atomically(dir_ / file, interactive_page_html(page));
  return file;
}

}  // namespace volspline::cli
