#pragma once
// The gallery page of `volspline demo` (index.html in its output folder) and what every demo
// writer gets: the folder, the gallery, the --only selection and progress reporting.
//
// A demo writer, for each of its examples:
//
//   void write_my_demo(DemoRun& demo) {
//     if (!demo.wants("my-example")) return;          // --only may name others
//     {
//       const ProgressPhase phase(demo.progress(), "my-example");
//       ... write demo.path("my-example.png") and friends ...
//     }
//     demo.gallery().add({"my-example", "what it shows",
//                         {"my-example.png"},                       // relative to the folder
//                         "volspline view my.json -o my-example.png"});  // run in the folder
//   }
//
// The command must be a real command line of this program that, run in the output folder,
// writes the pictures listed from the files there (the demo's examples/ holds the inputs): the
// commands a user would type, never `volspline demo --only` (the gallery test runs some of them
// and checks the pictures byte for byte).
#include <filesystem>
#include <set>
#include <string>
#include <string_view>
#include <vector>

#include "volspline/core/progress.h"
#include "volspline/web/interactive_page.h"

namespace volspline::cli {

/// One example on the gallery page.
struct GalleryEntry {
  /// The example's name, shown as its heading ("ball", "twisted-loft-boundary").
  std::string title;
  /// One sentence: what the pictures show (and where in the literature).
  std::string description;
  /// PNG file names relative to the gallery's folder.
  std::vector<std::string> pictures;
  /// A shell command line that, run in the gallery's folder, writes the pictures.
  std::string command;
  /// The example's interactive page (web/interactive_page.h), relative to the gallery's folder;
  /// empty where there is none. The thumbnails open it.
  std::string page{};
};

/// The entries of a gallery page, in the order added, and the page itself.
class Gallery {
 public:
  explicit Gallery(std::string heading = "volspline demo");
  void add(GalleryEntry entry);
  const std::vector<GalleryEntry>& entries() const { return entries_; }
  /// The page: a heading, then a grid of entries, each its pictures as thumbnails (linking to
  /// the interactive page where there is one, else to the picture), title, description and
  /// command, all text HTML-escaped.
  std::string html() const;
  /// Writes `folder`/index.html atomically. \throw IoError if it cannot be written.
  void write(const std::filesystem::path& folder) const;

 private:
  std::string heading_;
  std::vector<GalleryEntry> entries_;
};

/// `text` with & < > " ' replaced by character references.
std::string html_escape(std::string_view text);
/// `name` as a relative URL: bytes other than letters, digits and -._~/ percent-encoded.
std::string url_escape(std::string_view name);

/// One run of `volspline demo`.
class DemoRun {
 public:
  /// `only`: the names given to --only (empty: every example).
  DemoRun(std::filesystem::path dir, std::vector<std::string> only, Progress* progress);

  const std::filesystem::path& dir() const { return dir_; }
  /// `file` in the output folder, as a string.
  std::string path(const std::string& file) const { return (dir_ / file).string(); }
  Gallery& gallery() { return gallery_; }
  Progress* progress() const { return progress_; }
  /// Whether the example `name` is to be written (every one is unless --only names others).
  /// Every writer asks this for each of its examples, which makes the name known.
  bool wants(const std::string& name);
  /// Whether any example whose name starts with `prefix` may be wanted: for writers that build
  /// a group of examples at once, to skip building it. `what` describes the group for the list
  /// of known names.
  bool wants_group(const std::string& prefix, const std::string& what);
  /// Whether --only was given (then index.html is not written: it would list only those).
  bool selective() const { return !only_.empty(); }
  /// \throw InvalidInput naming the --only names no writer knew, and the known names.
  void check_selection() const;
  /// Writes `page` (with `command` as the command that makes it) as `file` in the output folder
  /// and returns `file`; where this build cannot write interactive pages, writes nothing and
  /// returns "" (the gallery entry then links its pictures).
  std::string write_page(const std::string& file, InteractivePage page, const std::string& command) const;

 private:
  std::filesystem::path dir_;
  std::set<std::string> only_;
  Progress* progress_;
  Gallery gallery_;
  std::vector<std::string> known_;
  std::set<std::string> matched_;
};

}  // namespace volspline::cli
