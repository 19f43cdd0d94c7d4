#include "report/common/page.h"

#include <cctype>
#include <cstdio>
#include <stdexcept>

#include "files/atomic_file.h"
#include "scene/history.h"
#include "util/relayed_text.h"

namespace rockbench::report {
namespace {

std::string ReadBytes(const std::filesystem::path& path) {
  std::string bytes = ReadTextFile(path);
  if (bytes.empty()) throw std::runtime_error(path.string() + ": figure is empty");
  return bytes;
}

std::string MimeType(const std::filesystem::path& file) {
  const std::string ext = file.extension().string();
  if (ext == ".svg") return "image/svg+xml";
  if (ext == ".png") return "image/png";
  if (ext == ".gif") return "image/gif";
  if (ext == ".jpg" || ext == ".jpeg") return "image/jpeg";
  if (ext == ".mp4") return "video/mp4";
  if (ext == ".webm") return "video/webm";
  throw std::runtime_error(file.string() + ": unknown figure type (expected .svg, .png, .gif)");
}

// Markdown text: no HTML (a < that could open a tag, comment or declaration as &lt;; "t < 1 s"
// stays as written), line breaks flattened (a heading or list item stays one line: text from a
// file cannot start a block of its own), other control characters shown as \xHH.
std::string MdText(const std::string& text) {
  std::string out;
  for (size_t i = 0; i < text.size(); ++i) {
    const char c = text[i];
    const auto u = static_cast<unsigned char>(c);
    const char next = i + 1 < text.size() ? text[i + 1] : ' ';
    const bool opens_tag =
        std::isalpha(static_cast<unsigned char>(next)) || next == '/' || next == '!' || next == '?';
    if (c == '<' && opens_tag) {
      out += "&lt;";
    } else if (c == '\n' || c == '\r') {
      out += ' ';
    } else if (u < 0x20 || u == 0x7f) {
      AppendHexEscape(out, u);
    } else {
      out += c;
    }
  }
  return out;
}

// Markdown table cells: MdText with pipes escaped.
std::string MdCell(const std::string& text) {
  std::string out;
  for (char c : MdText(text)) {
    if (c == '|') out += '\\';
    out += c;
  }
  return out;
}

// A relative file path as a Markdown link target: bytes other than letters, digits and
// "/._-~" percent-encoded (a space or parenthesis would end the link).
std::string MdUrl(const std::filesystem::path& file) {
  std::string out;
  for (char c : file.generic_string()) {
    const auto u = static_cast<unsigned char>(c);
    if ((c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') || c == '/' ||
        c == '.' || c == '_' || c == '-' || c == '~') {
      out += c;
    } else {
      char buf[8];
      std::snprintf(buf, sizeof buf, "%%%02X", u);
      out += buf;
    }
  }
  return out;
}

constexpr const char* kStyle =
    "body{font-family:'DejaVu Sans',Arial,sans-serif;max-width:1100px;margin:2em auto;"
    "padding:0 1em;color:#111;line-height:1.45}"
    "h1{font-size:1.7em}h2{margin-top:1.8em;border-bottom:1px solid #ccc}"
    "table{border-collapse:collapse;margin:1em 0;font-size:0.92em;display:block;"
    "overflow-x:auto;max-width:100%}"
    "th,td{border:1px solid #bbb;padding:0.25em 0.6em;text-align:left;"
    "overflow-wrap:normal;word-break:normal;hyphens:none}"
    "th{background:#eee}figure{margin:1.2em 0}figure img,figure video{max-width:100%;"
    "border:1px solid #ddd}figcaption{font-size:0.9em;color:#333}"
    ".rb-warnings{border:2px solid #b00;background:#fff4f4;padding:0.6em 1em}"
    ".rb-warnings li{margin:0.3em 0}";

}  // namespace

std::string HtmlEscape(const std::string& text) {
  std::string out;
  out.reserve(text.size());
  for (char c : text) {
    switch (c) {
      case '&':
        out += "&amp;";
        break;
      case '<':
        out += "&lt;";
        break;
      case '>':
        out += "&gt;";
        break;
      case '"':
        out += "&quot;";
        break;
      case '\'':
        out += "&#39;";
        break;
      default:
        out += c;
    }
  }
  return out;
}

std::string Base64(const std::string& bytes) {
  static constexpr char kAlphabet[] =
      "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::string out;
  out.reserve((bytes.size() + 2) / 3 * 4);
  size_t i = 0;
  for (; i + 2 < bytes.size(); i += 3) {
    const unsigned v = (static_cast<unsigned char>(bytes[i]) << 16) |
                       (static_cast<unsigned char>(bytes[i + 1]) << 8) |
                       static_cast<unsigned char>(bytes[i + 2]);
    out += kAlphabet[(v >> 18) & 63];
    out += kAlphabet[(v >> 12) & 63];
    out += kAlphabet[(v >> 6) & 63];
    out += kAlphabet[v & 63];
  }
  if (i + 1 == bytes.size()) {
    const unsigned v = static_cast<unsigned char>(bytes[i]) << 16;
    out += kAlphabet[(v >> 18) & 63];
    out += kAlphabet[(v >> 12) & 63];
    out += "==";
  } else if (i + 2 == bytes.size()) {
    const unsigned v = (static_cast<unsigned char>(bytes[i]) << 16) |
                       (static_cast<unsigned char>(bytes[i + 1]) << 8);
    out += kAlphabet[(v >> 18) & 63];
    out += kAlphabet[(v >> 12) & 63];
    out += kAlphabet[(v >> 6) & 63];
    out += '=';
  }
  return out;
}

Page::Page(std::string title) : title_(std::move(title)) {}

void Page::Warning(std::string text) {
  warnings_.push_back(std::move(text));
}

void Page::Heading(std::string text, int level) {
  if (level != 2 && level != 3) throw std::invalid_argument("Page::Heading: level must be 2 or 3");
  blocks_.push_back({level == 2 ? Kind::kHeading2 : Kind::kHeading3, std::move(text), {}, {}, {}});
}

void Page::Paragraph(std::string text) {
  blocks_.push_back({Kind::kParagraph, std::move(text), {}, {}, {}});
}

void Page::Table(std::vector<std::string> header, std::vector<std::vector<std::string>> rows) {
  for (const auto& row : rows) {
    if (row.size() != header.size()) {
      throw std::invalid_argument("Page::Table: a row has " + std::to_string(row.size()) +
                                  " cells, the header " + std::to_string(header.size()));
    }
  }
  blocks_.push_back({Kind::kTable, {}, {}, std::move(header), std::move(rows)});
}

void Page::Figure(std::filesystem::path file, std::string caption) {
  MimeType(file);  // rejects unknown types early
  blocks_.push_back({Kind::kFigure, std::move(caption), std::move(file), {}, {}});
}

void Page::Video(std::filesystem::path file, std::string caption) {
  blocks_.push_back({Kind::kVideo, std::move(caption), std::move(file), {}, {}});
}

void Page::Link(std::filesystem::path file, std::string text) {
  blocks_.push_back({Kind::kLink, std::move(text), std::move(file), {}, {}});
}

void Page::Append(const Page& other) {
  warnings_.insert(warnings_.end(), other.warnings_.begin(), other.warnings_.end());
  blocks_.insert(blocks_.end(), other.blocks_.begin(), other.blocks_.end());
}

std::vector<std::filesystem::path> Page::figures() const {
  std::vector<std::filesystem::path> out;
  for (const Block& b : blocks_) {
    if (b.kind == Kind::kFigure) out.push_back(b.file);
  }
  return out;
}

std::string Page::Html(const std::filesystem::path& page_dir) const {
  std::string h = "<!DOCTYPE html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\">\n<title>" +
                  HtmlEscape(title_) + "</title>\n<style>" + kStyle +
                  "</style>\n</head>\n<body>\n<h1>" + HtmlEscape(title_) + "</h1>\n";
  if (!warnings_.empty()) {
    h += "<div class=\"rb-warnings\"><strong>Validity warnings</strong>\n<ul>\n";
    for (const std::string& w : warnings_) h += "<li>" + HtmlEscape(w) + "</li>\n";
    h += "</ul></div>\n";
  }
  int figure_index = 0;
  for (const Block& b : blocks_) {
    switch (b.kind) {
      case Kind::kHeading2:
        h += "<h2>" + HtmlEscape(b.text) + "</h2>\n";
        break;
      case Kind::kHeading3:
        h += "<h3>" + HtmlEscape(b.text) + "</h3>\n";
        break;
      case Kind::kParagraph:
        h += "<p>" + HtmlEscape(b.text) + "</p>\n";
        break;
      case Kind::kTable: {
        h += "<table>\n<tr>";
        for (const std::string& c : b.header) h += "<th>" + HtmlEscape(c) + "</th>";
        h += "</tr>\n";
        for (const auto& row : b.rows) {
          h += "<tr>";
          for (const std::string& c : row) h += "<td>" + HtmlEscape(c) + "</td>";
          h += "</tr>\n";
        }
        h += "</table>\n";
        break;
      }
      case Kind::kFigure: {
        const std::string data = Base64(ReadBytes(page_dir / b.file));
        h += "<figure id=\"figure-" + std::to_string(++figure_index) +
             "\"><img class=\"rb-figure\" alt=\"" + HtmlEscape(b.text) +
             "\" src=\"data:" + MimeType(b.file) + ";base64," + data + "\"><figcaption>" +
             HtmlEscape(b.text) + "</figcaption></figure>\n";
        break;
      }
      case Kind::kVideo:
        h += "<figure><video class=\"rb-video\" controls loop muted src=\"" +
             HtmlEscape(b.file.generic_string()) + "\"></video><figcaption>" + HtmlEscape(b.text) +
             " (file: " + HtmlEscape(b.file.generic_string()) + ")</figcaption></figure>\n";
        break;
      case Kind::kLink:
        h += "<p><a href=\"" + HtmlEscape(b.file.generic_string()) + "\">" + HtmlEscape(b.text) +
             "</a></p>\n";
        break;
    }
  }
  return h + "</body>\n</html>\n";
}

std::string Page::Markdown() const {
  std::string m = "# " + MdText(title_) + "\n\n";
  if (!warnings_.empty()) {
    m += "> **Validity warnings**\n>\n";
    for (const std::string& w : warnings_) m += "> - " + MdText(w) + "\n";
    m += "\n";
  }
  for (const Block& b : blocks_) {
    switch (b.kind) {
      case Kind::kHeading2:
        m += "## " + MdText(b.text) + "\n\n";
        break;
      case Kind::kHeading3:
        m += "### " + MdText(b.text) + "\n\n";
        break;
      case Kind::kParagraph:
        m += MdText(b.text) + "\n\n";
        break;
      case Kind::kTable: {
        m += "|";
        for (const std::string& c : b.header) m.append(" ").append(MdCell(c)).append(" |");
        m += "\n|";
        for (size_t i = 0; i < b.header.size(); ++i) m += "---|";
        m += "\n";
        for (const auto& row : b.rows) {
          m += "|";
          for (const std::string& c : row) m.append(" ").append(MdCell(c)).append(" |");
          m += "\n";
        }
        m += "\n";
        break;
      }
      case Kind::kFigure:
        m += "![" + MdCell(b.text) + "](" + MdUrl(b.file) + ")\n\n*" + MdText(b.text) + "*\n\n";
        break;
      case Kind::kVideo:
        m += "[" + MdCell(b.text) + "](" + MdUrl(b.file) + ")\n\n";
        break;
      case Kind::kLink:
        m += "[" + MdCell(b.text) + "](" + MdUrl(b.file) + ")\n\n";
        break;
    }
  }
  return m;
}

}  // namespace rockbench::report
