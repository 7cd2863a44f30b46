#include "report_document.hpp"

#include <fstream>
#include <sstream>

#include <fmt/format.h>

namespace stickslip::study::detail {

void document::heading(int level, std::string text) {
  blocks_.push_back({doc_block::kind::heading, level, std::move(text), {}, {}, {}, {}});
}
void document::paragraph(std::string text) {
  blocks_.push_back({doc_block::kind::paragraph, 0, std::move(text), {}, {}, {}, {}});
}
void document::table(std::vector<std::vector<std::string>> rows) {
  blocks_.push_back({doc_block::kind::table, 0, {}, std::move(rows), {}, {}, {}});
}
void document::image(std::string title, std::string path, std::string caption) {
  blocks_.push_back(
      {doc_block::kind::image, 0, std::move(title), {}, {}, std::move(path), std::move(caption)});
}
void document::code(std::string text) {
  blocks_.push_back({doc_block::kind::code, 0, std::move(text), {}, {}, {}, {}});
}
void document::list(std::vector<std::string> items) {
  blocks_.push_back({doc_block::kind::list, 0, {}, {}, std::move(items), {}, {}});
}

namespace {

std::string md_cell(const std::string& s) {
  std::string o;
  for (char c : s) {
    if (c == '|') o += "\\|";
    else if (c == '\n') o += ' ';
    else o += c;
  }
  return o;
}

// Inline markup for HTML: `code` and **bold**, everything else escaped.
std::string inline_html(const std::string& s) {
  std::string o;
  bool code = false, bold = false;
  for (std::size_t i = 0; i < s.size(); ++i) {
    if (s[i] == '`') {
      o += code ? "</code>" : "<code>";
      code = !code;
    } else if (!code && s[i] == '*' && i + 1 < s.size() && s[i + 1] == '*') {
      o += bold ? "</strong>" : "<strong>";
      bold = !bold;
      ++i;
    } else {
      o += html_escape(std::string(1, s[i]));
    }
  }
  if (code) o += "</code>";
  if (bold) o += "</strong>";
  return o;
}

}  // namespace

std::string html_escape(const std::string& s) {
  std::string o;
  for (char c : s) {
    switch (c) {
      case '&': o += "&amp;"; break;
      case '<': o += "&lt;"; break;
      case '>': o += "&gt;"; break;
      case '"': o += "&quot;"; break;
      default: o += c;
    }
  }
  return o;
}

std::string base64(const std::string& bytes) {
  static constexpr char table[] =
      "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::string o;
  o.reserve((bytes.size() + 2) / 3 * 4);
  std::size_t i = 0;
  for (; i + 2 < bytes.size(); i += 3) {
    const unsigned v = (static_cast<unsigned char>(bytes[i]) << 16) |
                       (static_cast<unsigned char>(bytes[i + 1]) << 8) |
                       static_cast<unsigned char>(bytes[i + 2]);
    o += table[(v >> 18) & 63];
    o += table[(v >> 12) & 63];
    o += table[(v >> 6) & 63];
    o += table[v & 63];
  }
  if (i < bytes.size()) {
    unsigned v = static_cast<unsigned char>(bytes[i]) << 16;
    if (i + 1 < bytes.size()) v |= static_cast<unsigned char>(bytes[i + 1]) << 8;
    o += table[(v >> 18) & 63];
    o += table[(v >> 12) & 63];
    o += i + 1 < bytes.size() ? table[(v >> 6) & 63] : '=';
    o += '=';
  }
  return o;
}

std::string document::markdown() const {
  std::string o;
  for (const auto& b : blocks_) {
    switch (b.type) {
      case doc_block::kind::heading:
        o += std::string(static_cast<std::size_t>(b.level), '#') + " " + b.text + "\n\n";
        break;
      case doc_block::kind::paragraph: o += b.text + "\n\n"; break;
      case doc_block::kind::code: o += "```\n" + b.text + "\n```\n\n"; break;
      case doc_block::kind::list:
        for (const auto& it : b.items) o += "- " + it + "\n";
        o += "\n";
        break;
      case doc_block::kind::image:
        o += fmt::format("![{}]({})\n\n*{}* {}\n\n", b.text, b.path, b.text, b.caption);
        break;
      case doc_block::kind::table: {
        if (b.rows.empty()) break;
        for (std::size_t r = 0; r < b.rows.size(); ++r) {
          o += "|";
          for (const auto& c : b.rows[r]) {
            o += ' ';
            o += md_cell(c);
            o += " |";
          }
          o += "\n";
          if (r == 0) {
            o += "|";
            for (std::size_t c = 0; c < b.rows[0].size(); ++c) o += "---|";
            o += "\n";
          }
        }
        o += "\n";
        break;
      }
    }
  }
  return o;
}

std::string document::html(const std::string& title, const std::string& base_dir) const {
  std::string o = fmt::format(
      "<!DOCTYPE html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\">\n"
      "<title>{}</title>\n<style>\n"
      "body{{font-family:sans-serif;max-width:1200px;margin:2em auto;padding:0 1em;"
      "line-height:1.45;color:#222}}\n"
      "table{{border-collapse:collapse;margin:1em 0;font-size:0.9em}}\n"
      "th,td{{border:1px solid #bbb;padding:0.3em 0.5em;vertical-align:top}}\n"
      "th{{background:#f0f0f0}}\n"
      "figure{{margin:1.5em 0}} img{{max-width:100%;border:1px solid #ddd}}\n"
      "figcaption{{font-size:0.9em;color:#444}}\n"
      "pre{{background:#f6f6f6;padding:0.6em;overflow-x:auto}}\n"
      "code{{background:#f6f6f6}}\n"
      "</style>\n</head>\n<body>\n",
      html_escape(title));
  for (const auto& b : blocks_) {
    switch (b.type) {
      case doc_block::kind::heading:
        o += fmt::format("<h{0}>{1}</h{0}>\n", b.level, inline_html(b.text));
        break;
      case doc_block::kind::paragraph: o += "<p>" + inline_html(b.text) + "</p>\n"; break;
      case doc_block::kind::code: o += "<pre>" + html_escape(b.text) + "</pre>\n"; break;
      case doc_block::kind::list:
        o += "<ul>\n";
        for (const auto& it : b.items) o += "<li>" + inline_html(it) + "</li>\n";
        o += "</ul>\n";
        break;
      case doc_block::kind::image: {
        std::ifstream in(base_dir + "/" + b.path, std::ios::binary);
        std::ostringstream bytes;
        bytes << in.rdbuf();
        o += "<figure>\n";
        if (in && !bytes.str().empty())
          o += fmt::format("<img alt=\"{}\" src=\"data:image/png;base64,{}\">\n",
                           html_escape(b.text), base64(bytes.str()));
        else
          o += fmt::format("<p><em>(figure not rendered: {})</em></p>\n", html_escape(b.path));
        o += fmt::format("<figcaption><strong>{}</strong> {}</figcaption>\n</figure>\n",
                         inline_html(b.text), inline_html(b.caption));
        break;
      }
      case doc_block::kind::table:
        if (b.rows.empty()) break;
        o += "<table>\n";
        for (std::size_t r = 0; r < b.rows.size(); ++r) {
          o += "<tr>";
          for (const auto& c : b.rows[r])
          {
            o += r == 0 ? "<th>" : "<td>";
            o += inline_html(c);
            o += r == 0 ? "</th>" : "</td>";
          }
          o += "</tr>\n";
        }
        o += "</table>\n";
        break;
    }
  }
  o += "</body>\n</html>\n";
  return o;
}

}  // namespace stickslip::study::detail
