#pragma once
/// A report page, built once and written twice: as one self-contained HTML file (figures and
/// pictures embedded as data: URIs, so it opens offline from anywhere; only a video stays a file
/// beside it) and as its Markdown twin for repositories (figures and pictures as files beside
/// it). Every block keeps its order; warnings always come first.
#include <filesystem>
#include <string>
#include <vector>

namespace rockbench::report {

class Page {
 public:
  explicit Page(std::string title);

  /// A validity warning in plain words; all warnings are shown at the top of the page.
  void Warning(std::string text);
  /// A section heading, level 2 (section) or 3 (subsection).
  void Heading(std::string text, int level = 2);
  /// A paragraph of plain text (escaped; no markup).
  void Paragraph(std::string text);
  /// A table; every row has the header's number of cells.
  void Table(std::vector<std::string> header, std::vector<std::vector<std::string>> rows);
  /// A figure (SVG or PNG) at `file`, relative to the page's folder, with its caption.
  void Figure(std::filesystem::path file, std::string caption);
  /// A video (MP4/WebM/GIF) at `file`, relative to the page's folder: beside the HTML, not in it.
  void Video(std::filesystem::path file, std::string caption);
  /// A link to another file (relative to the page's folder) with its text.
  void Link(std::filesystem::path file, std::string text);

  /// Every block (and warning) of `other`, after this page's own (sections built before the
  /// summary that must come above them).
  void Append(const Page& other);

  const std::string& title() const { return title_; }
  /// Figures in the order they were added (relative paths).
  std::vector<std::filesystem::path> figures() const;

  /// The HTML page. Reads the figures from `page_dir` to embed them; throws std::runtime_error
  /// naming a figure that is missing or empty. Every figure is an <img class="rb-figure"> inside
  /// a <figure>, so tests and browsers can count them.
  std::string Html(const std::filesystem::path& page_dir) const;
  /// The Markdown twin (GitHub-flavoured: pipe tables, images by relative path).
  std::string Markdown() const;

 private:
  enum class Kind { kHeading2, kHeading3, kParagraph, kTable, kFigure, kVideo, kLink };
  struct Block {
    Kind kind;
    std::string text;
    std::filesystem::path file;
    std::vector<std::string> header;
    std::vector<std::vector<std::string>> rows;
  };
  std::string title_;
  std::vector<std::string> warnings_;
  std::vector<Block> blocks_;
};

/// Escapes &, <, >, " and ' for HTML text and attributes.
std::string HtmlEscape(const std::string& text);
/// Standard base64 (RFC 4648, with padding).
std::string Base64(const std::string& bytes);

}  // namespace rockbench::report
